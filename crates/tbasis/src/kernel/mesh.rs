//! The caller's mesh and output, as views over memory the library reads or writes in place.
#![forbid(unsafe_code)]

use crate::kernel::error::Error;
use crate::kernel::views::strided::{Element, Footprint, Strided, StridedMut};

/// The index buffer: three indices per triangle, or none (triangle `i` is vertices `3i..3i+3`).
///
/// ```
/// use tbasis::{Indices, Strided};
///
/// let quad = [0u16, 1, 2, 0, 2, 3];
/// let indices = Indices::U16(Strided::from_slice(&quad)); // or Indices::from(&quad)
/// assert_eq!(indices.triangle(1), [0, 2, 3]);
/// assert_eq!(Indices::None.triangle(1), [3, 4, 5]);
/// ```
#[derive(Clone, Copy)]
pub enum Indices<'a> {
    /// Unindexed: the vertex count must be a multiple of 3.
    None,
    /// 16-bit indices.
    U16(Strided<'a, u16>),
    /// 32-bit indices.
    U32(Strided<'a, u32>),
}

impl<'a> Indices<'a> {
    /// Number of triangles, given the vertex count (used when unindexed).
    ///
    /// ```
    /// use tbasis::{Error, Indices};
    ///
    /// assert_eq!(Indices::from(&[0u32, 1, 2, 2, 1, 3]).triangle_count(4), Ok(2));
    /// assert_eq!(Indices::None.triangle_count(7), Err(Error::InvalidIndexCount { count: 7 }));
    /// ```
    pub fn triangle_count(&self, vertex_count: usize) -> Result<usize, Error> {
        let index_count = self.corner_count(vertex_count);
        if index_count % 3 != 0 {
            return Err(Error::InvalidIndexCount { count: index_count });
        }
        Ok(index_count / 3)
    }

    /// Number of corners: the index count, or `vertex_count` when unindexed.
    ///
    /// ```
    /// use tbasis::Indices;
    ///
    /// assert_eq!(Indices::from(&[0u16, 1, 2, 0, 2, 3]).corner_count(4), 6);
    /// assert_eq!(Indices::None.corner_count(4), 4);
    /// ```
    pub fn corner_count(&self, vertex_count: usize) -> usize {
        match self {
            Indices::None => vertex_count,
            Indices::U16(view) => view.len(),
            Indices::U32(view) => view.len(),
        }
    }

    /// The vertex of corner `c` (callers keep `c` below `corner_count`).
    ///
    /// ```
    /// use tbasis::Indices;
    ///
    /// let indices = Indices::from(&[0u16, 1, 2, 0, 2, 3]);
    /// assert_eq!(indices.corner(5), 3);
    /// assert_eq!(Indices::None.corner(5), 5);
    /// ```
    #[inline(always)]
    pub fn corner(&self, c: usize) -> usize {
        match self {
            Indices::None => c,
            Indices::U16(view) => view.get(c) as usize,
            Indices::U32(view) => view.get(c) as usize,
        }
    }

    /// The vertices of triangle `t` (callers keep `t` below `triangle_count`).
    ///
    /// ```
    /// use tbasis::Indices;
    ///
    /// let indices = Indices::from(&[0u32, 1, 2, 0, 2, 3]);
    /// let triangles: Vec<[usize; 3]> = (0..indices.triangle_count(4)?).map(|t| indices.triangle(t)).collect();
    /// assert_eq!(triangles, [[0, 1, 2], [0, 2, 3]]);
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    #[inline(always)]
    pub fn triangle(&self, t: usize) -> [usize; 3] {
        match self {
            Indices::None => unindexed_corners(t),
            Indices::U16(view) => indexed_corners(*view, t),
            Indices::U32(view) => indexed_corners(*view, t),
        }
    }

    /// Runs `job` with the reader of triangle corners for this index type, so that a loop over
    /// the triangles inside it decides the index type once, not per triangle.
    #[inline(always)]
    pub(crate) fn with_corner_reader<J: PerIndexType>(&self, job: J) -> J::Output {
        match *self {
            Indices::None => job.run(unindexed_corners),
            Indices::U16(view) => job.run(move |t| indexed_corners(view, t)),
            Indices::U32(view) => job.run(move |t| indexed_corners(view, t)),
        }
    }

    /// Asks the CPU to bring triangle `t`'s indices into its cache ahead of a read (a hint, for
    /// loops that read indices faster than memory streams them unasked).
    #[inline(always)]
    pub(crate) fn prefetch_triangle(&self, t: usize) {
        match self {
            Indices::None => {}
            Indices::U16(view) => view.prefetch(3 * t),
            Indices::U32(view) => view.prefetch(3 * t),
        }
    }

    /// Where the index bytes are, if there are any.
    ///
    /// ```
    /// use tbasis::Indices;
    ///
    /// let quad = [0u32, 1, 2, 0, 2, 3];
    /// let footprint = Indices::from(&quad).footprint().unwrap();
    /// assert_eq!((footprint.start, footprint.stride, footprint.count), (quad.as_ptr() as usize, 4, 6));
    /// assert!(Indices::None.footprint().is_none());
    /// ```
    pub fn footprint(&self) -> Option<Footprint> {
        match self {
            Indices::None => None,
            Indices::U16(view) => Some(view.footprint()),
            Indices::U32(view) => Some(view.footprint()),
        }
    }
}

impl<'a> From<&'a [u16]> for Indices<'a> {
    fn from(indices: &'a [u16]) -> Self {
        Indices::U16(Strided::from_slice(indices))
    }
}

