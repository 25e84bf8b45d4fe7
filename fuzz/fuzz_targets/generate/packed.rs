//! The mesh of a plan as the library reads it, copied into plain arrays: for the Rust API and for
//! mikktspace.c, which take no strides.

use std::cell::OnceCell;

use tbasis::Mesh;

use crate::arena::{vec_at, Buf};
use crate::mikktspace_cost::reference_cost;
use crate::mikktspace_reference::reference_corners;
use crate::plan::{read_indices, Plan, IDX, NRM, POS, UV};

pub struct Packed {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    /// `None` when the call passes no texture coordinates.
    pub texcoords: Option<Vec<[f32; 2]>>,
    /// Widened to u32; `None`: unindexed.
    pub indices: Option<Vec<u32>>,
    /// mikktspace.c's corners with `flip_v` off and on, computed when first asked for.
    references: [OnceCell<Vec<[f32; 4]>>; 2],
    /// Whether mikktspace.c runs on this mesh in reasonable time (`generate/mikktspace_cost.rs`).
    affordable: OnceCell<bool>,
}

/// Pair comparisons mikktspace.c may make on one mesh, at most, for the harness to run it: about
/// 20 ms in an optimized build (a few times that with a sanitizer), for each of the up to ten
/// runs an input makes. Every mesh of distinct positions stays far below; a mesh of thousands of
/// corners at one position with other normals or texture coordinates (a large mesh whose
/// positions ran out of bytes, the snapped variant of a large mesh) goes past it.
const REFERENCE_BUDGET: u64 = 1 << 20;

/// The buffer's elements, when the library can read them all (none when it is NULL and empty).
fn elements<const N: usize>(buf: &Buf, arena: &[u8]) -> Option<Vec<[f32; N]>> {
    let readable = buf.violations() == 0 && (buf.count == 0 || buf.placed(arena.len()));
    readable.then(|| (0..buf.count).map(|i| vec_at(arena, buf.element(i))).collect())
}

impl Packed {
    /// The mesh of `plan` over `arena`, when it is one the library must accept: every buffer it
    /// reads readable, whole triangles, indices in range.
    pub fn of(plan: &Plan, arena: &[u8]) -> Option<Packed> {
        let b = &plan.bufs;
        let positions = elements(&b[POS], arena)?;
        let normals = elements(&b[NRM], arena)?;
        let texcoords = if b[UV].null {
            None
        } else {
            Some(elements(&b[UV], arena)?)
        };
        let indices = if b[IDX].null {
            (b[IDX].count == 0 && plan.vertex_count % 3 == 0).then_some(None)?
        } else {
            let readable = plan.index_type_valid() && b[IDX].violations() == 0 && b[IDX].placed(arena.len());
            let values = readable.then(|| read_indices(plan, arena))?;
            let whole = values.len() % 3 == 0 && values.iter().all(|&i| i < plan.vertex_count);
            whole.then(|| Some(values.into_iter().map(|i| i as u32).collect()))?
        };
        Some(Packed::new(positions, normals, texcoords, indices))
    }

    fn new(
        positions: Vec<[f32; 3]>,
        normals: Vec<[f32; 3]>,
        texcoords: Option<Vec<[f32; 2]>>,
        indices: Option<Vec<u32>>,
    ) -> Packed {
        Packed {
            positions,
            normals,
            texcoords,
            indices,
            references: Default::default(),
            affordable: OnceCell::new(),
        }
    }

