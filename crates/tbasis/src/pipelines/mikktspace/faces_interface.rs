//! mikktspace.c's own interface: faces of 3 or 4 vertices read through callbacks, quads split as
//! it splits them, and every output of `setTSpace` (tangent, bitangent, magnitudes, orientation).
//!
//! Each face vertex is a slot of its own (numbered face after face), carrying mikktspace.c's index
//! for it, `4 * face + vert` (`MakeIndex`); the triangles index the slots, and the triangle pipeline runs on them
//! ([`super::solve`]) with the three things quads add: the sub-group rule that joins a quad's two
//! triangles, the orientation one quad's triangles share, and the quad's slots its two triangles
//! both write (averaged, `AvgTSpace`), or that its degenerate triangle leaves to its good one.
#![forbid(unsafe_code)]

use core::cmp::Ordering;
use core::ops::Range;

use super::attributes::Attributes;
use super::frames::Arrays;
use super::tspace::{threshold_cosine, Full};
use super::{copy_to_degenerate, scratch_bytes, solve as solve_triangles, Buffers, FaceExtras, NONE};
use crate::kernel::error::Error;
use crate::kernel::memory::{vec_filled, vec_with_capacity, zeroed_bytes, Arena};
use crate::kernel::mesh::Mesh;
use crate::kernel::report::Report;
use crate::kernel::vector::{equal, Vec3};

/// A mesh as mikktspace.c's callbacks give it: each face's vertices, one slot per face vertex.
pub(crate) struct FaceMesh<'a> {
    /// Per slot.
    pub positions: &'a [Vec3],
    pub normals: &'a [Vec3],
    pub texcoords: &'a [[f32; 2]],
    /// Per face of 3 or 4 vertices: its number among all faces and its first slot (its slots
    /// run to the next one's first, or to the end).
    pub faces: &'a [(u32, u32)],
    /// Face 0's vertex 0's position when face 0 has neither 3 nor 4 vertices (see
    /// [`Attributes::index_zero`]).
    pub index_zero: Option<Vec3>,
}

/// Each face of `faces` (see [`FaceMesh::faces`]) with the range of its slots, `slot_count` in all.
pub(crate) fn face_slots(
    faces: &[(u32, u32)],
    slot_count: usize,
) -> impl Iterator<Item = (u32, Range<usize>)> + Clone + '_ {
    let ends = faces
        .iter()
        .skip(1)
        .map(|&(_, first)| first as usize)
        .chain([slot_count]);
    faces
        .iter()
        .zip(ends)
        .map(|(&(face, first), end)| (face, first as usize..end))
}

/// Per slot: its tangent space (`setTSpace`'s tangent, bitangent and magnitudes) and whether the
/// texture keeps the winding there (1) or mirrors it (0).
pub(crate) struct Spaces {
    pub spaces: Vec<Full>,
    pub preserving: Vec<u8>,
}

/// The largest slot count: slots, corners and mikktspace.c's indices stay clear of the sentinels.
const MAX_SLOTS: usize = (i32::MAX / 4) as usize;

