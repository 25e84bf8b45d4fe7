//! Per-vertex results for every policy but LEGACY: pick a handedness, Gram-Schmidt, or fall back.
#![forbid(unsafe_code)]

use glam::Vec3;

use crate::kernel::fold::{first_side, is_mirror_fold};
use crate::kernel::frame::{
    fallback, fallback_tangent, finish_tangent, is_unit_length, length_and_direction_fast, orthonormalize,
    orthonormalize_fast, VertexNormal,
};
use crate::kernel::lanes::{lane3, lanes_in_use, set_lane3, Lanes, LANES};
use crate::kernel::mesh::{Mesh, OutputPart};
use crate::kernel::options::DegeneratePolicy;
use crate::kernel::report::Report;
use crate::kernel::sums::{flag, Scratch, VertexSums};
use crate::pipelines::per_vertex::inherit;

/// A summed tangent whose component off the normal is below this share of the total weight that
/// went into it is cancellation or rounding noise (mirror contributions meeting head-on, or a
/// tangent parallel to the normal), not a measurement.
const USABLE_SHARE: f32 = 1e-3;

/// The outcome for one vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Resolved {
    /// A measured unit tangent and its handedness.
    Measured(Vec3, f32),
    /// No usable tangent: the policy decides (inherit or fall back).
    Missing,
}

/// Keeps the handedness [`first_side`] picks (`primary`: right-handed, w = +1), removes the normal
/// from its sum and normalizes it, if what is left is usable; else the other handedness's,
/// likewise.
#[inline(always)]
pub fn resolve(sums: &VertexSums, flags: u8, normal: Option<Vec3>) -> Resolved {
    let ((first, w), other) = first_side(sums, flags);
    match resolve_side(Vec3::from_array(first), w, sums.weight, normal) {
        Resolved::Missing => resolve_side(Vec3::from_array(other), -w, sums.weight, normal),
        measured => measured,
    }
}

/// The frame of the handedness [`resolve`] did not keep (the one with `w = -kept_w`), by the same
/// test against the same total weight: at a mirror fold, the frame of the other side's corners.
#[inline(always)]
pub fn resolve_other_side(sums: &VertexSums, kept_w: f32, normal: Option<Vec3>) -> Resolved {
    let (sum, w) = if kept_w > 0.0 {
        (sums.secondary, -1.0)
    } else {
        (sums.primary, 1.0)
    };
    resolve_side(Vec3::from_array(sum), w, sums.weight, normal)
}

/// One handedness's sum made a frame: the normal removed, normalized, if what is left is at least
/// [`USABLE_SHARE`] of `weight`, the total weight that went into the vertex.
#[inline(always)]
fn resolve_side(sum: Vec3, w: f32, weight: f32, normal: Option<Vec3>) -> Resolved {
    match orthonormalize(sum, normal) {
        Some((in_plane, tangent)) if in_plane > USABLE_SHARE * weight => {
            Resolved::Measured(finish_tangent(sum, tangent, normal), w)
        }
        _ => Resolved::Missing,
    }
}

/// Writes the result of every vertex `scratch` holds for policies SKIP, INHERIT and REJECT and
/// counts what it did; returns how many vertices wait for [`write_inherited`].
///
/// Measured vertices are written at once. Under INHERIT the others wait for their neighbours;
/// under SKIP (and REJECT, which reaches here only without degenerate triangles) they get the
/// fallback frame at once. The common case runs a batch of vertices at a time in SIMD lanes
/// ([`Lanes`]); a vertex it cannot settle exactly takes the careful path ([`resolve`]).
///
/// Without an `output` (the per-corner output) each vertex keeps its frame in its sums instead
/// ([`VertexSums::keep_frame`]), and a measured mirror-fold vertex also keeps its other side's
/// frame when that side's sum is usable ([`resolve_other_side`], flag [`flag::SIDE_FRAME`]).
#[inline(always)]
pub fn write_measured(
    mesh: &Mesh,
    policy: DegeneratePolicy,
    scratch: &mut Scratch,
    mut output: Option<&mut OutputPart>,
    report: &mut Report,
) -> usize {
    let defer_missing = policy == DegeneratePolicy::Inherit && mesh.texcoords.is_some();
    let keep_sides = output.is_none();
    let mut deferred = 0usize;
    let mut lanes = ResolvedLanes::new();
    for (batch, sums) in scratch.sums.chunks_mut(LANES).enumerate() {
        let first = scratch.first + batch * LANES;
        let flags = &scratch.flags[batch * LANES..batch * LANES + sums.len()];
        lanes.resolve(mesh, first, sums, flags);
        for (i, sums) in sums.iter_mut().enumerate() {
            let (v, slot) = (first + i, batch * LANES + i);
            let (normal, resolved) = if lanes.exact[i] != 0 {
                let normal = VertexNormal {
                    unit: Some(lane3(&lanes.normal, i)),
                    was_unit: lanes.was_unit[i] != 0,
                };
                (normal, Resolved::Measured(lane3(&lanes.tangent, i), lanes.w[i]))
            } else {
                let normal = VertexNormal::new(mesh.normals.get(v));
                (normal, resolve(sums, scratch.flags[slot], normal.unit))
            };
            report.abnormal_normals += usize::from(!normal.was_unit);
            match resolved {
                Resolved::Measured(t, w) => {
                    let flags = &mut scratch.flags[slot];
                    // The other side's frame, from its sum, before the frame takes the sum's place.
                    let side = if keep_sides && is_mirror_fold(*flags) {
                        resolve_other_side(sums, w, normal.unit)
                    } else {
                        Resolved::Missing
                    };
                    write_vertex(output.as_deref_mut(), sums, v, t, w, normal.unit);
                    if let Resolved::Measured(side_tangent, _) = side {
                        sums.secondary = side_tangent.to_array();
                        *flags |= flag::SIDE_FRAME;
                    }
                    if defer_missing {
                        sums.keep_frame(t, w);
                        *flags |= flag::RESOLVED;
                    }
                }
                Resolved::Missing if defer_missing => {
                    sums.secondary = [0.0; 3];
                    sums.weight = 0.0;
                    scratch.flags[slot] |= flag::DEFERRED;
                    deferred += 1;
                }
                Resolved::Missing => {
                    let (t, w) = fallback(normal.unit);
                    write_vertex(output.as_deref_mut(), sums, v, t, w, normal.unit);
                    report.fallback_vertices += 1;
                }
            }
        }
    }
    deferred
}

