//! Per-triangle tangents for every policy but LEGACY, weighted per method and summed per vertex
//! by handedness.
#![forbid(unsafe_code)]

use core::ops::Range;
use core::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Barrier, Mutex, MutexGuard, PoisonError};

use glam::{Vec2, Vec3};

use crate::kernel::arc_cosine::acos_lanes;
use crate::kernel::degenerate::Shape;
use crate::kernel::error::Error;
use crate::kernel::frame::{is_well_scaled, length_and_direction, length_and_direction_fast};
use crate::kernel::index_bounds::{runs, IndexBounds};
use crate::kernel::lanes::{lane3, lanes_in_use, set_lane3, BatchReader, Lanes, TriangleBatch, LANES};
use crate::kernel::memory::vec_with_capacity;
use crate::kernel::mesh::Mesh;
use crate::kernel::options::{Method, Options};
use crate::kernel::report::Report;
use crate::kernel::sums::{flag, Scratch, VertexSums};
use crate::kernel::vector as mikk;
use crate::kernel::views::strided::Strided;
use crate::kernel::{parallel, simd};

/// Per-triangle results for one batch (a lane per triangle).
///
/// Both the UV and the position edges are divided by their largest component first: the quality
/// test and the 2x2 solve then work on numbers near 1 whatever the scale of the mesh or its UVs.
struct Faces {
    /// 1 when the triangle is measurable: finite, and UV and position quality at least the
    /// threshold; else 0. (Lane flags are `u32`: a byte per lane keeps the loop from compiling
    /// to SIMD.)
    valid: [u32; LANES],
    /// 1 when the fast path's lengths over- or underflowed: the lane is redone with
    /// [`length_and_direction`].
    careful: [u32; LANES],
    /// Direction of dP/du, unit length: mikktspace.c's where [`Faces::exact`] is 1.
    direction: [Lanes; 3],
    /// 1 when `direction` is mikktspace.c's unit dP/ds, bit for bit (see [`Faces::solve`]).
    exact: [u32; LANES],
    /// `|dP/du|`, kept apart from the direction so that neither overflows at extreme UV scales
    /// (UVs of 1e-20 give a length near 1e20, whose square no f32 holds).
    length: Lanes,
    /// Position edges `Q1`, `Q2` divided by their largest component.
    edges: [[Lanes; 3]; 2],
    /// `edges[0] x edges[1]`: the face normal the winding gives, its length twice the scaled area.
    face_normal: [Lanes; 3],
    /// `|edges[0] x edges[1]|`.
    twice_area: Lanes,
    /// The largest component of `Q1`, `Q2`, to undo the scaling of areas.
    position_scale: Lanes,
    /// The UV determinant (its sign: the UV triangle's winding).
    det: Lanes,
    /// How much of its weight the triangle keeps (see [`Shape::confidence`]).
    confidence: Lanes,
}

impl Faces {
    fn new() -> Self {
        Faces {
            valid: [0; LANES],
            careful: [0; LANES],
            direction: [[0.0; LANES]; 3],
            exact: [0; LANES],
            length: [0.0; LANES],
            edges: [[[0.0; LANES]; 3]; 2],
            face_normal: [[0.0; LANES]; 3],
            twice_area: [0.0; LANES],
            position_scale: [0.0; LANES],
            det: [0.0; LANES],
            confidence: [0.0; LANES],
        }
    }

