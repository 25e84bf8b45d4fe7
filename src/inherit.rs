//! Policy INHERIT: a vertex without a measured tangent takes one from its neighbours.
#![forbid(unsafe_code)]

use glam::Vec3;

use crate::frame::orthonormalize;
use crate::mesh::Mesh;
use crate::resolve::VertexNormal;
use crate::scratch::{flag, Scratch};

/// Spreads resolved tangents into unresolved vertices one ring of shared triangles at a time,
/// until a ring resolves nothing; returns how many vertices were resolved.
///
/// Expects resolved vertices to hold their unit tangent in `primary` and handedness in `weight`,
/// and unresolved ones zeroed `secondary` and `weight` (their accumulators). Each ring sees only
/// the vertices resolved before it (Jacobi order), so the result does not depend on the order of
/// the triangles within a ring. A ring costs one pass over the triangles; the number of rings is
/// the widest distance from an unresolved vertex to a resolved one.
pub fn propagate(mesh: &Mesh, scratch: &mut Scratch) -> usize {
    assert!(
        scratch.first == 0 && scratch.flags.len() == mesh.vertex_count(),
        "needs the whole mesh's scratch"
    );
    let triangle_count = mesh.indices.triangle_count(mesh.vertex_count()).unwrap_or(0);
    let mut inherited = 0;
    loop {
        let mut touched = false;
        for t in 0..triangle_count {
            let corners = mesh.indices.triangle(t);
            for &v in &corners {
                if scratch.flags[v] & flag::RESOLVED != 0 {
                    continue;
                }
                for &u in &corners {
                    if scratch.flags[u] & flag::RESOLVED != 0 {
                        let from = scratch.sums[u];
                        let to = &mut scratch.sums[v];
                        to.secondary = (Vec3::from_array(to.secondary) + Vec3::from_array(from.primary)).to_array();
                        to.weight += from.weight;
                        touched = true;
                    }
                }
            }
        }
        if !touched {
            return inherited;
        }
        let ring = settle_ring(mesh, scratch);
        if ring == 0 {
            return inherited;
        }
        inherited += ring;
    }
}

/// Turns each unresolved vertex's gathered neighbour tangents into its own (projected into its
/// tangent plane and normalized, handedness by majority, ties +1) and clears the accumulators.
fn settle_ring(mesh: &Mesh, scratch: &mut Scratch) -> usize {
    let mut settled = 0;
    for v in 0..mesh.vertex_count() {
        if scratch.flags[v] & flag::RESOLVED != 0 {
            continue;
        }
        let sums = &mut scratch.sums[v];
        let gathered = Vec3::from_array(sums.secondary);
        let vote = sums.weight;
        sums.secondary = [0.0; 3];
        sums.weight = 0.0;
        let normal = VertexNormal::new(mesh.normals.get(v)).unit;
        // Neighbours' tangents are unit vectors: a remainder below 1e-3 of one is cancellation.
        if let Some((in_plane, tangent)) = orthonormalize(gathered, normal) {
            if in_plane > 1e-3 {
                sums.primary = tangent.to_array();
                sums.weight = if vote < 0.0 { -1.0 } else { 1.0 };
                scratch.flags[v] |= flag::RESOLVED;
                settled += 1;
            }
        }
    }
    settled
}
