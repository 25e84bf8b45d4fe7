//! The caller's mesh and output, as views over memory the library reads or writes in place.
#![forbid(unsafe_code)]

use crate::status::Error;
use crate::strided::{Element, Footprint, Strided, StridedMut};

/// The index buffer: three indices per triangle, or none (triangle `i` is vertices `3i..3i+3`).
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
    pub fn triangle_count(&self, vertex_count: usize) -> Result<usize, Error> {
        let index_count = self.corner_count(vertex_count);
        if index_count % 3 != 0 {
            return Err(Error::InvalidIndexCount);
        }
        Ok(index_count / 3)
    }

    /// Number of corners: the index count, or `vertex_count` when unindexed.
    pub fn corner_count(&self, vertex_count: usize) -> usize {
        match self {
            Indices::None => vertex_count,
            Indices::U16(view) => view.len(),
            Indices::U32(view) => view.len(),
        }
    }

    /// The vertex of corner `c` (callers keep `c` below `corner_count`).
    #[inline(always)]
    pub fn corner(&self, c: usize) -> usize {
        match self {
            Indices::None => c,
            Indices::U16(view) => view.get(c) as usize,
            Indices::U32(view) => view.get(c) as usize,
        }
    }

    /// The vertices of triangle `t` (callers keep `t` below `triangle_count`).
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

    /// Where the index bytes are, if there are any.
    pub fn footprint(&self) -> Option<Footprint> {
        match self {
            Indices::None => None,
            Indices::U16(view) => Some(view.footprint()),
            Indices::U32(view) => Some(view.footprint()),
        }
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
    [0, 1, 2].map(|k| view.get(3 * t + k).into() as usize)
}

/// A triangle mesh: per-vertex attributes as strided views, and its triangles.
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
    /// Number of vertices (the positions' length; the other attributes must match it).
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangle corners: the index count, or the vertex count when unindexed. The
    /// per-corner output has this many elements, corner `3t + k` being corner `k` of triangle `t`.
    pub fn corner_count(&self) -> usize {
        self.indices.corner_count(self.vertex_count())
    }
}

/// Where results go.
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
            return Err(Error::IndexOutOfRange);
        }
        Ok(corners)
    }
}

impl<'a> Output<'a> {
    /// The whole output as one part starting at vertex 0.
    pub(crate) fn whole(&mut self) -> OutputPart<'_> {
        OutputPart {
            tangents: self.tangents.reborrow(),
            bitangents: self.bitangents.as_mut().map(StridedMut::reborrow),
            first: 0,
        }
    }

    /// Disjoint parts for consecutive vertex ranges (exclusive `ends`), one per worker.
    pub(crate) fn split(&mut self, ends: &[usize]) -> Vec<OutputPart<'_>> {
        let tangents = self.tangents.split(ends);
        let mut bitangents = self.bitangents.as_mut().map(|b| b.split(ends).into_iter());
        let starts = core::iter::once(0).chain(ends.iter().copied());
        tangents
            .into_iter()
            .zip(starts)
            .map(|(tangents, first)| OutputPart {
                tangents,
                bitangents: bitangents.as_mut().and_then(Iterator::next),
                first,
            })
            .collect()
    }
}

/// The output of one consecutive range of vertices.
pub(crate) struct OutputPart<'a> {
    tangents: StridedMut<'a, [f32; 4]>,
    bitangents: Option<StridedMut<'a, [f32; 3]>>,
    first: usize,
}

impl OutputPart<'_> {
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