    /// Solves `Q1 = s1 T + t1 B`, `Q2 = s2 T + t2 B` for `T` (Lengyel 2001) in every lane, and
    /// marks degenerate the lanes with a non-finite input or a UV or position quality below
    /// `threshold`.
    #[inline(always)]
    fn solve(&mut self, batch: &TriangleBatch, v_sign: f32, threshold: f32) {
        let flip_v = v_sign < 0.0;
        let [p0, p1, p2] = &batch.position;
        let [w0, w1, w2] = &batch.texcoord;
        for i in 0..lanes_in_use(batch.len) {
            let q1 = Vec3::new(p1[0][i] - p0[0][i], p1[1][i] - p0[1][i], p1[2][i] - p0[2][i]);
            let q2 = Vec3::new(p2[0][i] - p0[0][i], p2[1][i] - p0[1][i], p2[2][i] - p0[2][i]);
            let e1 = Vec2::new(w1[0][i] - w0[0][i], (w1[1][i] - w0[1][i]) * v_sign);
            let e2 = Vec2::new(w2[0][i] - w0[0][i], (w2[1][i] - w0[1][i]) * v_sign);
            let uv_scale = e1.abs().max(e2.abs()).max_element();
            let position_scale = q1.abs().max(q2.abs()).max_element();
            // Also false for NaN: a non-finite input makes the triangle degenerate.
            let measurable = (uv_scale > 0.0)
                & (uv_scale < f32::INFINITY)
                & (position_scale > 0.0)
                & (position_scale < f32::INFINITY);
            let (e1, e2) = (e1 * (1.0 / uv_scale), e2 * (1.0 / uv_scale));
            let (s1, s2) = (q1 * (1.0 / position_scale), q2 * (1.0 / position_scale));
            let det = e1.perp_dot(e2);
            let face_normal = s1.cross(s2);
            let uv_shape = Shape {
                twice_area: det.abs(),
                squared_edges: e1.length_squared() + e2.length_squared() + (e2 - e1).length_squared(),
            };
            let position_shape = Shape {
                twice_area: face_normal.length(),
                squared_edges: s1.length_squared() + s2.length_squared() + (s2 - s1).length_squared(),
            };
            // T = (t2 Q1 - t1 Q2) / det; with scaled UV edges, det = det' * uv_scale^2.
            let (numerator_length, direction, in_range) = length_and_direction_fast(q1 * e2.y - q2 * e1.y);
            let direction = direction * det.signum();
            let length = numerator_length / (det.abs() * uv_scale);

            // mikktspace.c's unit dP/ds (InitTriInfo, eq. 18) from the unscaled edges, V as given
            // or 1 - V, operation for operation, wherever its squared length stays well inside
            // f32's range and its orientation agrees: then a vertex sums exactly mikktspace.c's
            // terms ([`Corners::weigh_angle`]). Elsewhere the scaled solve above stands.
            let texture_v = |w: &[Lanes; 2]| if flip_v { 1.0 - w[1][i] } else { w[1][i] };
            let (t21x, t31x) = (w1[0][i] - w0[0][i], w2[0][i] - w0[0][i]);
            let (t21y, t31y) = (texture_v(w1) - texture_v(w0), texture_v(w2) - texture_v(w0));
            let signed_area = t21x * t31y - t21y * t31x;
            let os = mikk::sub(mikk::scale(t31y, q1.to_array()), mikk::scale(t21y, q2.to_array()));
            let squared = mikk::dot(os, os);
            let sign = if signed_area > 0.0 { 1.0 } else { -1.0 };
            let unit_os = mikk::scale(sign / squared.sqrt(), os);
            let exact = mikk::not_zero(signed_area) & ((signed_area > 0.0) == (det > 0.0)) & is_well_scaled(squared);
            let direction = if exact { Vec3::from_array(unit_os) } else { direction };

            let valid = measurable & uv_shape.at_least(threshold) & position_shape.at_least(threshold);
            self.valid[i] = u32::from(valid);
            self.exact[i] = u32::from(exact);
            self.careful[i] = u32::from(!(in_range & length.is_finite()));
            set_lane3(&mut self.direction, i, direction.to_array());
            set_lane3(&mut self.edges[0], i, s1.to_array());
            set_lane3(&mut self.edges[1], i, s2.to_array());
            set_lane3(&mut self.face_normal, i, face_normal.to_array());
            self.length[i] = length;
            self.twice_area[i] = position_shape.twice_area;
            self.position_scale[i] = position_scale;
            self.det[i] = det;
            self.confidence[i] = uv_shape.confidence();
        }
        for i in 0..batch.len {
            if self.valid[i] & self.careful[i] != 0 {
                self.solve_carefully(batch, i, v_sign);
            }
        }
    }

    /// Lane `i` again, its dP/du from [`length_and_direction`], which survives any finite scale
    /// (the direction stays mikktspace.c's where that one held); degenerate if even that length
    /// is not finite.
    #[cold]
    fn solve_carefully(&mut self, batch: &TriangleBatch, i: usize, v_sign: f32) {
        let corner = |k: usize| {
            Vec3::new(
                batch.position[k][0][i],
                batch.position[k][1][i],
                batch.position[k][2][i],
            )
        };
        let uv = |k: usize| Vec2::new(batch.texcoord[k][0][i], batch.texcoord[k][1][i] * v_sign);
        let (q1, q2) = (corner(1) - corner(0), corner(2) - corner(0));
        let (e1, e2) = (uv(1) - uv(0), uv(2) - uv(0));
        let uv_scale = e1.abs().max(e2.abs()).max_element();
        let (e1, e2) = (e1 * (1.0 / uv_scale), e2 * (1.0 / uv_scale));
        let det = self.det[i];
        let solved = length_and_direction(q1 * e2.y - q2 * e1.y)
            .map(|(numerator_length, direction)| (numerator_length / (det.abs() * uv_scale), direction))
            .filter(|(length, _)| length.is_finite());
        let Some((length, direction)) = solved else {
            self.valid[i] = 0;
            return;
        };
        if self.exact[i] == 0 {
            set_lane3(&mut self.direction, i, (direction * det.signum()).to_array());
        }
        self.length[i] = length;
    }
}

