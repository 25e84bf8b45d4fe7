//! The original listing (Lengyel 2001, `CalculateTangentArray`), operation for operation.
//!
//! Kept apart from the other kernels on purpose: every float operation here runs in the listing's
//! order, so policy LEGACY reproduces its bits, including the inf/NaN it writes when a triangle's
//! UV determinant is zero. Rust never fuses a multiply and an add, so no FMA changes a result.
#![forbid(unsafe_code)]

use glam::Vec3;

use crate::kernel::error::Error;
use crate::kernel::memory::{self, Arena, Place};
use crate::kernel::mesh::{Mesh, Output, OutputPart, PerIndexType, Target};
use crate::kernel::options::Options;
use crate::kernel::parallel;
use crate::kernel::report::Report;
use crate::kernel::sums::{self, count_flags, flag, slot_in, Scratch, VertexSums};
use crate::kernel::views::strided::Strided;

/// Bytes of working memory a call needs: the per-vertex sums (`tan1`, `tan2`) and flags,
/// `vertex_count * 29 + 3`. `None` on overflow.
pub(crate) fn memory_bytes(vertex_count: usize) -> Option<usize> {
    memory::vertex_arrays_bytes(vertex_count, 0, Place::Caller)
}

/// Writes every vertex's frame, or every corner its vertex's, into `target`.
pub(crate) fn generate(
    mesh: &Mesh,
    options: &Options,
    memory: &mut [u8],
    place: Place,
    target: Target,
    report: &mut Report,
) -> Result<(), Error> {
    // The listing has no adjacency: nothing is reserved apart.
    let mut no_links = Vec::new();
    let mut scratch = memory::vertex_arrays(&mut Arena::Carve(memory), mesh.vertex_count(), 0, place, &mut no_links)?;
    match target {
        Target::Vertices(output) => run(mesh, options, &mut scratch, Some(output), report),
        Target::Corners(tangents) => {
            run(mesh, options, &mut scratch, None, report)?;
            sums::write_corner_frames(mesh, options.threads, scratch.sums, tangents, |_, _| Ok(()))
        }
    }
}

/// Both loops of the listing, each vertex's frame written into `output` or, without one, kept in
/// its sums. With several workers, each takes a consecutive range of vertices and reads the
/// triangles that touch it, in triangle order, where the triangle order follows the vertex order
/// (elsewhere one worker does all).
fn run(
    mesh: &Mesh,
    options: &Options,
    scratch: &mut Scratch,
    output: Option<&mut Output>,
    report: &mut Report,
) -> Result<(), Error> {
    let Some(texcoords) = mesh.texcoords else {
        // Validation refuses policy LEGACY without texture coordinates.
        return Err(Error::MissingTexcoords {
            method: options.method,
            policy: options.degenerate_policy,
        });
    };
    let workers = parallel::worker_count(options.threads, mesh);
    let first_loop = |part: &mut Scratch, _: Option<&mut OutputPart>| accumulate(mesh, texcoords, options.flip_v, part);
    let mut found = sums::for_each_range(scratch, None, workers, first_loop, parallel::merge_results)?;
    count_flags(scratch.flags, &mut found);
    sums::for_each_range(
        scratch,
        output,
        workers,
        |part, out| resolve(mesh, part, out),
        |(), ()| (),
    );
    *report = found;
    Ok(())
}

/// First loop of the listing: per triangle, solve `[T B] = [Q1 Q2] * inverse([s1 t1; s2 t2])`
/// and add `sdir` (dP/du) to `tan1`, `tdir` (dP/dv) to `tan2` of its three vertices, in triangle
/// order, for the vertices `scratch` holds. Also checks every index, and counts the
/// zero-determinant or non-finite triangles whose first vertex it holds.
pub fn accumulate(
    mesh: &Mesh,
    texcoords: Strided<[f32; 2]>,
    flip_v: bool,
    scratch: &mut Scratch,
) -> Result<Report, Error> {
    let triangle_count = mesh.indices.triangle_count(mesh.vertex_count())?;
    let v_sign = if flip_v { -1.0 } else { 1.0 };
    let listing = Listing {
        mesh,
        texcoords,
        v_sign,
        triangle_count,
    };
    mesh.indices.with_corner_reader(FirstLoop { listing, scratch })
}