impl<'a> From<&'a [u32]> for Indices<'a> {
    fn from(indices: &'a [u32]) -> Self {
        Indices::U32(Strided::from_slice(indices))
    }
}

impl<'a, const N: usize> From<&'a [u16; N]> for Indices<'a> {
    fn from(indices: &'a [u16; N]) -> Self {
        Indices::U16(Strided::from_slice(indices))
    }
}

impl<'a, const N: usize> From<&'a [u32; N]> for Indices<'a> {
    fn from(indices: &'a [u32; N]) -> Self {
        Indices::U32(Strided::from_slice(indices))
    }
}

/// Work compiled once per index type (see [`Indices::with_corner_reader`]).
pub(crate) trait PerIndexType {
    /// What the work returns.
    type Output;
    /// Does the work, reading triangle `t`'s vertices with `corners(t)`.
    fn run(self, corners: impl Fn(usize) -> [usize; 3]) -> Self::Output;
}

#[inline(always)]
fn unindexed_corners(t: usize) -> [usize; 3] {
    [3 * t, 3 * t + 1, 3 * t + 2]
}

#[inline(always)]
fn indexed_corners<T: Element + Into<u32>>(view: Strided<T>, t: usize) -> [usize; 3] {
    let [a, b, c] = view.get_three([3 * t, 3 * t + 1, 3 * t + 2]);
    [a.into() as usize, b.into() as usize, c.into() as usize]
}

/// A triangle mesh: per-vertex attributes as strided views, and its triangles.
///
/// ```
/// use tbasis::{Mesh, Strided};
///
/// // Position and normal interleaved, 24 bytes per vertex.
/// let floats = [[0.0f32, 0.0, 0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 0.0, 0.0, 1.0]];
/// let bytes: Vec<u8> = floats.iter().flatten().flat_map(|f| f.to_ne_bytes()).collect();
/// let mesh = Mesh::new(Strided::from_bytes(&bytes, 24, 3)?, Strided::from_bytes(&bytes[12..], 24, 3)?);
/// assert_eq!(mesh.positions.get(1), [1.0, 0.0, 0.0]);
/// assert_eq!(mesh.normals.get(2), [0.0, 0.0, 1.0]);
/// # Ok::<(), tbasis::Error>(())
/// ```
#[derive(Clone, Copy)]
pub struct Mesh<'a> {
    /// Positions (x, y, z).
    pub positions: Strided<'a, [f32; 3]>,
    /// Normals (x, y, z), expected unit length.
    pub normals: Strided<'a, [f32; 3]>,
    /// Texture coordinates (u, v); `None` gives every vertex the fallback frame.
    pub texcoords: Option<Strided<'a, [f32; 2]>>,
    /// The triangles.
    pub indices: Indices<'a>,
}

impl<'a> Mesh<'a> {
    /// An unindexed mesh without texture coordinates; add them with [`Mesh::with_texcoords`] and
    /// [`Mesh::with_indices`]. Takes slices of `[f32; 3]`, glam `Vec3` or `Vec3A`, or [`Strided`]
    /// views into interleaved vertices.
    ///
    /// ```
    /// use glam::{Vec2, Vec3};
    /// let positions = [Vec3::ZERO, Vec3::X, Vec3::Y];
    /// let normals = [Vec3::Z; 3];
    /// let texcoords = [Vec2::ZERO, Vec2::X, Vec2::Y];
    /// let mesh = tbasis::Mesh::new(&positions[..], &normals[..]).with_texcoords(&texcoords[..]).with_indices(&[0u16, 1, 2]);
    /// assert_eq!((mesh.vertex_count(), mesh.corner_count()), (3, 3));
    /// ```
    pub fn new(positions: impl Into<Strided<'a, [f32; 3]>>, normals: impl Into<Strided<'a, [f32; 3]>>) -> Self {
        Mesh {
            positions: positions.into(),
            normals: normals.into(),
            texcoords: None,
            indices: Indices::None,
        }
    }