/// Each corner's handedness for one batch: which of its vertex's sums the corner adds to.
struct Sides {
    /// 1 for a right-handed corner, else 0 (`u32` for the reason [`Faces::valid`] gives).
    right_handed: [[u32; LANES]; 3],
}

impl Sides {
    fn new() -> Self {
        Sides {
            right_handed: [[0; LANES]; 3],
        }
    }

    /// A corner is right-handed when its triangle's UV determinant is positive, unless its vertex
    /// normal faces away from the winding, which turns the frame's handedness; a non-finite normal
    /// says nothing about it.
    #[inline(always)]
    fn classify(&mut self, faces: &Faces, batch: &TriangleBatch) {
        for k in 0..3 {
            for i in 0..lanes_in_use(batch.len) {
                let normal = lane3(&batch.normal[k], i);
                let facing_away = normal.is_finite() & (normal.dot(lane3(&faces.face_normal, i)) < 0.0);
                self.right_handed[k][i] = u32::from((faces.det[i] > 0.0) != facing_away);
            }
        }
    }
}

/// Corner `k`'s contributions for one batch: the tangent times its weight, and the weight.
struct Corners {
    tangent: [[Lanes; 3]; 3],
    weight: [Lanes; 3],
}

impl Corners {
    fn new() -> Self {
        Corners {
            tangent: [[[0.0; LANES]; 3]; 3],
            weight: [[0.0; LANES]; 3],
        }
    }

    /// What each corner adds to its vertex (normal `n`).
    ///
    /// LENGYEL adds the unnormalized dP/du, so long or stretched triangles dominate; ANGLE adds
    /// mikktspace.c's term ([`Corners::weigh_angle`]); AREA and UNIFORM add the unit face tangent
    /// weighted by area or by 1 (per-face averaging). Every weight is scaled by the triangle's
    /// confidence.
    #[inline(always)]
    fn weigh(&mut self, method: Method, faces: &Faces, batch: &TriangleBatch) {
        let lanes = lanes_in_use(batch.len);
        if matches!(method, Method::Angle | Method::Mikktspace) {
            self.weigh_angle(faces, batch, lanes);
            return;
        }
        // One loop per case, with nothing to decide inside: each compiles to SIMD (its closure
        // forced inline: a call per lane would keep the loop scalar).
        for k in 0..3 {
            match method {
                Method::Lengyel => self.set(
                    k,
                    lanes,
                    #[inline(always)]
                    |i| (lane3(&faces.direction, i), faces.length[i]),
                    faces,
                ),
                // ANGLE is weighed above; MIKKTSPACE has its own module and never comes here.
                Method::Angle | Method::Mikktspace => {}
                Method::Area => self.set(
                    k,
                    lanes,
                    #[inline(always)]
                    |i| {
                        let scale = faces.position_scale[i];
                        (lane3(&faces.direction, i), 0.5 * faces.twice_area[i] * scale * scale)
                    },
                    faces,
                ),
                Method::Uniform => self.set(
                    k,
                    lanes,
                    #[inline(always)]
                    |i| (lane3(&faces.direction, i), 1.0),
                    faces,
                ),
            }
        }
    }

    /// ANGLE: mikktspace.c's term per corner (EvalTspace): the face tangent projected into the
    /// tangent plane of the vertex normal and normalized, weighted by the corner angle between the
    /// corner's two edges, themselves projected into that plane and normalized,
    /// `(float)acos((double)cos)`. A vertex whose triangles all have [`Faces::exact`] directions
    /// and confidence 1 thus sums exactly what mikktspace.c sums for it. A corner whose normal is
    /// not unit length within 1e-3 (or not finite), or whose edges are far from unit scale, is
    /// weighed by the scale-free [`angle_corner`] instead.
    #[inline(always)]
    fn weigh_angle(&mut self, faces: &Faces, batch: &TriangleBatch, lanes: usize) {
        let mut tangents = [[[0.0; LANES]; 3]; 3];
        let mut cosines = [[0.0; LANES]; 3];
        let mut angles = [[0.0; LANES]; 3];
        let mut careful = [[0u32; LANES]; 3];
        let in_range = |e: mikk::Vec3| is_well_scaled(mikk::dot(e, e));
        for k in 0..3 {
            let (next, previous) = ((k + 1) % 3, (k + 2) % 3);
            for i in 0..lanes {
                let n = lane3(&batch.normal[k], i).to_array();
                let position = |c: usize| lane3(&batch.position[c], i).to_array();
                let (e1, e2) = (
                    mikk::sub(position(previous), position(k)),
                    mikk::sub(position(next), position(k)),
                );
                let tangent = mikk::project_normalized(lane3(&faces.direction, i).to_array(), n);
                let cos = mikk::projected_cosine(e1, e2, n);
                let n_squared = mikk::dot(n, n);
                let usable = (0.998..=1.002).contains(&n_squared) & in_range(e1) & in_range(e2);
                careful[k][i] = u32::from(!usable);
                cosines[k][i] = cos;
                set_lane3(&mut tangents[k], i, tangent);
            }
            acos_lanes(&cosines[k], &mut angles[k], lanes);
        }
        for (k, careful) in careful.iter().enumerate() {
            for i in (0..lanes).filter(|&i| careful[i] != 0) {
                let edges = |a: Vec3, b: Vec3| match k {
                    0 => (a, b),
                    1 => (b - a, -a),
                    _ => (-b, a - b),
                };
                let (tangent, angle) = angle_corner(faces, &batch.normal[k], i, edges);
                set_lane3(&mut tangents[k], i, tangent.to_array());
                angles[k][i] = angle;
            }
        }
        for k in 0..3 {
            self.set(
                k,
                lanes,
                #[inline(always)]
                |i| (lane3(&tangents[k], i), angles[k][i]),
                faces,
            );
        }
    }