/// The inputs of the listing's first loop.
struct Listing<'m> {
    mesh: &'m Mesh<'m>,
    texcoords: Strided<'m, [f32; 2]>,
    v_sign: f32,
    triangle_count: usize,
}

/// The first loop into one worker's scratch.
struct FirstLoop<'m, 's, 'a> {
    listing: Listing<'m>,
    scratch: &'s mut Scratch<'a>,
}

impl PerIndexType for FirstLoop<'_, '_, '_> {
    type Output = Result<Report, Error>;

    /// A scratch holding every vertex (one worker) skips the test of whether it holds a corner.
    #[inline(always)]
    fn run(self, corners: impl Fn(usize) -> [usize; 3]) -> Result<Report, Error> {
        let FirstLoop { listing, scratch } = self;
        let vertex_count = listing.mesh.vertex_count();
        if scratch.first == 0 && scratch.flags.len() == vertex_count {
            let (sums, flags) = (&mut scratch.sums[..vertex_count], &mut scratch.flags[..vertex_count]);
            listing.sweep(sums, flags, corners, Some)
        } else {
            let (first, len) = (scratch.first, scratch.flags.len());
            let (sums, flags) = (&mut scratch.sums[..len], &mut scratch.flags[..len]);
            listing.sweep(sums, flags, corners, move |v| slot_in(v, first, len))
        }
    }
}

impl Listing<'_> {
    /// The triangles in order; `slot(v)` is where vertex `v` sits in `sums` and `flags`, if there.
    #[inline(always)]
    fn sweep(
        &self,
        sums: &mut [VertexSums],
        flags: &mut [u8],
        corners: impl Fn(usize) -> [usize; 3],
        slot: impl Fn(usize) -> Option<usize>,
    ) -> Result<Report, Error> {
        let mut report = Report::default();
        for a in 0..self.triangle_count {
            let [i1, i2, i3] = self.mesh.checked(corners(a))?;
            if [i1, i2, i3].iter().all(|&v| slot(v).is_none()) {
                continue;
            }
            let (sdir, tdir, orientation) = self.solve(i1, i2, i3);
            if orientation == 0 && slot(i1).is_some() {
                report.note_degenerate(a);
            }
            for v in [i1, i2, i3] {
                let Some(slot) = slot(v) else { continue };
                let vertex = &mut sums[slot];
                for k in 0..3 {
                    vertex.primary[k] += sdir[k];
                    vertex.secondary[k] += tdir[k];
                }
                flags[slot] |= flag::REFERENCED | orientation;
            }
        }
        Ok(report)
    }

    /// One triangle of the listing: `sdir`, `tdir`, and the orientation flag of its UV winding
    /// (0 when the determinant is zero or an edge is not finite).
    #[inline(always)]
    fn solve(&self, i1: usize, i2: usize, i3: usize) -> ([f32; 3], [f32; 3], u8) {
        let positions = self.mesh.positions;
        let (v1, v2, v3) = (positions.get(i1), positions.get(i2), positions.get(i3));
        let (w1, w2, w3) = (self.texcoords.get(i1), self.texcoords.get(i2), self.texcoords.get(i3));

        let x1 = v2[0] - v1[0];
        let x2 = v3[0] - v1[0];
        let y1 = v2[1] - v1[1];
        let y2 = v3[1] - v1[1];
        let z1 = v2[2] - v1[2];
        let z2 = v3[2] - v1[2];

        let s1 = w2[0] - w1[0];
        let s2 = w3[0] - w1[0];
        let t1 = (w2[1] - w1[1]) * self.v_sign;
        let t2 = (w3[1] - w1[1]) * self.v_sign;

        let det = s1 * t2 - s2 * t1;
        let r = 1.0f32 / det;
        let sdir = [
            (t2 * x1 - t1 * x2) * r,
            (t2 * y1 - t1 * y2) * r,
            (t2 * z1 - t1 * z2) * r,
        ];
        let tdir = [
            (s1 * x2 - s2 * x1) * r,
            (s1 * y2 - s2 * y1) * r,
            (s1 * z2 - s2 * z1) * r,
        ];

        // Without short-circuit: ten tests and no branch.
        let finite = [x1, x2, y1, y2, z1, z2, s1, s2, t1, t2]
            .iter()
            .fold(true, |all, x| all & x.is_finite());
        let orientation = if det == 0.0 || !finite {
            0
        } else if det > 0.0 {
            flag::POSITIVE_UV
        } else {
            flag::NEGATIVE_UV
        };
        (sdir, tdir, orientation)
    }
}

