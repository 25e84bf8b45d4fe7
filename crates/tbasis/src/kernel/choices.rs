//! What the caller chooses: the method, the degenerate-UV policy, and the threshold's default.
#![forbid(unsafe_code)]

/// How per-triangle tangents are combined at a vertex.
///
/// ```
/// use tbasis::{generate, Mesh, Method, Options, Output};
///
/// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
/// # let normals = [[0.0, 0.0, 1.0f32]; 3];
/// # let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
/// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords);
/// for method in [Method::Lengyel, Method::Angle, Method::Area, Method::Uniform, Method::Mikktspace] {
///     let mut tangents = [[0.0f32; 4]; 3];
///     generate(&mesh, &Options::default().with_method(method), &mut Output::new(&mut tangents))?;
///     assert_eq!(tangents[0], [1.0, 0.0, 0.0, 1.0], "{method:?}");
/// }
/// # Ok::<(), tbasis::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Method {
    /// The original listing: each triangle adds its unnormalized dP/du and dP/dv (Lengyel 2001).
    Lengyel,
    /// Each triangle's tangent, projected into the vertex's tangent plane and normalized, weighted
    /// by the triangle's corner angle at the vertex measured in that plane, each term in
    /// mikktspace.c's arithmetic (`EvalTspace`), with or without [`Options::flip_v`](crate::Options::flip_v): on a clean
    /// mesh, exactly mikktspace.c's frame for the vertex's first corner (README, "Methods", states
    /// where exactly). Elsewhere the scale-free robust arithmetic and the vertex's own sums decide.
    Angle,
    /// Unit face tangents weighted by triangle area.
    Area,
    /// Unit face tangents with equal weights (per-face averaging).
    Uniform,
    /// Exactly what mikktspace.c's `genTangSpaceDefault` gives, float for float, per corner: the
    /// tangents almost every normal map is baked against. Its default policy is `Legacy`.
    Mikktspace,
}

impl Method {
    /// The method used when the caller asks for the default (`0` in C): ANGLE, which gives
    /// mikktspace.c's per-vertex frames bit for bit on 33 of the 35 analytic scenes of
    /// `docs/accuracy.md` (on the other two, with noisy texture coordinates, 4 vertices of 10,396
    /// differ and the default's mean error is the lower), and
    /// whose mean error is about half the listing's.
    ///
    /// ```
    /// use tbasis::{Method, Options};
    ///
    /// assert_eq!(Method::DEFAULT, Method::Angle);
    /// assert_eq!(Options::default().method, Method::DEFAULT);
    /// ```
    pub const DEFAULT: Method = Method::Angle;

    /// Whether policy [`DegeneratePolicy::Legacy`] holds with this method: LENGYEL (the listing)
    /// and MIKKTSPACE (mikktspace.c) have a legacy form to reproduce; the others do not.
    ///
    /// ```
    /// use tbasis::Method;
    ///
    /// assert!(Method::Lengyel.has_legacy_form() && Method::Mikktspace.has_legacy_form());
    /// assert!(!Method::Angle.has_legacy_form());
    /// ```
    pub fn has_legacy_form(self) -> bool {
        matches!(self, Method::Lengyel | Method::Mikktspace)
    }
}