    /// Stores corner `k`'s `tangent * weight` and weight, from the method's `(tangent, weight)`
    /// scaled by the triangle's confidence.
    #[inline(always)]
    fn set(&mut self, k: usize, lanes: usize, corner: impl Fn(usize) -> (Vec3, f32), faces: &Faces) {
        for i in 0..lanes {
            let (tangent, weight) = corner(i);
            let weight = weight * faces.confidence[i];
            let tangent = tangent * weight;
            set_lane3(&mut self.tangent[k], i, tangent.to_array());
            self.weight[k][i] = weight;
        }
    }
}

/// ANGLE at one corner the scale-free way, for the corners [`Corners::weigh_angle`] cannot weigh
/// in mikktspace.c's arithmetic: the face tangent projected into the vertex's tangent plane, and
/// the angle between the corner's edges `edges(Q1', Q2')` projected into that plane too (on coarse
/// meshes the plane angle, not the 3D one, is what the tangent plane around the vertex holds).
///
/// No projection is formed: projecting along `n` keeps an edge's triple product with `n`, so the
/// projected edges `e1'`, `e2'` have `|e1' x e2'| = |F . n| / |n|` with `F = e1 x e2` the face
/// normal, and `e1' . e2' = e1 . e2 - (n . e1)(n . e2) / |n|^2`. A zero, non-finite or extreme
/// normal keeps the 3D angle.
#[inline(always)]
fn angle_corner(
    faces: &Faces,
    normals: &[Lanes; 3],
    i: usize,
    edges: impl Fn(Vec3, Vec3) -> (Vec3, Vec3),
) -> (Vec3, f32) {
    let (e1, e2) = edges(lane3(&faces.edges[0], i), lane3(&faces.edges[1], i));
    let n = lane3(normals, i);
    let n_squared = n.length_squared();
    let inverse = 1.0 / n_squared;
    let plane_sin = lane3(&faces.face_normal, i).dot(n).abs() * inverse.sqrt();
    let plane_cos = e1.dot(e2) - n.dot(e1) * n.dot(e2) * inverse;
    // Normals far from unit length (beyond 1e-15..1e15) would lose the angle to underflow.
    let in_plane = (n_squared > 1e-30)
        & (n_squared < 1e30)
        & (plane_sin.abs() < f32::INFINITY)
        & (plane_cos.abs() < f32::INFINITY);
    // A select on the bits: the lane loop stays SIMD.
    let keep = 0u32.wrapping_sub(u32::from(in_plane));
    let select = |plane: f32, space: f32| f32::from_bits((plane.to_bits() & keep) | (space.to_bits() & !keep));
    let (sin, cos) = (select(plane_sin, faces.twice_area[i]), select(plane_cos, e1.dot(e2)));
    (project(lane3(&faces.direction, i), n), atan2_upper(sin, cos))
}

/// `T - N (N.T) / (N.N)`, normalized (zero when nothing is left): the projection needs no unit
/// normal; a zero or non-finite normal leaves `T` as it is.
#[inline(always)]
fn project(direction: Vec3, normal: Vec3) -> Vec3 {
    let n_squared = normal.length_squared();
    let usable = (n_squared > 0.0) & n_squared.is_finite();
    let projected = direction - normal * (normal.dot(direction) / n_squared);
    let projected = if usable { projected } else { direction };
    let inverse_length = 1.0 / projected.length();
    if inverse_length.is_finite() & (inverse_length > 0.0) {
        projected * inverse_length
    } else {
        Vec3::ZERO
    }
}