/// Second loop of the listing: `T' = normalize(t - n * dot(n, t))`,
/// `w = dot(cross(n, t), tan2) < 0 ? -1 : 1`. Without an `output` (the per-corner output) each
/// vertex keeps its frame in its sums instead.
pub fn resolve(mesh: &Mesh, scratch: &mut Scratch, mut output: Option<&mut OutputPart>) {
    for (slot, sums) in scratch.sums.iter_mut().enumerate() {
        let a = scratch.first + slot;
        let n = Vec3::from_array(mesh.normals.get(a));
        let t = Vec3::from_array(sums.primary);
        let tan2 = Vec3::from_array(sums.secondary);

        let orthogonal = t - n * dot(n, t);
        let tangent = orthogonal * (1.0 / dot(orthogonal, orthogonal).sqrt());
        let w = if dot(cross(n, t), tan2) < 0.0 { -1.0 } else { 1.0 };
        match output.as_deref_mut() {
            Some(output) => output.write(a, tangent, w, n),
            None => sums.keep_frame(tangent, w),
        }
    }
}

/// The listing's `Dot`: `x*x' + y*y' + z*z'`, summed left to right.
#[inline(always)]
fn dot(a: Vec3, b: Vec3) -> f32 {
    a.x * b.x + a.y * b.y + a.z * b.z
}

/// The listing's `Cross`.
#[inline(always)]
fn cross(a: Vec3, b: Vec3) -> Vec3 {
    Vec3::new(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::test_rng::TestRng;

    /// The orientation flag by its definition: zero when the UV determinant is zero or any of the
    /// ten edge components is not finite, else the determinant's sign.
    fn defined_orientation(v: [[f32; 3]; 3], w: [[f32; 2]; 3]) -> u8 {
        let edges = (0..3).flat_map(|k| [v[1][k] - v[0][k], v[2][k] - v[0][k]]);
        let uv = (0..2).flat_map(|k| [w[1][k] - w[0][k], w[2][k] - w[0][k]]);
        let finite = edges.chain(uv).all(f32::is_finite);
        let (s1, s2, t1, t2) = (
            w[1][0] - w[0][0],
            w[2][0] - w[0][0],
            w[1][1] - w[0][1],
            w[2][1] - w[0][1],
        );
        let det = s1 * t2 - s2 * t1;
        match (finite && det != 0.0, det > 0.0) {
            (false, _) => 0,
            (true, true) => flag::POSITIVE_UV,
            (true, false) => flag::NEGATIVE_UV,
        }
    }

    #[test]
    fn the_orientation_flag_follows_its_definition_on_hostile_values() {
        let palette = [
            0.0,
            -0.0,
            1.0,
            -2.5,
            3e38,
            -3e38,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            1e-45,
        ];
        let mut rng = TestRng(0x0B1E);
        let mut seen = [0usize; 3];
        for _ in 0..20_000 {
            let mut pick = || {
                if rng.chance(70) {
                    rng.unit() * 4.0 - 2.0
                } else {
                    palette[rng.below(palette.len())]
                }
            };
            let v: [[f32; 3]; 3] = core::array::from_fn(|_| core::array::from_fn(|_| pick()));
            let w: [[f32; 2]; 3] = core::array::from_fn(|_| core::array::from_fn(|_| pick()));
            let normals = [[0.0, 0.0, 1.0]; 3];
            let mesh = Mesh::new(&v[..], &normals[..]).with_texcoords(&w[..]);
            let listing = Listing {
                mesh: &mesh,
                texcoords: mesh.texcoords.unwrap(),
                v_sign: 1.0,
                triangle_count: 1,
            };
            let (_, _, orientation) = listing.solve(0, 1, 2);
            assert_eq!(
                orientation,
                defined_orientation(v, w),
                "positions {v:?}, texture coordinates {w:?}"
            );
            seen[usize::from(orientation / 2)] += 1;
        }
        // Every outcome occurs, each many times.
        assert!(seen.iter().all(|&n| n > 1000), "{seen:?}");
    }
}