/// [`VertexNormal::new`] and [`resolve`] for a batch of vertices, one per lane, where both take
/// their common path. Lane flags are `u32` (1 or 0): a byte per lane keeps the loop from
/// compiling to SIMD.
struct ResolvedLanes {
    /// The caller's normals, the sums of the sides [`first_side`] picks with their `w`, and the
    /// total weights, gathered.
    raw_normal: [Lanes; 3],
    sum: [Lanes; 3],
    weight: Lanes,
    /// 1 when the lane took the common path; otherwise the careful one decides.
    exact: [u32; LANES],
    normal: [Lanes; 3],
    was_unit: [u32; LANES],
    tangent: [Lanes; 3],
    w: Lanes,
}

impl ResolvedLanes {
    fn new() -> Self {
        ResolvedLanes {
            raw_normal: [[0.0; LANES]; 3],
            sum: [[0.0; LANES]; 3],
            weight: [0.0; LANES],
            exact: [0; LANES],
            normal: [[0.0; LANES]; 3],
            was_unit: [0; LANES],
            tangent: [[0.0; LANES]; 3],
            w: [0.0; LANES],
        }
    }

    /// Vertices `first..first + sums.len()`.
    #[inline(always)]
    fn resolve(&mut self, mesh: &Mesh, first: usize, sums: &[VertexSums], flags: &[u8]) {
        for (i, sums) in sums.iter().enumerate() {
            set_lane3(&mut self.raw_normal, i, mesh.normals.get(first + i));
            let ((first, w), _) = first_side(sums, flags[i]);
            set_lane3(&mut self.sum, i, first);
            self.w[i] = w;
            self.weight[i] = sums.weight;
        }
        for i in 0..lanes_in_use(sums.len()) {
            let (length, unit, normal_exact) = length_and_direction_fast(lane3(&self.raw_normal, i));
            let sum = lane3(&self.sum, i);
            let (in_plane, tangent, tangent_exact) = orthonormalize_fast(sum, unit);
            let tangent = finish_tangent(sum, tangent, Some(unit));
            // A first side too short to measure leaves the other side to the careful path.
            let measured = in_plane > USABLE_SHARE * self.weight[i];
            self.exact[i] = u32::from(normal_exact & tangent_exact & measured);
            self.was_unit[i] = u32::from(is_unit_length(length));
            for axis in 0..3 {
                self.normal[axis][i] = unit[axis];
                self.tangent[axis][i] = tangent[axis];
            }
        }
    }
}

/// Policy INHERIT, after [`write_measured`] deferred some vertices: spreads tangents into them
/// from their neighbours ([`inherit::propagate`], on the whole mesh), then writes them (or, without
/// an `output`, keeps them in their sums), with the fallback frame where nothing reached.
pub fn write_inherited(mesh: &Mesh, scratch: &mut Scratch, mut output: Option<&mut OutputPart>, report: &mut Report) {
    report.inherited_vertices = inherit::propagate(mesh, scratch);
    for v in 0..mesh.vertex_count() {
        if scratch.flags[v] & flag::DEFERRED == 0 {
            continue;
        }
        let normal = VertexNormal::new(mesh.normals.get(v)).unit;
        let sums = &mut scratch.sums[v];
        let (t, w) = if scratch.flags[v] & flag::RESOLVED != 0 {
            (Vec3::from_array(sums.primary), sums.weight)
        } else {
            report.fallback_vertices += 1;
            fallback(normal)
        };
        write_vertex(output.as_deref_mut(), sums, v, t, w, normal);
    }
}

/// Writes `(t, w)` and the bitangent `w * cross(n, t)`; without a usable normal, any unit vector
/// orthogonal to `t` stands in for `n`, so the bitangent is still a unit vector orthogonal to `t`.
/// Without an `output`, keeps `(t, w)` in the vertex's `sums`.
#[inline(always)]
fn write_vertex(
    output: Option<&mut OutputPart>,
    sums: &mut VertexSums,
    v: usize,
    t: Vec3,
    w: f32,
    normal: Option<Vec3>,
) {
    match output {
        Some(output) => output.write(v, t, w, normal.unwrap_or_else(|| fallback_tangent(t))),
        None => sums.keep_frame(t, w),
    }
}