/// The interior angle at a corner is `atan2(|e1 x e2|, e1 . e2)`, accurate for small and obtuse
/// angles alike; `|e1 x e2|` is the same at every corner (twice the area).
///
/// `atan2(y, x)` for `y >= 0`, within 2e-6 radians: ample for a weight, and far cheaper than libm.
///
/// The octant is folded onto `atan(a)` with `a = min/max` in [0, 1], where an odd polynomial of
/// degree 11 (a minimax fit, maximum error 1.7e-6) stands in for it.
#[inline(always)]
fn atan2_upper(y: f32, x: f32) -> f32 {
    const C: [f32; 6] = [
        0.999_977_2,
        -0.332_622_86,
        0.193_540_4,
        -0.116_426_39,
        0.052_647_17,
        -0.011_719_046,
    ];
    let ax = x.abs();
    let (small, large) = if y <= ax { (y, ax) } else { (ax, y) };
    let a = small / large;
    let s = a * a;
    let atan = a * (C[0] + s * (C[1] + s * (C[2] + s * (C[3] + s * (C[4] + s * C[5])))));
    let first_quadrant = if y > ax {
        core::f32::consts::FRAC_PI_2 - atan
    } else {
        atan
    };
    let angle = if x < 0.0 {
        core::f32::consts::PI - first_quadrant
    } else {
        first_quadrant
    };
    if large > 0.0 {
        angle
    } else {
        0.0
    }
}

/// What corner `k` of a triangle adds to its vertex (24 bytes: the chunked sums keep many).
#[derive(Clone, Copy, Default)]
struct CornerTerm {
    /// The vertex, where [`accumulate_in_chunks`] keeps it (below 2^32 vertices).
    vertex: u32,
    /// `tangent * weight`, and the weight.
    tangent: [f32; 3],
    weight: f32,
    /// The flag bits it sets on its vertex.
    flags: u8,
    /// The sums it adds to: [`PRIMARY`] (right-handed), [`SECONDARY`], or [`NONE`] (a degenerate
    /// triangle, which only marks its vertices used).
    side: u8,
}

/// [`CornerTerm::side`] values.
const NONE: u8 = 0;
const PRIMARY: u8 = 1;
const SECONDARY: u8 = 2;

impl CornerTerm {
    /// Adds the term to its vertex's sums and flags.
    #[inline(always)]
    fn add_to(&self, sums: &mut VertexSums, flags: &mut u8) {
        let first = *flags & (flag::POSITIVE_UV | flag::NEGATIVE_UV) == 0;
        *flags |= self.flags;
        let side = match self.side {
            PRIMARY => &mut sums.primary,
            SECONDARY => {
                if first {
                    *flags |= flag::FIRST_LEFT;
                }
                &mut sums.secondary
            }
            _ => return,
        };
        for (sum, tangent) in side.iter_mut().zip(self.tangent) {
            *sum += tangent;
        }
        sums.weight += self.weight;
    }
}

/// Measures the triangles of `triangles` whose vertices `keep` accepts and calls
/// `visit(t, k, v, term)` for corner `k` (vertex `v`) of each triangle `t`, in triangle order: the tangent split
/// by the corner's handedness (the UV orientation relative to the vertex normal), so that a vertex
/// on a mirror fold can keep one side's frame instead of a cancelled sum.
///
/// Per-triangle and per-corner arithmetic runs a batch of triangles at a time, lane by lane.
/// Where the triangles jump around the vertex arrays ([`BatchReader::asks_ahead`]), each batch
/// goes to `ahead` before its arithmetic, so that what `visit` will touch can be asked for.
#[inline(always)]
fn measure(
    mesh: &Mesh,
    texcoords: Strided<[f32; 2]>,
    options: &Options,
    triangles: Range<usize>,
    keep: impl Fn(&[usize; 3]) -> bool,
    ahead: impl Fn(&TriangleBatch),
    mut visit: impl FnMut(usize, usize, usize, CornerTerm),
) -> Result<(), Error> {
    let v_sign = if options.flip_v { -1.0 } else { 1.0 };
    let mut reader = BatchReader::new(mesh, texcoords, triangles, keep, true);
    // Each in its own let, so that the 16 KiB of lanes are built in place rather than moved.
    let mut batch = TriangleBatch::new();
    let mut faces = Faces::new();
    let mut sides = Sides::new();
    let mut corners = Corners::new();
    while reader.fill(&mut batch)? {
        if reader.asks_ahead() {
            ahead(&batch);
        }
        faces.solve(&batch, v_sign, options.degenerate_threshold);
        sides.classify(&faces, &batch);
        corners.weigh(options.method, &faces, &batch);
        for lane in 0..batch.len {
            let t = batch.triangle[lane];
            if faces.valid[lane] == 0 {
                for (k, corner) in batch.vertex.iter().enumerate() {
                    let flags = flag::REFERENCED;
                    visit(
                        t,
                        k,
                        corner[lane],
                        CornerTerm {
                            flags,
                            ..CornerTerm::default()
                        },
                    );
                }
                continue;
            }
            let orientation = if faces.det[lane] > 0.0 {
                flag::POSITIVE_UV
            } else {
                flag::NEGATIVE_UV
            };
            for (k, corner) in batch.vertex.iter().enumerate() {
                let tangent = &corners.tangent[k];
                let term = CornerTerm {
                    tangent: [tangent[0][lane], tangent[1][lane], tangent[2][lane]],
                    weight: corners.weight[k][lane],
                    flags: flag::REFERENCED | orientation,
                    side: if sides.right_handed[k][lane] != 0 {
                        PRIMARY
                    } else {
                        SECONDARY
                    },
                    ..CornerTerm::default()
                };
                visit(t, k, corner[lane], term);
            }
        }
    }
    Ok(())
}