/// What happens to triangles whose texture coordinates (or inputs) are degenerate.
///
/// ```
/// use tbasis::{generate, DegeneratePolicy, Error, Mesh, Options, Output};
///
/// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
/// # let normals = [[0.0, 0.0, 1.0f32]; 3];
/// let collapsed = [[0.5, 0.5f32]; 3]; // every corner at the same UV
/// let mesh = Mesh::new(&positions, &normals).with_texcoords(&collapsed);
/// let mut tangents = [[0.0f32; 4]; 3];
/// let skip = Options::default().with_policy(DegeneratePolicy::Skip);
/// let report = generate(&mesh, &skip, &mut Output::new(&mut tangents))?;
/// assert_eq!(report.fallback_vertices, 3);
///
/// let reject = Options::default().with_policy(DegeneratePolicy::Reject);
/// let error = generate(&mesh, &reject, &mut Output::new(&mut tangents)).unwrap_err();
/// assert!(matches!(error, Error::DegenerateUv { triangle: 0, .. }));
/// # Ok::<(), tbasis::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum DegeneratePolicy {
    /// Exactly the listing (method LENGYEL) or mikktspace.c (method MIKKTSPACE), bit for bit,
    /// including the inf/NaN the listing writes on a zero UV determinant. The other methods have
    /// no legacy form: with them this policy is refused ([`Error::NoLegacyForm`](crate::Error::NoLegacyForm)).
    Legacy,
    /// Degenerate triangles contribute nothing; a vertex left without a tangent gets a fallback
    /// frame built from its normal.
    Skip,
    /// Like `Skip`, but a vertex left without a tangent first takes one from its neighbours across
    /// shared triangles, and falls back only when its whole connected region has none.
    Inherit,
    /// Refuse the mesh with [`Error::DegenerateUv`](crate::Error::DegenerateUv), naming the first degenerate triangle.
    Reject,
}

impl DegeneratePolicy {
    /// The policy used when the caller asks for the default (`0` in C).
    ///
    /// ```
    /// use tbasis::{DegeneratePolicy, Options};
    ///
    /// assert_eq!(DegeneratePolicy::DEFAULT, DegeneratePolicy::Inherit);
    /// assert_eq!(Options::default().degenerate_policy, DegeneratePolicy::DEFAULT);
    /// ```
    pub const DEFAULT: DegeneratePolicy = DegeneratePolicy::Inherit;

    /// The policy `0` stands for with `method`: `Legacy` for [`Method::Mikktspace`] (exactly
    /// mikktspace.c), [`DegeneratePolicy::DEFAULT`] for the others.
    ///
    /// ```
    /// use tbasis::{DegeneratePolicy, Method};
    ///
    /// assert_eq!(DegeneratePolicy::default_for(Method::Mikktspace), DegeneratePolicy::Legacy);
    /// assert_eq!(DegeneratePolicy::default_for(Method::Area), DegeneratePolicy::DEFAULT);
    /// ```
    pub fn default_for(method: Method) -> DegeneratePolicy {
        match method {
            Method::Mikktspace => DegeneratePolicy::Legacy,
            _ => DegeneratePolicy::DEFAULT,
        }
    }
}

/// The default for [`Options::degenerate_threshold`](crate::Options::degenerate_threshold).
///
/// A triangle's UV quality `q = 2*sqrt(3)*|det| / (|e0|^2 + |e1|^2 + |e2|^2)` is 1 for an
/// equilateral triangle, about 0.87 for a grid's right triangle, and falls like `sqrt(3)/k` for a
/// sliver of aspect ratio `k`. Below 1e-5 (aspect ratios beyond ~170 000:1) the UV edges that define
/// the tangent differ by less than a float's relative precision of the coordinates they come from,
/// so the solved tangent is rounding noise.
///
/// ```
/// use tbasis::{generate, Mesh, Options, Output, DEFAULT_DEGENERATE_THRESHOLD};
///
/// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
/// # let normals = [[0.0, 0.0, 1.0f32]; 3];
/// // A sliver in UV space, of quality q = 2*sqrt(3) * 1e-6 / 1.5, about 2.3e-6.
/// let sliver = [[0.0, 0.0], [1.0, 0.0], [0.5, 1e-6]];
/// let mesh = Mesh::new(&positions, &normals).with_texcoords(&sliver);
/// let mut tangents = [[0.0f32; 4]; 3];
/// let options = Options::default();
/// assert_eq!(options.degenerate_threshold, DEFAULT_DEGENERATE_THRESHOLD);
/// assert_eq!(generate(&mesh, &options, &mut Output::new(&mut tangents))?.degenerate_triangles, 1);
/// # Ok::<(), tbasis::Error>(())
/// ```
pub const DEFAULT_DEGENERATE_THRESHOLD: f32 = 1e-5;