    /// With texture coordinates (`[f32; 2]`, glam `Vec2`, or a [`Strided`] view).
    ///
    /// ```
    /// use tbasis::{generate, Mesh, Options, Output};
    ///
    /// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
    /// # let normals = [[0.0, 0.0, 1.0f32]; 3];
    /// // u along +y and v along +x: a mirrored mapping, so w = -1.
    /// let texcoords = [[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]];
    /// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords);
    /// let mut tangents = [[0.0f32; 4]; 3];
    /// generate(&mesh, &Options::default(), &mut Output::new(&mut tangents))?;
    /// assert_eq!(tangents[0], [0.0, 1.0, 0.0, -1.0]);
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn with_texcoords(self, texcoords: impl Into<Strided<'a, [f32; 2]>>) -> Self {
        Mesh {
            texcoords: Some(texcoords.into()),
            ..self
        }
    }

    /// With an index buffer (`&[u16]`, `&[u32]`, or [`Indices`]).
    ///
    /// ```
    /// let mesh = tbasis::Mesh::new(&[[0.0f32; 3]; 4], &[[0.0, 0.0, 1.0f32]; 4]);
    /// assert_eq!(mesh.corner_count(), 4); // unindexed: one corner per vertex
    /// let quad = mesh.with_indices(&[0u32, 1, 2, 0, 2, 3]);
    /// assert_eq!(quad.corner_count(), 6);
    /// ```
    pub fn with_indices(self, indices: impl Into<Indices<'a>>) -> Self {
        Mesh {
            indices: indices.into(),
            ..self
        }
    }

    /// Number of vertices (the positions' length; the other attributes must match it).
    ///
    /// ```
    /// use tbasis::{generate, Mesh, Options, Output};
    ///
    /// let mesh = Mesh::new(&[[0.0f32; 3]; 6], &[[0.0, 0.0, 1.0f32]; 6]);
    /// let mut tangents = vec![[0.0f32; 4]; mesh.vertex_count()];
    /// generate(&mesh, &Options::default(), &mut Output::new(&mut tangents[..]))?;
    /// assert_eq!(tangents.len(), 6);
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangle corners: the index count, or the vertex count when unindexed. The
    /// per-corner output has this many elements, corner `3t + k` being corner `k` of triangle `t`.
    ///
    /// ```
    /// use tbasis::{generate_corners, Mesh, Options, StridedMut};
    ///
    /// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0f32]];
    /// # let normals = [[0.0, 0.0, 1.0f32]; 4];
    /// # let texcoords = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    /// let indices = [0u32, 1, 2, 0, 2, 3];
    /// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords).with_indices(&indices);
    /// assert_eq!((mesh.vertex_count(), mesh.corner_count()), (4, 6));
    ///
    /// let mut corners = vec![[0.0f32; 4]; mesh.corner_count()];
    /// generate_corners(&mesh, &Options::default(), &mut StridedMut::from_slice(&mut corners))?;
    /// assert_eq!(corners[5], [1.0, 0.0, 0.0, 1.0]);
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn corner_count(&self) -> usize {
        self.indices.corner_count(self.vertex_count())
    }
}

/// Where results go.
///
/// ```
/// use tbasis::{generate, Mesh, Options, Output};
///
/// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
/// # let normals = [[0.0, 0.0, 1.0f32]; 3];
/// # let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
/// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords);
/// let mut tangents = [[0.0f32; 4]; 3];
/// let mut output = Output::new(&mut tangents);
/// generate(&mesh, &Options::default(), &mut output)?;
/// assert_eq!(output.tangents.len(), 3);
/// assert_eq!(tangents[1], [1.0, 0.0, 0.0, 1.0]);
/// # Ok::<(), tbasis::Error>(())
/// ```
pub struct Output<'a> {
    /// Tangent x, y, z and handedness w (+1 or -1) per vertex.
    pub tangents: StridedMut<'a, [f32; 4]>,
    /// Bitangent `w * cross(n, t)` per vertex, when wanted.
    pub bitangents: Option<StridedMut<'a, [f32; 3]>>,
}

impl<'a> Mesh<'a> {
    /// The vertices of triangle `t`, each checked to be below the vertex count.
    #[inline(always)]
    pub(crate) fn checked_triangle(&self, t: usize) -> Result<[usize; 3], Error> {
        self.checked(self.indices.triangle(t))
    }

    /// `corners`, each checked to be below the vertex count.
    #[inline(always)]
    pub(crate) fn checked(&self, corners: [usize; 3]) -> Result<[usize; 3], Error> {
        if corners[0].max(corners[1]).max(corners[2]) >= self.vertex_count() {
            return Err(self.index_error());
        }
        Ok(corners)
    }