/// Every slot's tangent space, bit for bit what mikktspace.c's `genTangSpace` gives.
pub(crate) fn solve(mesh: &FaceMesh, angular_threshold: f32, threads: u32) -> Result<Spaces, Error> {
    let slot_count = mesh.positions.len();
    if slot_count > MAX_SLOTS {
        return Err(Error::SizeOverflow);
    }
    // 1. The triangles, as mikktspace.c lists them (GenerateInitialVerticesIndexList).
    let triangles = Triangles::split(mesh)?;
    let corner_count = triangles.slots.len();

    // 2. The triangle pipeline on the slots, with the quads' rules (steps 3 to 9).
    let view = Mesh::new(mesh.positions, mesh.normals)
        .with_texcoords(mesh.texcoords)
        .with_indices(&triangles.slots[..]);
    let attributes = Attributes {
        mesh: &view,
        flip_v: false,
        corner_values: Some(&triangles.values),
        index_zero: mesh.index_zero,
    };
    let mut memory = zeroed_bytes(scratch_bytes(slot_count, corner_count).ok_or(Error::SizeOverflow)?)?;
    let mut buffers = Buffers::take(&mut Arena::Carve(&mut memory), slot_count, corner_count)?;
    buffers.welded.copy_from_slice(&triangles.slots);
    let mut corners: Vec<Full> = vec_filled(corner_count, Full::DEFAULT)?;
    let mut magnitudes = vec_filled(corner_count / 3, [0.0f32; 2])?;
    let mut write_order = vec_filled(corner_count, NONE)?;
    let mut extras = FaceExtras {
        face_of: &triangles.face_of,
        magnitudes: &mut magnitudes,
        threshold: threshold_cosine(angular_threshold),
        write_order: &mut write_order,
    };
    let mut report = Report::default();
    let solved = solve_triangles(
        &attributes,
        threads,
        &mut buffers,
        &mut corners,
        None,
        Some(&mut extras),
        &mut report,
    )?;

    // 3. Each slot takes its corner's space, or both corners' average where the two triangles
    //    of a quad meet, in the C's write order, with the orientation of the later write
    //    (GenerateTSpaces, AvgTSpace).
    //    Without quads, slots are corners: those no group reaches keep the initial space and
    //    orientation 0 (the scratch starts zeroed).
    let mut out = if slot_count == corner_count {
        let mut preserving = vec_with_capacity(slot_count)?;
        preserving.extend_from_slice(buffers.orientation);
        Spaces {
            spaces: corners,
            preserving,
        }
    } else {
        assemble_slots(&triangles, &buffers, solved.good, (&corners, &write_order), slot_count)?
    };

    // 4. Degenerate triangles copy a good corner's space (DegenEpilogue), except in a quad whose
    //    other triangle is good: there the slot the good one lacks copies the one of its slots
    //    at the same position.
    let mut degenerate: Vec<bool> = vec_filled(corner_count / 3, false)?;
    for &t in &buffers.order[solved.good..corner_count / 3] {
        degenerate[t as usize] = true;
    }
    let one_degenerate = |t: usize| {
        let partner = [t.wrapping_sub(1), t + 1]
            .into_iter()
            .find(|&p| p < degenerate.len() && triangles.face_of[p] == triangles.face_of[t]);
        partner.is_some_and(|p| degenerate[p] != degenerate[t])
    };
    let slot_of = |corner: usize| triangles.slots[corner] as usize;
    copy_to_degenerate(
        &mut buffers,
        &solved,
        &mut Arrays {
            spaces: &mut out.spaces,
            orientation: &mut out.preserving,
        },
        slot_of,
        one_degenerate,
        None,
    );
    for &t in buffers.order[..solved.good]
        .iter()
        .filter(|&&t| one_degenerate(t as usize))
    {
        let corners = 3 * t as usize..3 * t as usize + 3;
        let verts = [0, 1, 2].map(|k| (triangles.values[corners.start + k] % 4) as usize);
        let present = verts.iter().fold(0u32, |bits, &v| bits | 1 << v);
        let missing = [1, 2, 3].into_iter().find(|&v| present & (1 << v) == 0).unwrap_or(0);
        let first_slot = slot_of(corners.start) - verts[0];
        let target = mesh.positions[first_slot + missing];
        if let Some(&v) = verts.iter().find(|&&v| equal(mesh.positions[first_slot + v], target)) {
            let (from, to) = (first_slot + v, first_slot + missing);
            out.spaces[to] = out.spaces[from];
            out.preserving[to] = out.preserving[from];
        }
    }
    Ok(out)
}

/// Step 3 with quads: each slot from the one or two corners on it that a group reached, in the
/// order `GenerateTSpaces` writes them (`write_order`, per good corner): `AvgTSpace` keeps the
/// first space's bits when the two compare equal (a `-0` against a `+0` in one component), and
/// the orientation is the last one's.
fn assemble_slots(
    triangles: &Triangles,
    buffers: &Buffers,
    good: usize,
    (corners, write_order): (&[Full], &[u32]),
    slot_count: usize,
) -> Result<Spaces, Error> {
    let mut out = Spaces {
        spaces: vec_filled(slot_count, Full::DEFAULT)?,
        preserving: vec_filled(slot_count, 0u8)?,
    };
    // The write order of the corner a slot holds, while it holds one.
    let mut written: Vec<u32> = vec_filled(slot_count, NONE)?;
    for (g, (&t, groups)) in buffers.order[..good].iter().zip(&*buffers.assigned).enumerate() {
        for k in (0..3).filter(|&k| groups[k] != NONE) {
            let corner = 3 * t as usize + k;
            let slot = triangles.slots[corner] as usize;
            let write = (corners[corner], buffers.orientation[corner], write_order[3 * g + k]);
            (out.spaces[slot], out.preserving[slot]) = match written[slot] {
                NONE => (write.0, write.1),
                order => both_writes((out.spaces[slot], out.preserving[slot], order), write),
            };
            written[slot] = write.2;
        }
    }
    Ok(out)
}

/// What `GenerateTSpaces` leaves in a slot written twice, given the two writes (space,
/// orientation, write order) in either order: `AvgTSpace` of the first and the second, and the
/// second's orientation.
fn both_writes(a: (Full, u8, u32), b: (Full, u8, u32)) -> (Full, u8) {
    let (first, second) = if a.2 < b.2 { (a, b) } else { (b, a) };
    (first.0.average(second.0), second.1)
}