/// Adds each triangle's corner terms ([`measure`]) to the vertices `scratch` holds, one triangle
/// at a time, in triangle order; with `bounds`, only the blocks of triangles with a vertex it
/// holds are read. Degenerate triangles only mark their vertices used, and are counted where
/// `scratch` holds their first vertex.
#[inline(always)]
pub fn accumulate(
    mesh: &Mesh,
    options: &Options,
    scratch: &mut Scratch,
    bounds: Option<&IndexBounds>,
) -> Result<Report, Error> {
    let Some(texcoords) = mesh.texcoords else {
        return mark_referenced(mesh, scratch);
    };
    let mut report = Report::default();
    let owned = scratch.first..scratch.first + scratch.flags.len();
    let all = 0..mesh.indices.triangle_count(mesh.vertex_count())?;
    let keep = |corners: &[usize; 3]| corners.iter().any(|v| owned.contains(v));
    let ahead = SumsAhead::of(scratch);
    for triangles in runs(bounds, all, owned.clone()) {
        measure(
            mesh,
            texcoords,
            options,
            triangles,
            keep,
            |batch| ahead.batch(batch),
            |t, k, v, term| {
                let Some(slot) = scratch.slot(v) else {
                    return;
                };
                if k == 0 && term.side == NONE {
                    report.note_degenerate(t);
                }
                term.add_to(&mut scratch.sums[slot], &mut scratch.flags[slot]);
            },
        )?;
    }
    Ok(report)
}

/// Triangles per chunk of [`accumulate_in_chunks`]: the workers wait for one another once per
/// chunk, and a chunk's corner terms (0.6 MB) stay in the cache until they are added (on the
/// benchmark asset, two workers took longest with 1024 and with 16384 of the sizes from 1024 to
/// 65536, least with 8192). Unit tests cut small meshes into several chunks too.
const CHUNK_TRIANGLES: usize = if cfg!(test) { 8 } else { 8 * 1024 };

/// How many terms ahead [`accumulate_in_chunks`] asks for the sums a term is added to.
const PREFETCH_TERMS: usize = 16;

/// Asks for vertices' sums and flags before their terms are added. Where the triangles jump
/// around the vertex arrays, each addition would otherwise wait for memory: on FlightHelmet.cc1
/// the line that adds a term took over a quarter of a call's samples (`docs/speed-goals.md`).
#[derive(Clone, Copy)]
struct SumsAhead {
    sums: simd::Addresses,
    flags: simd::Addresses,
    first: usize,
}

impl SumsAhead {
    fn of(scratch: &Scratch) -> Self {
        SumsAhead {
            sums: simd::Addresses::of(scratch.sums),
            flags: simd::Addresses::of(scratch.flags),
            first: scratch.first,
        }
    }

    /// Vertex `v`'s, if the scratch holds it.
    #[inline(always)]
    fn vertex(self, v: usize) {
        let slot = v.wrapping_sub(self.first);
        self.sums.prefetch(slot);
        self.flags.prefetch(slot);
    }

    /// Those of every corner of `batch`, before its arithmetic: they are there when its terms are
    /// added.
    #[inline(always)]
    fn batch(self, batch: &TriangleBatch) {
        for &v in batch.vertex.iter().flat_map(|corner| &corner[..batch.len]) {
            self.vertex(v);
        }
    }
}

/// `lists` lists of corner terms, each with room for `room` terms, or [`Error::OutOfMemory`].
fn term_lists(lists: usize, room: usize) -> Result<Vec<Mutex<Vec<CornerTerm>>>, Error> {
    let mut all = Vec::new();
    all.try_reserve_exact(lists).map_err(|_| Error::OutOfMemory)?;
    for _ in 0..lists {
        all.push(Mutex::new(vec_with_capacity(room)?));
    }
    Ok(all)
}

/// A term list, whatever a panicking worker left in it (a panic is passed on after every worker).
fn lock(list: &Mutex<Vec<CornerTerm>>) -> MutexGuard<'_, Vec<CornerTerm>> {
    list.lock().unwrap_or_else(PoisonError::into_inner)
}

