//! Triangles in batches: the attributes of their corners copied into one short array per
//! component, so that the per-triangle arithmetic runs as loops over lanes that compile to SIMD,
//! while the sums are still added one triangle at a time, in triangle order.
#![forbid(unsafe_code)]

use glam::Vec3;

use crate::kernel::error::Error;
use crate::kernel::mesh::Mesh;
use crate::kernel::views::strided::Strided;

/// Triangles per batch: the gathered copies (about 8 KiB) stay in the L1 cache.
pub(crate) const LANES: usize = 64;

/// How many triangles ahead a reader asks for indices: a worker that keeps few of the triangles
/// (those with a corner in its vertex range) reads indices faster than memory streams them
/// unasked.
pub(crate) const PREFETCH_TRIANGLES: usize = 64;

/// One value per triangle of a batch.
pub type Lanes = [f32; LANES];

/// The lanes loops over a batch of `len` items run: `len` rounded up to a whole SIMD register's
/// worth (the lanes past `len` hold finished or zeroed values, computed and ignored), so that a
/// small mesh does not pay for a whole batch.
#[inline(always)]
pub fn lanes_in_use(len: usize) -> usize {
    len.next_multiple_of(8).min(LANES)
}

/// Lane `i` of three component arrays, as a vector.
#[inline(always)]
pub fn lane3(lanes: &[Lanes; 3], i: usize) -> Vec3 {
    Vec3::new(lanes[0][i], lanes[1][i], lanes[2][i])
}

/// Stores `value` in lane `i` of three component arrays.
#[inline(always)]
pub fn set_lane3(lanes: &mut [Lanes; 3], i: usize, value: [f32; 3]) {
    for (component, value) in lanes.iter_mut().zip(value) {
        component[i] = value;
    }
}

/// A batch of triangles and the attributes of their corners, `[corner][component][lane]`.
pub struct TriangleBatch {
    /// Triangles in the batch (the lanes in use).
    pub len: usize,
    /// Index of each triangle in the mesh.
    pub triangle: [usize; LANES],
    /// The vertices of each triangle's corners.
    pub vertex: [[usize; LANES]; 3],
    /// Corner positions.
    pub position: [[Lanes; 3]; 3],
    /// Corner texture coordinates.
    pub texcoord: [[Lanes; 2]; 3],
    /// Corner normals, when the batch was filled with them.
    pub normal: [[Lanes; 3]; 3],
}

impl TriangleBatch {
    /// An empty batch (on the stack: a call with caller scratch allocates nothing).
    pub fn new() -> Self {
        TriangleBatch {
            len: 0,
            triangle: [0; LANES],
            vertex: [[0; LANES]; 3],
            position: [[[0.0; LANES]; 3]; 3],
            texcoord: [[[0.0; LANES]; 2]; 3],
            normal: [[[0.0; LANES]; 3]; 3],
        }
    }
}

/// Walks a range of a mesh's triangles in order, a batch at a time, keeping those whose vertices
/// `keep` accepts (e.g. those with a corner in one worker's vertex range) and checking every index
/// on the way.
pub struct BatchReader<'m, K> {
    mesh: &'m Mesh<'m>,
    texcoords: Strided<'m, [f32; 2]>,
    keep: K,
    with_normals: bool,
    next: usize,
    end: usize,
}

impl<'m, K: Fn(&[usize; 3]) -> bool> BatchReader<'m, K> {
    /// A reader over `triangles`, whole triangles of `mesh`.
    pub fn new(
        mesh: &'m Mesh<'m>,
        texcoords: Strided<'m, [f32; 2]>,
        triangles: core::ops::Range<usize>,
        keep: K,
        with_normals: bool,
    ) -> Self {
        BatchReader {
            mesh,
            texcoords,
            keep,
            with_normals,
            next: triangles.start,
            end: triangles.end,
        }
    }

    /// Fills `batch` with the next triangles; false once every triangle has been read.
    #[inline(always)]
    pub fn fill(&mut self, batch: &mut TriangleBatch) -> Result<bool, Error> {
        batch.len = 0;
        while batch.len < LANES && self.next < self.end {
            let t = self.next;
            self.next += 1;
            self.mesh.indices.prefetch_triangle(t + PREFETCH_TRIANGLES);
            let corners = self.mesh.checked_triangle(t)?;
            if !(self.keep)(&corners) {
                continue;
            }
            let lane = batch.len;
            batch.triangle[lane] = t;
            for (k, &v) in corners.iter().enumerate() {
                batch.vertex[k][lane] = v;
                set_lane3(&mut batch.position[k], lane, self.mesh.positions.get(v));
                let uv = self.texcoords.get(v);
                batch.texcoord[k][0][lane] = uv[0];
                batch.texcoord[k][1][lane] = uv[1];
                if self.with_normals {
                    set_lane3(&mut batch.normal[k], lane, self.mesh.normals.get(v));
                }
            }
            batch.len += 1;
        }
        Ok(batch.len > 0)
    }
}