    /// Meshes made from this one on which what mikktspace.c's welding, edge pairing and grouping
    /// hinge on is common, each meeting one condition under which the library's weld by value must
    /// decline or find the last run of the edge sort (`last_run.rs`):
    /// - every value snapped to one of a few (equal corners, shared edges, collapsed triangles,
    ///   exact mirror seams; NaN stays NaN);
    /// - the same corners unindexed (welding must find the vertices the index buffer shared);
    /// - every vertex twice, corners alternating between the copies (duplicates mikktspace.c welds
    ///   back, as exporters write them), and the same with the second copy's zeros negated (equal
    ///   under `==`, other bits: the representative's bits matter);
    /// - the snapped mesh with a NaN in its first corner (mikktspace.c's bounding box stays NaN
    ///   and nothing welds);
    /// - the snapped mesh with its last triangle's first edge used three more times at the end of
    ///   the triangle list (non-manifold edges among the largest welded indices, where the edge
    ///   sort's unsorted last run lies).
    pub fn variants(&self) -> Vec<Packed> {
        let snap = |x: f32| (x / 4.0).round().clamp(-2.0, 2.0);
        let snap_normal = |x: f32| x.round().clamp(-1.0, 1.0);
        let snapped = || {
            Packed::new(
                self.positions.iter().map(|p| p.map(snap)).collect(),
                self.normals.iter().map(|n| n.map(snap_normal)).collect(),
                self.texcoords
                    .as_ref()
                    .map(|t| t.iter().map(|uv| uv.map(snap)).collect()),
                self.indices.clone(),
            )
        };
        let corners = 0..self.corner_count();
        let mut variants = vec![snapped()];
        if self.indices.is_some() {
            let gather = |values: &[[f32; 3]]| corners.clone().map(|c| values[self.corner_vertex(c)]).collect();
            variants.push(Packed::new(
                gather(&self.positions),
                gather(&self.normals),
                self.texcoords
                    .as_ref()
                    .map(|t| corners.clone().map(|c| t[self.corner_vertex(c)]).collect()),
                None,
            ));
        }
        let vertex_count = self.vertex_count() as u32;
        for negate_zeros in [false, true] {
            let copy = |x: f32| if negate_zeros && x == 0.0 { -x } else { x };
            let twice = |values: &[[f32; 3]]| values.iter().copied().chain(values.iter().map(|v| v.map(copy))).collect();
            variants.push(Packed::new(
                twice(&self.positions),
                twice(&self.normals),
                self.texcoords
                    .as_ref()
                    .map(|t| t.iter().copied().chain(t.iter().map(|uv| uv.map(copy))).collect()),
                Some(
                    corners
                        .clone()
                        .map(|c| self.corner_vertex(c) as u32 + (c % 2) as u32 * vertex_count)
                        .collect(),
                ),
            ));
        }
        if self.corner_count() >= 3 {
            let mut first_nan = snapped();
            let first = self.corner_vertex(0);
            first_nan.positions[first][0] = f32::NAN;
            variants.push(first_nan);

            let mut shared_edge = snapped();
            let last = self.corner_count() - 3;
            let [a, b] = [last, last + 1].map(|c| self.corner_vertex(c) as u32);
            let others = [0, self.corner_count() / 2, last + 2].map(|c| self.corner_vertex(c) as u32);
            let indices: Vec<u32> = corners.clone().map(|c| self.corner_vertex(c) as u32).collect();
            let appended = [[b, a, others[0]], [a, b, others[1]], [b, a, others[2]]];
            shared_edge.indices = Some(indices.into_iter().chain(appended.into_iter().flatten()).collect());
            variants.push(shared_edge);
        }
        variants
    }

    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    pub fn corner_count(&self) -> usize {
        self.indices.as_ref().map_or(self.vertex_count(), Vec::len)
    }

    pub fn corner_vertex(&self, c: usize) -> usize {
        self.indices.as_ref().map_or(c, |indices| indices[c] as usize)
    }

    pub fn mesh(&self) -> Mesh<'_> {
        let mut mesh = Mesh::new(&self.positions[..], &self.normals[..]);
        if let Some(texcoords) = &self.texcoords {
            mesh = mesh.with_texcoords(&texcoords[..]);
        }
        if let Some(indices) = &self.indices {
            mesh = mesh.with_indices(&indices[..]);
        }
        mesh
    }

    /// mikktspace.c's frame per corner; `None` without texture coordinates, or when mikktspace.c's
    /// quadratic steps would take too long on this mesh (`REFERENCE_BUDGET`).
    pub fn reference(&self, flip_v: bool) -> Option<&[[f32; 4]]> {
        let texcoords = self.texcoords.as_deref()?;
        let affordable = *self.affordable.get_or_init(|| {
            let positions: Vec<[f32; 3]> = (0..self.corner_count())
                .map(|c| self.positions[self.corner_vertex(c)])
                .collect();
            reference_cost(&positions) <= REFERENCE_BUDGET
        });
        if !affordable {
            return None;
        }
        let corners = self.references[usize::from(flip_v)].get_or_init(|| {
            // mikktspace.c returns false, writing nothing, only without triangles.
            reference_corners(
                &self.positions,
                &self.normals,
                texcoords,
                self.indices.as_deref(),
                flip_v,
            )
            .unwrap_or_else(|| {
                assert_eq!(self.corner_count(), 0, "mikktspace.c failed on a mesh with triangles");
                Vec::new()
            })
        });
        Some(corners)
    }

    /// Prints the mesh, for `FUZZ_DEBUG=1` and for writing a finding down.
    pub fn describe(&self) {
        for v in 0..self.vertex_count() {
            let uv = self.texcoords.as_ref().map(|t| t[v]);
            eprintln!(
                "v{v}: p {:?} n {:?} uv {:?}  bits p {:08x?} n {:08x?} uv {:08x?}",
                self.positions[v],
                self.normals[v],
                uv,
                self.positions[v].map(f32::to_bits),
                self.normals[v].map(f32::to_bits),
                uv.map(|uv| uv.map(f32::to_bits))
            );
        }
        match &self.indices {
            Some(indices) => eprintln!("indices {indices:?}"),
            None => eprintln!("unindexed"),
        }
    }
}