/// [`accumulate`] on several workers whatever the mesh's vertex order, with the same bits:
/// `scratch` is cut into the consecutive vertex ranges ending at `ends`, one per worker. Each
/// worker measures a consecutive range of each chunk of triangles, keeping each corner's term in
/// a list for the part that holds its vertex; in the next round each part adds its lists, from
/// the first range to the last, so that every vertex still adds its terms in triangle order. The
/// first range of a chunk follows everything its part has added, so the first worker adds its own
/// part's terms at once.
/// Round `r` adds chunk `r - 1` and measures chunk `r`; the workers run side by side from the
/// first round to the last, and wait for one another between rounds. When their threads cannot
/// all be started, one worker does everything.
///
/// Memory: two sets (the lists being filled and those being added) of `workers * workers` lists,
/// reserved fallibly before any round; with two workers each list has room for every corner of
/// its worker's share of a chunk, so no list ever grows. With more, a list that fills up grows
/// fallibly too. Any failure is [`Error::OutOfMemory`], before any output is written.
pub fn accumulate_in_chunks(
    mesh: &Mesh,
    options: &Options,
    scratch: &mut Scratch,
    ends: &[usize],
) -> Result<Report, Error> {
    let Some(texcoords) = mesh.texcoords else {
        let mark = |mut part: Scratch| mark_referenced(mesh, &mut part);
        return parallel::run_folded(scratch.split(ends), mark, parallel::merge_results)
            .unwrap_or(Ok(Report::default()));
    };
    let workers = ends.len();
    let triangle_count = mesh.indices.triangle_count(mesh.vertex_count())?;
    // Room for a range's terms in each list, more than its share (a list grows only when one
    // part holds most of a range's vertices), and never more than every corner of the range.
    let most = 3 * CHUNK_TRIANGLES.div_ceil(workers);
    let room = (2 * 3 * CHUNK_TRIANGLES / (workers * workers)).min(most);
    // Round `r` fills set `r % 2` and adds the other; in each, list `w * workers + d` holds the
    // terms worker `w` measured for part `d`.
    let sets = [
        term_lists(workers * workers, room)?,
        term_lists(workers * workers, room)?,
    ];
    let rounds = triangle_count.div_ceil(CHUNK_TRIANGLES) + 1;
    let (barrier, failed) = (Barrier::new(workers), AtomicBool::new(false));
    let worker = |(d, mut part): (usize, Scratch)| -> Result<Report, Error> {
        let mut lockstep = parallel::Lockstep::new(&barrier, rounds);
        // The lists this worker fills in a round, taken out of their places meanwhile.
        let mut own: [Vec<CornerTerm>; parallel::MAX_RANGES] = [const { Vec::new() }; parallel::MAX_RANGES];
        let own = &mut own[..workers];
        let mut report = Report::default();
        for round in 0..rounds {
            // After a failure the others only wait out the rounds.
            if !failed.load(Ordering::Relaxed) {
                let (filling, adding) = (&sets[round % 2], &sets[(round + 1) % 2]);
                let ahead = SumsAhead::of(&part);
                for w in 0..workers {
                    let list = lock(&adding[w * workers + d]);
                    for (i, term) in list.iter().enumerate() {
                        // The terms' vertices jump around (else the workers would split the
                        // vertices instead): each asks for a later one's sums.
                        if let Some(later) = list.get(i + PREFETCH_TERMS) {
                            ahead.vertex(later.vertex as usize);
                        }
                        let slot = term.vertex as usize - part.first;
                        term.add_to(&mut part.sums[slot], &mut part.flags[slot]);
                    }
                }
                let places = &filling[d * workers..(d + 1) * workers];
                for (list, place) in own.iter_mut().zip(places) {
                    *list = core::mem::take(&mut *lock(place));
                    list.clear();
                }
                let chunk =
                    (round * CHUNK_TRIANGLES).min(triangle_count)..((round + 1) * CHUNK_TRIANGLES).min(triangle_count);
                let at = |w: usize| chunk.start + chunk.len() * w / workers;
                // The first range of a chunk follows every term its part has added so far: the
                // first worker adds its own part's terms at once.
                let first_part = (d == 0).then_some(&mut part);
                // Forced inline, here and in `measure_into_lists`: a closure the compiler leaves
                // out of line is compiled for the baseline only.
                let measured = simd::run(
                    #[inline(always)]
                    || {
                        let sinks = TermSinks {
                            ends,
                            lists: own,
                            first_part,
                            room,
                        };
                        measure_into_lists(mesh, texcoords, options, at(d)..at(d + 1), sinks)
                    },
                );
                for (list, place) in own.iter_mut().zip(places) {
                    *lock(place) = core::mem::take(list);
                }
                match measured {
                    Ok(found) => report.merge(&found),
                    Err(error) => {
                        failed.store(true, Ordering::Relaxed);
                        return Err(error);
                    }
                }
            }
            lockstep.end_round();
        }
        Ok(report)
    };
    match parallel::run_together(scratch.split(ends).enumerate(), worker, parallel::merge_results) {
        Some(outcome) => outcome,
        None => simd::run(
            #[inline(always)]
            || accumulate(mesh, options, scratch, None),
        ),
    }
}

