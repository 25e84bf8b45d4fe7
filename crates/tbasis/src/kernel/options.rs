//! Everything a call is told besides the mesh and the output, and the checks the types cannot
//! make.
#![forbid(unsafe_code)]

pub use crate::kernel::choices::{DegeneratePolicy, Method, DEFAULT_DEGENERATE_THRESHOLD};
use crate::kernel::error::Error;

/// Everything a call can be told besides the mesh and the output: [`Options::default`], then the
/// `with_*` builders.
///
/// ```
/// use tbasis::{DegeneratePolicy, Method, Options};
/// let options = Options::default().with_method(Method::Area).with_policy(DegeneratePolicy::Skip).with_threads(4);
/// assert_eq!(options.method, Method::Area);
/// assert_eq!(Options::mikktspace().with_flip_v(true).degenerate_policy, DegeneratePolicy::Legacy);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Options {
    /// How per-triangle tangents are combined.
    pub method: Method,
    /// What happens to degenerate triangles.
    pub degenerate_policy: DegeneratePolicy,
    /// Texture coordinates have V pointing down (glTF, Direct3D): the tangent frame is computed as
    /// for `v' = 1 - v`, which turns the handedness `w` so that `bitangent = w * cross(n, t)`
    /// points towards increasing V as the file stores it upside down.
    pub flip_v: bool,
    /// Quality below which a triangle counts as degenerate (see [`DEFAULT_DEGENERATE_THRESHOLD`]).
    pub degenerate_threshold: f32,
    /// Upper bound on worker threads; 0 and 1 both mean the calling thread only.
    pub threads: u32,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            method: Method::DEFAULT,
            degenerate_policy: DegeneratePolicy::DEFAULT,
            flip_v: false,
            degenerate_threshold: DEFAULT_DEGENERATE_THRESHOLD,
            threads: 0,
        }
    }
}

impl Options {
    /// The listing, exactly: method LENGYEL with policy LEGACY.
    ///
    /// ```
    /// use tbasis::{generate, Mesh, Options, Output};
    ///
    /// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
    /// # let normals = [[0.0, 0.0, 1.0f32]; 3];
    /// // The listing divides by the UV determinant, zero here: it writes what that gives.
    /// let mesh = Mesh::new(&positions, &normals).with_texcoords(&[[0.5, 0.5]; 3]);
    /// let mut tangents = [[0.0f32; 4]; 3];
    /// generate(&mesh, &Options::legacy(), &mut Output::new(&mut tangents))?;
    /// assert!(tangents[0].iter().any(|x| !x.is_finite()));
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn legacy() -> Self {
        Options {
            method: Method::Lengyel,
            degenerate_policy: DegeneratePolicy::Legacy,
            ..Options::default()
        }
    }

    /// mikktspace.c's tangents, bit for bit: method MIKKTSPACE with policy LEGACY.
    ///
    /// ```
    /// use tbasis::{generate, DegeneratePolicy, Error, Mesh, Method, Options, Output};
    ///
    /// // mikktspace.c needs texture coordinates.
    /// let mesh = Mesh::new(&[[0.0f32; 3]; 3], &[[0.0, 0.0, 1.0f32]; 3]);
    /// let mut tangents = [[0.0f32; 4]; 3];
    /// let error = generate(&mesh, &Options::mikktspace(), &mut Output::new(&mut tangents)).unwrap_err();
    /// assert_eq!(error, Error::MissingTexcoords { method: Method::Mikktspace, policy: DegeneratePolicy::Legacy });
    /// ```
    pub fn mikktspace() -> Self {
        Options {
            method: Method::Mikktspace,
            degenerate_policy: DegeneratePolicy::Legacy,
            ..Options::default()
        }
    }

    /// With `method`. The policy stays as it is: policy LEGACY holds only with the methods that
    /// have a legacy form, LENGYEL and MIKKTSPACE ([`Options::validate`]).
    ///
    /// ```
    /// use tbasis::{DegeneratePolicy, Error, Method, Options};
    ///
    /// let options = Options::default().with_method(Method::Area);
    /// assert_eq!(options.method, Method::Area);
    /// let legacy = Options::legacy().with_method(Method::Area);
    /// assert_eq!(legacy.validate(), Err(Error::NoLegacyForm { method: Method::Area }));
    /// assert_eq!(legacy.with_policy(DegeneratePolicy::Skip).validate(), Ok(()));
    /// ```
    pub fn with_method(self, method: Method) -> Self {
        Options { method, ..self }
    }

