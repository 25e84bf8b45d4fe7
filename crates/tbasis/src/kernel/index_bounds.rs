//! The smallest and largest vertex of each block of consecutive triangles. A worker that takes the
//! triangles with a corner in its range of vertices (where the triangle order follows the vertex
//! order) skips, by these bounds, every block with none, instead of reading each of its triangles
//! to find out. The bounds come from the index buffer read as a plain array, in SIMD lanes, which
//! costs far less per triangle than the test it saves; a strided index buffer gets none.
#![forbid(unsafe_code)]

use core::ops::Range;

use crate::kernel::error::Error;
use crate::kernel::memory;
use crate::kernel::mesh::{Indices, Mesh};
use crate::kernel::parallel;

/// Triangles per block: a block a worker reads whole costs it little where most of its triangles
/// lie in its range, and the bounds take 8 bytes per block.
const BLOCK_TRIANGLES: usize = if cfg!(test) { 4 } else { 128 };

/// Each block's `[smallest, largest]` vertex.
pub(crate) struct IndexBounds {
    blocks: Vec<[u32; 2]>,
    triangle_count: usize,
}

/// The bounds of `mesh`'s first `triangle_count` triangles, on `workers` ranges of blocks, where
/// its indices sit packed; `None` where they do not, or there are none. Checks every index read: an
/// index past the vertex count gives [`Mesh::index_error`], so that a worker that skips a block
/// still reports it.
pub(crate) fn index_bounds(mesh: &Mesh, triangle_count: usize, workers: usize) -> Result<Option<IndexBounds>, Error> {
    let bounds = match mesh.indices {
        Indices::U16(view) => view.packed().map(|indices| bounds_of(indices, triangle_count, workers)),
        Indices::U32(view) => view.packed().map(|indices| bounds_of(indices, triangle_count, workers)),
        Indices::None => None,
    };
    let Some(bounds) = bounds.transpose()? else {
        return Ok(None);
    };
    if bounds
        .blocks
        .iter()
        .any(|&[_, largest]| largest as usize >= mesh.vertex_count())
    {
        return Err(mesh.index_error());
    }
    Ok(Some(bounds))
}

fn bounds_of<T: Copy + Into<u32> + Sync>(
    indices: &[T],
    triangle_count: usize,
    workers: usize,
) -> Result<IndexBounds, Error> {
    let corners = &indices[..3 * triangle_count];
    let mut blocks = memory::vec_filled(triangle_count.div_ceil(BLOCK_TRIANGLES), [0; 2])?;
    let ranges = parallel::range_ends(blocks.len(), workers);
    let ends = ranges.ends();
    parallel::run_ranges(ends, parallel::split(&mut blocks, ends, 1), |first, part| {
        let chunks = corners[3 * BLOCK_TRIANGLES * first..].chunks(3 * BLOCK_TRIANGLES);
        for (bounds, chunk) in part.iter_mut().zip(chunks) {
            // Two folds, each a reduction the compiler keeps in lanes.
            let smallest = chunk.iter().fold(u32::MAX, |m, &v| m.min(v.into()));
            let largest = chunk.iter().fold(0, |m, &v| m.max(v.into()));
            *bounds = [smallest, largest];
        }
    });
    Ok(IndexBounds { blocks, triangle_count })
}

/// The runs of consecutive triangles, within `triangles`, that a worker holding `vertices` reads:
/// those of the blocks with a vertex in `vertices`, in order, or without `bounds` every triangle
/// as one run. One type for both, so that a loop over them compiles once.
pub(crate) fn runs<'b>(bounds: Option<&'b IndexBounds>, triangles: Range<usize>, vertices: Range<usize>) -> Runs<'b> {
    let (block, end_block) = match bounds {
        Some(bounds) => (
            triangles.start / BLOCK_TRIANGLES,
            triangles.end.min(bounds.triangle_count).div_ceil(BLOCK_TRIANGLES),
        ),
        None => (0, usize::from(!triangles.is_empty())),
    };
    Runs {
        bounds,
        triangles,
        vertices,
        block,
        end_block,
    }
}