/// Where [`measure_into_lists`] puts each corner term: the list of its vertex's part (the parts'
/// vertex ranges end at `ends`), which grows by `room` terms when full, or, for the first part
/// when it is given, that part's sums at once.
struct TermSinks<'l, 's, 'a> {
    ends: &'l [usize],
    lists: &'l mut [Vec<CornerTerm>],
    first_part: Option<&'s mut Scratch<'a>>,
    room: usize,
}

/// Measures `triangles` ([`measure`]) into `sinks`.
#[inline(always)]
fn measure_into_lists(
    mesh: &Mesh,
    texcoords: Strided<[f32; 2]>,
    options: &Options,
    triangles: Range<usize>,
    sinks: TermSinks,
) -> Result<Report, Error> {
    let TermSinks {
        ends,
        lists,
        mut first_part,
        room,
    } = sinks;
    let (mut found, mut out_of_memory) = (Report::default(), false);
    let everything = |_: &[usize; 3]| true;
    let ahead = first_part.as_deref().map(SumsAhead::of);
    measure(
        mesh,
        texcoords,
        options,
        triangles,
        everything,
        |batch| {
            if let Some(ahead) = ahead {
                ahead.batch(batch);
            }
        },
        #[inline(always)]
        |t, k, v: usize, term: CornerTerm| {
            if k == 0 && term.side == NONE {
                found.note_degenerate(t);
            }
            let term = CornerTerm {
                vertex: v as u32,
                ..term
            };
            let part = ends.partition_point(|&end| end <= v);
            if let Some(first) = first_part.as_deref_mut().filter(|_| part == 0) {
                let slot = v - first.first;
                term.add_to(&mut first.sums[slot], &mut first.flags[slot]);
                return;
            }
            let list = &mut lists[part];
            if list.len() == list.capacity() && list.try_reserve(room.max(1)).is_err() {
                out_of_memory = true;
                return;
            }
            list.push(term);
        },
    )?;
    if out_of_memory {
        return Err(Error::OutOfMemory);
    }
    Ok(found)
}

/// Calls `visit(t, k, v, right_handed)` for corner `k` (vertex `v`) of each non-degenerate
/// triangle `t` in `triangles` whose vertices `keep` accepts, in triangle order: the handedness
/// [`accumulate`] added that corner with, computed the same way. Without texture coordinates no
/// triangle is measured and nothing is visited.
pub fn visit_corner_sides(
    mesh: &Mesh,
    options: &Options,
    triangles: core::ops::Range<usize>,
    keep: impl Fn(&[usize; 3]) -> bool,
    mut visit: impl FnMut(usize, usize, usize, bool),
) -> Result<(), Error> {
    let Some(texcoords) = mesh.texcoords else {
        return Ok(());
    };
    let v_sign = if options.flip_v { -1.0 } else { 1.0 };
    let mut reader = BatchReader::new(mesh, texcoords, triangles, keep, true);
    let mut batch = TriangleBatch::new();
    let mut faces = Faces::new();
    let mut sides = Sides::new();
    while reader.fill(&mut batch)? {
        faces.solve(&batch, v_sign, options.degenerate_threshold);
        sides.classify(&faces, &batch);
        for lane in (0..batch.len).filter(|&lane| faces.valid[lane] != 0) {
            for k in 0..3 {
                visit(
                    batch.triangle[lane],
                    k,
                    batch.vertex[k][lane],
                    sides.right_handed[k][lane] != 0,
                );
            }
        }
    }
    Ok(())
}

/// Without texture coordinates nothing is measured: the triangles only mark their vertices used.
fn mark_referenced(mesh: &Mesh, scratch: &mut Scratch) -> Result<Report, Error> {
    for t in 0..mesh.indices.triangle_count(mesh.vertex_count())? {
        for v in mesh.checked_triangle(t)? {
            if let Some(slot) = scratch.slot(v) {
                scratch.flags[slot] |= flag::REFERENCED;
            }
        }
    }
    Ok(Report::default())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomial_atan2_is_within_2e6_of_libm_over_the_upper_half_plane() {
        let mut worst = 0.0f32;
        for i in 0..=20_000 {
            let angle = core::f32::consts::PI * i as f32 / 20_000.0;
            for length in [1e-3f32, 1.0, 7.5e3] {
                let (y, x) = (angle.sin().abs() * length, angle.cos() * length);
                worst = worst.max((atan2_upper(y, x) - y.atan2(x)).abs());
            }
        }
        assert!(worst <= 2e-6, "worst error {worst}");
        assert_eq!(atan2_upper(0.0, 0.0), 0.0);
    }
}