    /// The [`Error::IndexOutOfRange`] naming the first triangle with an index out of range, found
    /// again from the start so that every worker and thread count names the same one.
    #[cold]
    pub(crate) fn index_error(&self) -> Error {
        let vertex_count = self.vertex_count();
        let corners = self.corner_count() - self.corner_count() % 3;
        let bad = (0..corners).find(|&c| self.indices.corner(c) >= vertex_count);
        // Only called after a corner was found out of range, so `bad` is always some corner.
        let c = bad.unwrap_or_default();
        Error::IndexOutOfRange {
            triangle: c / 3,
            index: self.indices.corner(c),
            vertex_count,
        }
    }
}

impl<'a> Output<'a> {
    /// Tangents only (`[f32; 4]`, glam `Vec4`, or a [`StridedMut`] view into interleaved
    /// vertices); add bitangents with [`Output::with_bitangents`].
    ///
    /// ```
    /// let mut tangents = vec![glam::Vec4::ZERO; 3];
    /// let output = tbasis::Output::new(&mut tangents[..]);
    /// assert_eq!(output.tangents.len(), 3);
    /// ```
    pub fn new(tangents: impl Into<StridedMut<'a, [f32; 4]>>) -> Self {
        Output {
            tangents: tangents.into(),
            bitangents: None,
        }
    }

    /// With bitangents `w * cross(n, t)` written too.
    ///
    /// ```
    /// use tbasis::{generate, Mesh, Options, Output};
    ///
    /// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
    /// # let normals = [[0.0, 0.0, 1.0f32]; 3];
    /// # let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    /// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords);
    /// let (mut tangents, mut bitangents) = ([[0.0f32; 4]; 3], [[0.0f32; 3]; 3]);
    /// let mut output = Output::new(&mut tangents).with_bitangents(&mut bitangents);
    /// generate(&mesh, &Options::default(), &mut output)?;
    /// assert_eq!(tangents[0], [1.0, 0.0, 0.0, 1.0]);
    /// assert_eq!(bitangents[0], [0.0, 1.0, 0.0]);
    /// # Ok::<(), tbasis::Error>(())
    /// ```
    pub fn with_bitangents(self, bitangents: impl Into<StridedMut<'a, [f32; 3]>>) -> Self {
        Output {
            bitangents: Some(bitangents.into()),
            ..self
        }
    }

    /// The whole output as one part starting at vertex 0.
    pub(crate) fn whole(&mut self) -> OutputPart<'_> {
        OutputPart {
            tangents: self.tangents.reborrow(),
            bitangents: self.bitangents.as_mut().map(StridedMut::reborrow),
            first: 0,
        }
    }

    /// Disjoint parts for consecutive vertex ranges (exclusive `ends`), one per worker, without
    /// allocating.
    pub(crate) fn split<'p>(&'p mut self, ends: &'p [usize]) -> impl Iterator<Item = OutputPart<'p>> + 'p {
        let tangents = self.tangents.split(ends, 1).into_iter();
        let mut bitangents = self.bitangents.as_mut().map(|b| b.split(ends, 1).into_iter());
        let starts = core::iter::once(0).chain(ends.iter().copied());
        tangents.zip(starts).map(move |(tangents, first)| OutputPart {
            tangents,
            bitangents: bitangents.as_mut().and_then(Iterator::next),
            first,
        })
    }
}

/// What a call writes: a frame per vertex, or per triangle corner.
pub(crate) enum Target<'o, 'a> {
    /// `generate`: per vertex, into an [`Output`].
    Vertices(&'o mut Output<'a>),
    /// `generate_corners`: per corner, `3t + k` for corner `k` of triangle `t`.
    Corners(&'o mut StridedMut<'a, [f32; 4]>),
}

/// The output of one consecutive range of vertices.
pub(crate) struct OutputPart<'a> {
    tangents: StridedMut<'a, [f32; 4]>,
    bitangents: Option<StridedMut<'a, [f32; 3]>>,
    first: usize,
}

impl OutputPart<'_> {
    /// The tangents as a packed array, when nothing else is written and they sit packed
    /// ([`StridedMut::packed_mut`]).
    #[inline(always)]
    pub(crate) fn packed_tangents(&mut self) -> Option<&mut [[f32; 4]]> {
        match self.bitangents {
            None => self.tangents.packed_mut(),
            Some(_) => None,
        }
    }

    /// Writes vertex `v`: tangent `(t, w)` and, when wanted, the bitangent `w * cross(n, t)`.
    #[inline(always)]
    pub(crate) fn write(&mut self, v: usize, t: glam::Vec3, w: f32, n: glam::Vec3) {
        let slot = v - self.first;
        self.tangents.set(slot, [t.x, t.y, t.z, w]);
        if let Some(bitangents) = &mut self.bitangents {
            bitangents.set(slot, (n.cross(t) * w).to_array());
        }
    }
}
