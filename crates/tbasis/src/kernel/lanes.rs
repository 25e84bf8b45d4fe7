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

/// How many triangles ahead a reader that asks ahead ([`BatchReader::asks_ahead`]) asks for its
/// corners' attributes: far enough that they arrive before the batch's arithmetic needs them.
const PREFETCH_ATTRIBUTES: usize = 16;

/// How many triangles apart [`jumps_around`] compares: one batch.
const ORDER_STRIDE: usize = LANES;

/// How many pairs of triangles [`jumps_around`] compares, at most.
const ORDER_SAMPLES: usize = 64;

/// How far apart the first vertices of two triangles a batch apart may lie where the triangle
/// order follows the vertex order: a batch there brings about 32 new vertices (a closed mesh has
/// about two triangles per vertex; 32 on the benchmark's torus, hundreds to thousands on
/// FlightHelmet.cc1's primitives).
const NEAR_VERTICES: usize = 256;

/// Whether the triangles of `triangles` jump around the vertex arrays, so that a batch's corners
/// would each wait for memory: true when more than a quarter of the pairs of triangles a batch
/// apart, evenly spaced, have first vertices more than [`NEAR_VERTICES`] apart. Where the triangle
/// order follows the vertex order (a grid, a mesh whose vertices were renumbered in order of first
/// use) the processor's own prefetching finds the vertices, and asking for them costs time.
fn jumps_around(mesh: &Mesh, triangles: &core::ops::Range<usize>) -> bool {
    let Some(last) = triangles
        .end
        .checked_sub(ORDER_STRIDE)
        .filter(|&last| last > triangles.start)
    else {
        return false;
    };
    let step = (last - triangles.start).div_ceil(ORDER_SAMPLES).max(1);
    let (mut sampled, mut jumps) = (0usize, 0usize);
    for t in (triangles.start..last).step_by(step) {
        let (a, b) = (mesh.indices.triangle(t)[0], mesh.indices.triangle(t + ORDER_STRIDE)[0]);
        jumps += usize::from(a.abs_diff(b) > NEAR_VERTICES);
        sampled += 1;
    }
    4 * jumps > sampled
}

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
    asks_ahead: bool,
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
            asks_ahead: jumps_around(mesh, &triangles),
            next: triangles.start,
            end: triangles.end,
        }
    }

    /// Whether the reader asks for the attributes of the triangles it will read next, where its
    /// triangles jump around the vertex arrays ([`jumps_around`]): then whoever adds the batch's
    /// terms to per-vertex sums should ask for those ahead too.
    pub fn asks_ahead(&self) -> bool {
        self.asks_ahead
    }

    /// Fills `batch` with the next triangles; false once every triangle has been read.
    #[inline(always)]
    pub fn fill(&mut self, batch: &mut TriangleBatch) -> Result<bool, Error> {
        batch.len = 0;
        while batch.len < LANES && self.next < self.end {
            let t = self.next;
            self.next += 1;
            self.mesh.indices.prefetch_triangle(t + PREFETCH_TRIANGLES);
            if self.asks_ahead && t + PREFETCH_ATTRIBUTES < self.end {
                // Unchecked indices: a prefetch past a view's end asks for nothing.
                for v in self.mesh.indices.triangle(t + PREFETCH_ATTRIBUTES) {
                    self.mesh.positions.prefetch(v);
                    self.texcoords.prefetch(v);
                    if self.with_normals {
                        self.mesh.normals.prefetch(v);
                    }
                }
            }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::mesh::Indices;
    use crate::kernel::test_rng::TestRng;

    /// Whether a reader over every triangle of `indices` asks ahead.
    fn asks_ahead(indices: &[u32]) -> bool {
        let vertex_count = indices.iter().max().map_or(0, |&v| v as usize + 1);
        let (vectors, texcoords) = (vec![[0.0f32; 3]; vertex_count], vec![[0.0f32; 2]; vertex_count]);
        let mesh = Mesh {
            positions: Strided::from_slice(&vectors),
            normals: Strided::from_slice(&vectors),
            texcoords: Some(Strided::from_slice(&texcoords)),
            indices: Indices::U32(Strided::from_slice(indices)),
        };
        let triangles = 0..indices.len() / 3;
        BatchReader::new(&mesh, Strided::from_slice(&texcoords), triangles, |_| true, true).asks_ahead()
    }

    /// The two triangles of each cell of a `width` x `height` grid of vertices, row by row, vertex
    /// `(i, j)` numbered `number[j * width + i]`.
    fn grid(width: usize, height: usize, number: &[u32]) -> Vec<u32> {
        let id = |i: usize, j: usize| number[j * width + i];
        let mut indices = Vec::new();
        for j in 0..height - 1 {
            for i in 0..width - 1 {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                indices.extend([a, b, c, a, c, d]);
            }
        }
        indices
    }

    #[test]
    fn a_reader_asks_ahead_only_where_the_triangles_jump_around_the_vertices() {
        let mut rng = TestRng(0x9e37_79b9_7f4a_7c15);
        for (width, height) in [(300, 200), (1000, 20), (40, 40)] {
            let in_order: Vec<u32> = (0..(width * height) as u32).collect();
            let mut shuffled = in_order.clone();
            for i in (1..shuffled.len()).rev() {
                shuffled.swap(i, rng.below(i + 1));
            }
            assert!(
                !asks_ahead(&grid(width, height, &in_order)),
                "{width} x {height} in order"
            );
            assert!(
                asks_ahead(&grid(width, height, &shuffled)),
                "{width} x {height} shuffled"
            );
        }
        // Fewer triangles than a batch: nothing to tell, no asking.
        let in_order: Vec<u32> = (0..16).collect();
        let mut shuffled = in_order.clone();
        shuffled.reverse();
        assert!(!asks_ahead(&grid(4, 4, &shuffled)));
        assert!(!asks_ahead(&[]));
    }
}