    /// With `policy` for degenerate triangles.
    ///
    /// ```
    /// use tbasis::{generate, DegeneratePolicy, Mesh, Options, Output};
    ///
    /// let mesh = Mesh::new(&[[0.0f32; 3]; 3], &[[0.0, 0.0, 1.0f32]; 3]); // no texture coordinates
    /// let mut tangents = [[0.0f32; 4]; 3];
    /// let mut output = Output::new(&mut tangents);
    /// assert!(generate(&mesh, &Options::legacy(), &mut output).is_err());
    /// let skip = Options::legacy().with_policy(DegeneratePolicy::Skip);
    /// assert_eq!(generate(&mesh, &skip, &mut output)?.fallback_vertices, 3);
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn with_policy(self, policy: DegeneratePolicy) -> Self {
        Options {
            degenerate_policy: policy,
            ..self
        }
    }

    /// With V pointing down (glTF, Direct3D): see [`Options::flip_v`].
    ///
    /// ```
    /// use tbasis::{generate, Mesh, Options, Output};
    ///
    /// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
    /// # let normals = [[0.0, 0.0, 1.0f32]; 3];
    /// # let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    /// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords);
    /// let mut tangents = [[0.0f32; 4]; 3];
    /// generate(&mesh, &Options::default().with_flip_v(true), &mut Output::new(&mut tangents))?;
    /// assert_eq!(tangents[0], [1.0, 0.0, 0.0, -1.0]); // the handedness turns
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn with_flip_v(self, flip_v: bool) -> Self {
        Options { flip_v, ..self }
    }

    /// With at most `threads` worker threads (0 and 1: the calling thread only).
    ///
    /// ```
    /// use tbasis::{generate, Mesh, Options, Output};
    ///
    /// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
    /// # let normals = [[0.0, 0.0, 1.0f32]; 3];
    /// # let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    /// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords);
    /// let (mut one, mut four) = ([[0.0f32; 4]; 3], [[0.0f32; 4]; 3]);
    /// generate(&mesh, &Options::default().with_threads(1), &mut Output::new(&mut one))?;
    /// generate(&mesh, &Options::default().with_threads(4), &mut Output::new(&mut four))?;
    /// assert_eq!(one, four);
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn with_threads(self, threads: u32) -> Self {
        Options { threads, ..self }
    }

    /// With `threshold` as the quality below which a triangle is degenerate.
    ///
    /// ```
    /// use tbasis::{generate, Mesh, Options, Output};
    ///
    /// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
    /// # let normals = [[0.0, 0.0, 1.0f32]; 3];
    /// // A sliver in UV space, of quality q = 2*sqrt(3) * 1e-6 / 1.5, about 2.3e-6.
    /// let sliver = [[0.0, 0.0], [1.0, 0.0], [0.5, 1e-6]];
    /// let mesh = Mesh::new(&positions, &normals).with_texcoords(&sliver);
    /// let mut tangents = [[0.0f32; 4]; 3];
    /// let options = Options::default().with_degenerate_threshold(1e-7);
    /// assert_eq!(generate(&mesh, &options, &mut Output::new(&mut tangents))?.degenerate_triangles, 0);
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn with_degenerate_threshold(self, threshold: f32) -> Self {
        Options {
            degenerate_threshold: threshold,
            ..self
        }
    }

    /// Checks what the types cannot: the threshold is finite and not negative, and policy LEGACY
    /// comes with a method that has a legacy form (LENGYEL: the listing; MIKKTSPACE: mikktspace.c).
    ///
    /// ```
    /// use tbasis::{Error, Method, Options};
    ///
    /// assert_eq!(Options::default().validate(), Ok(()));
    /// let nan = Options::default().with_degenerate_threshold(f32::NAN);
    /// assert!(matches!(nan.validate(), Err(Error::InvalidThreshold { .. })));
    /// let angle = Options::legacy().with_method(Method::Angle);
    /// assert_eq!(angle.validate(), Err(Error::NoLegacyForm { method: Method::Angle }));
    /// ```
    pub fn validate(&self) -> Result<(), Error> {
        if !self.degenerate_threshold.is_finite() || self.degenerate_threshold < 0.0 {
            return Err(Error::InvalidThreshold {
                threshold: self.degenerate_threshold,
            });
        }
        if self.degenerate_policy == DegeneratePolicy::Legacy && !self.method.has_legacy_form() {
            return Err(Error::NoLegacyForm { method: self.method });
        }
        Ok(())
    }
}