/// The iterator of [`runs`].
pub(crate) struct Runs<'b> {
    bounds: Option<&'b IndexBounds>,
    triangles: Range<usize>,
    vertices: Range<usize>,
    block: usize,
    end_block: usize,
}

impl Iterator for Runs<'_> {
    type Item = Range<usize>;

    fn next(&mut self) -> Option<Range<usize>> {
        let Some(bounds) = self.bounds else {
            // Without bounds, one run: every triangle.
            let whole = self.block < self.end_block;
            self.block = self.end_block;
            return whole.then(|| self.triangles.clone());
        };
        let touches = |b: usize| {
            let [smallest, largest] = bounds.blocks[b].map(|v| v as usize);
            smallest < self.vertices.end && largest >= self.vertices.start
        };
        while self.block < self.end_block && !touches(self.block) {
            self.block += 1;
        }
        let start = self.block;
        while self.block < self.end_block && touches(self.block) {
            self.block += 1;
        }
        let clip = |block: usize| (block * BLOCK_TRIANGLES).clamp(self.triangles.start, self.triangles.end);
        (start < self.end_block).then(|| clip(start)..clip(self.block))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::test_rng::TestRng;

    #[test]
    fn the_blocks_touching_a_range_hold_every_triangle_with_a_corner_in_it() {
        let mut rng = TestRng(0xB10C);
        let positions = [[0.0f32; 3]; 64];
        for round in 0..300 {
            let triangle_count = rng.below(40);
            // Mostly rising, as where the triangle order follows the vertex order, with jumps.
            let indices: Vec<u32> = (0..3 * triangle_count)
                .map(|c| if rng.chance(10) { rng.below(64) } else { (c * 64 / (3 * triangle_count)).min(63) } as u32)
                .collect();
            let narrow: Vec<u16> = indices.iter().map(|&v| v as u16).collect();
            let meshes = [
                Mesh::new(&positions[..], &positions[..]).with_indices(&indices[..]),
                Mesh::new(&positions[..], &positions[..]).with_indices(&narrow[..]),
            ];
            let (start, len) = (rng.below(64), rng.below(20));
            let vertices = start..start + len;
            let triangles = rng.below(triangle_count + 1)..triangle_count;
            let workers = 1 + rng.below(3);
            for mesh in &meshes {
                let bounds = index_bounds(mesh, triangle_count, workers).unwrap().unwrap();
                let taken: Vec<usize> = runs(Some(&bounds), triangles.clone(), vertices.clone())
                    .flatten()
                    .collect();
                let needed: Vec<usize> = triangles
                    .clone()
                    .filter(|&t| mesh.indices.triangle(t).iter().any(|v| vertices.contains(v)))
                    .collect();
                assert!(
                    taken.windows(2).all(|w| w[0] < w[1]),
                    "round {round}: in order, once each"
                );
                assert!(
                    taken.iter().all(|t| triangles.contains(t)),
                    "round {round}: within the triangles"
                );
                assert!(
                    needed.iter().all(|t| taken.contains(t)),
                    "round {round}: {needed:?} in {taken:?}"
                );
            }
        }
    }

    #[test]
    fn an_index_past_the_vertex_count_is_the_mesh_s_error() {
        let positions = [[0.0f32; 3]; 4];
        let indices = [0u32, 1, 2, 0, 2, 3, 1, 2, 4, 0, 1, 2];
        let mesh = Mesh::new(&positions[..], &positions[..]).with_indices(&indices[..]);
        for workers in 1..4 {
            let error = index_bounds(&mesh, 4, workers).err();
            assert_eq!(error, Some(mesh.index_error()), "{workers} workers");
        }
        assert!(
            index_bounds(&mesh, 2, 2).is_ok(),
            "only the triangles asked for are read"
        );
        let unindexed = Mesh::new(&positions[..3], &positions[..3]);
        assert!(index_bounds(&unindexed, 1, 2).unwrap().is_none());
        let whole: Vec<(usize, usize)> = runs(None, 2..9, 0..1).map(|r| (r.start, r.end)).collect();
        assert_eq!(whole, [(2, 9)], "without bounds, every triangle");
        assert_eq!(runs(None, 3..3, 0..1).count(), 0);
    }
}