/// The triangles of the faces, in face order: per corner its slot and mikktspace.c's index, per
/// triangle its face.
struct Triangles {
    slots: Vec<u32>,
    values: Vec<u32>,
    face_of: Vec<u32>,
}

impl Triangles {
    /// Splits each quad along its shorter diagonal in texture space, or in position when those
    /// are equal (the 0-2 diagonal unless 1-3 is strictly shorter), as mikktspace.c does.
    fn split(mesh: &FaceMesh) -> Result<Triangles, Error> {
        let faces = face_slots(mesh.faces, mesh.positions.len());
        let triangle_count: usize = faces.clone().map(|(_, slots)| slots.len() - 2).sum();
        let mut triangles = Triangles {
            slots: vec_with_capacity(3 * triangle_count)?,
            values: vec_with_capacity(3 * triangle_count)?,
            face_of: vec_with_capacity(triangle_count)?,
        };
        for (face, slots) in faces {
            let squared = |a: Vec3, b: Vec3| {
                let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
                d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
            };
            let slot = |vert: usize| slots.start + vert;
            let uv = |vert: usize| {
                let [u, v] = mesh.texcoords[slot(vert)];
                [u, v, 1.0]
            };
            let split: &[[usize; 3]] = if slots.len() == 3 {
                &[[0, 1, 2]]
            } else {
                let (texture_02, texture_13) = (squared(uv(0), uv(2)), squared(uv(1), uv(3)));
                let p = |vert: usize| mesh.positions[slot(vert)];
                // A tie, or a NaN, goes to the positions; there 1-3 must be strictly shorter.
                let diagonal_02 = match texture_02.partial_cmp(&texture_13) {
                    Some(Ordering::Less) => true,
                    Some(Ordering::Greater) => false,
                    _ => squared(p(1), p(3)).partial_cmp(&squared(p(0), p(2))) != Some(Ordering::Less),
                };
                if diagonal_02 {
                    &[[0, 1, 2], [0, 2, 3]]
                } else {
                    &[[0, 1, 3], [1, 2, 3]]
                }
            };
            for verts in split {
                triangles.face_of.push(face);
                for &vert in verts {
                    triangles.slots.push(slot(vert) as u32);
                    triangles.values.push(4 * face + vert as u32);
                }
            }
        }
        Ok(triangles)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two spaces equal under `==` whose bits differ (a `-0` against a `+0`): the slot keeps the
    /// one written first, whichever order the triangles come in, and the last one's orientation.
    #[test]
    fn a_slot_written_twice_keeps_the_first_write_of_equal_spaces() {
        let space = |sign: f32| Full {
            s: [1.0, sign * 0.0, 0.0],
            t: [0.0, 1.0, 0.0],
            mag_s: 1.0,
            mag_t: 1.0,
        };
        let (plus, minus) = (space(1.0), space(-1.0));
        assert!(plus.average(minus).s[1].is_sign_positive() && minus.average(plus).s[1].is_sign_negative());
        for (a, b) in [((plus, 1, 7), (minus, 0, 9)), ((minus, 0, 9), (plus, 1, 7))] {
            let (kept, preserving) = both_writes(a, b);
            assert!(kept.s[1].is_sign_positive(), "the first write, order 7");
            assert_eq!(preserving, 0, "the last write's orientation");
        }
    }

    /// Past INT_MAX / 4 face vertices in all (mikktspace.c would take them), the call fails before
    /// it reads anything: the slots stay clear of the sentinels. The positions are fresh zero
    /// memory the test never touches, 6.4 GB of address space and no more pages than a few.
    #[test]
    fn more_than_int_max_over_4_face_vertices_are_refused() {
        let slots = MAX_SLOTS + 1;
        let Ok(mut bytes) = zeroed_bytes(slots * size_of::<Vec3>() + align_of::<Vec3>()) else {
            // A system that grants no such address space (strict overcommit, little memory).
            assert!(std::env::var_os("CI").is_none(), "6.4 GB of address space refused");
            eprintln!("more_than_int_max_over_4_face_vertices_are_refused: skipped: 6.4 GB of address space refused");
            return;
        };
        let positions: &[Vec3] = Arena::Carve(&mut bytes).take(slots).expect("carved");
        let mesh = FaceMesh {
            positions,
            normals: &[],
            texcoords: &[],
            faces: &[(0, 0)],
            index_zero: None,
        };
        assert_eq!(MAX_SLOTS, 536_870_911);
        assert!(matches!(solve(&mesh, 180.0, 1), Err(Error::SizeOverflow)));
    }
}
