//! `tbasis_calculate_tangent_array`, the listing's own signature (packed arrays, `long` counts),
//! and the C port of the listing both calls are checked against.

use core::ffi::c_long;
use core::ptr;

use crate::ffi::*;
use crate::status::*;

use arbitrary::{Arbitrary, Result, Unstructured};

use crate::arena::{bit, fill_vectors, first_change_outside, vec_at, Buf};
use crate::describe;
use crate::frames::same;
use crate::input::{below, index_value, nudge, one_in, pick_encoding, shuffle, weighted, Attribute};
use crate::listing::listing_tangents;
use crate::plan::SMALL_VERTICES;
use crate::statuses::{check_status, Expect};

/// Bytes of the arena of a `tbasis_calculate_tangent_array` call.
const LISTING_ARENA: usize = 4 * 1024;

/// Lengyel's `CalculateTangentArray` (2001) as the C port `c_tests/listing.c` computes it (linked
/// by `fuzz/build.rs`, built with `-ffp-contract=off`), on packed copies of the inputs.
pub fn listing(
    vertex_count: usize,
    triangles: &[[usize; 3]],
    position: impl Fn(usize) -> [f32; 3],
    normal: impl Fn(usize) -> [f32; 3],
    texcoord: impl Fn(usize) -> [f32; 2],
) -> Vec<[f32; 4]> {
    let mut tangents = vec![[0.0f32; 4]; vertex_count];
    let positions: Vec<[f32; 3]> = (0..vertex_count).map(position).collect();
    let normals: Vec<[f32; 3]> = (0..vertex_count).map(normal).collect();
    let texcoords: Vec<[f32; 2]> = (0..vertex_count).map(texcoord).collect();
    let indices: Vec<u32> = triangles.iter().flatten().map(|&i| i as u32).collect();
    // SAFETY: only called after the library accepted the call, so every index is in range.
    unsafe { listing_tangents(&positions, &normals, &texcoords, &indices, &mut tangents) };
    tangents
}

// Its buffers.
const L_VERTEX: usize = 0;
const L_NORMAL: usize = 1;
const L_TEXCOORD: usize = 2;
const L_TRIANGLE: usize = 3;
const L_TANGENT: usize = 4;

/// A `long` count: usually small, sometimes negative, sometimes so large every span overflows.
fn long_count(u: &mut Unstructured, small_max: u8, huge_bit: u32) -> Result<c_long> {
    Ok(match weighted(u, &[14, 1, 1])? {
        0 => c_long::from(u.int_in_range(0..=small_max)?),
        1 => {
            if one_in::<4>(u)? {
                c_long::MIN
            } else {
                -1 - c_long::from(u32::arbitrary(u)? >> 1)
            }
        }
        _ => ((1u64 << huge_bit) | (u64::arbitrary(u)? & c_long::MAX as u64)) as c_long,
    })
}

pub fn check_listing_entry(u: &mut Unstructured) -> Result<()> {
    // Huge vertex counts start at 2^60 (12-byte spans overflow), triangle counts at 2^61.
    let vertex_count = long_count(u, SMALL_VERTICES as u8, 60)?;
    let triangle_count = long_count(u, 32, 61)?;
    let vc = usize::try_from(vertex_count).ok();
    let ic = usize::try_from(triangle_count).ok().and_then(|t| t.checked_mul(3));
    let mut bufs = [Buf::default(); 5];
    for (k, size) in [12, 12, 8, 2, 16].into_iter().enumerate() {
        bufs[k] = Buf {
            null: one_in::<32>(u)?,
            base: 0,
            stride: size,
            size,
            count: if k == L_TRIANGLE {
                ic.unwrap_or(0)
            } else {
                vc.unwrap_or(0)
            },
        };
    }
    let mut order = [L_VERTEX, L_NORMAL, L_TEXCOORD, L_TRIANGLE, L_TANGENT];
    shuffle(u, &mut order)?;
    let mut cursor = below(u, 8)?;
    for k in order {
        bufs[k].base = cursor;
        cursor += bufs[k].extent().filter(|&e| e <= LISTING_ARENA).unwrap_or(0) + below(u, 8)?;
    }
    if one_in::<4>(u)? {
        let source = below(u, 4)?;
        let delta = nudge(u, 20)?;
        bufs[L_TANGENT].base = (bufs[source].base as isize + delta).clamp(0, LISTING_ARENA as isize - 1) as usize;
    }
    for b in &mut bufs {
        b.clamp_into(LISTING_ARENA);
    }

    let fill = u8::arbitrary(u)?;
    let mut arena = vec![fill; LISTING_ARENA];
    let encodings = [pick_encoding(u)?, pick_encoding(u)?, pick_encoding(u)?];
    fill_vectors::<3>(u, encodings[0], Attribute::Position, &bufs[L_VERTEX], &mut arena)?;
    fill_vectors::<3>(u, encodings[1], Attribute::Normal, &bufs[L_NORMAL], &mut arena)?;
    fill_vectors::<2>(u, encodings[2], Attribute::Texcoord, &bufs[L_TEXCOORD], &mut arena)?;
    let tri = bufs[L_TRIANGLE];
    if tri.placed(LISTING_ARENA) {
        for k in 0..tri.count {
            let value = index_value(u, vc.unwrap_or(0))? as u16;
            arena[tri.element(k)..tri.element(k) + 2].copy_from_slice(&value.to_le_bytes());
        }
    }
    describe::listing(vertex_count, triangle_count, &bufs, fill, &arena);

    // What the inputs call for.
    let mut hard = 0u32;
    let mut soft = 0u32;
    if vc.is_none() || triangle_count < 0 {
        hard |= bit(TBASIS_ERROR_INVALID_COUNT);
    } else {
        if ic.is_none() {
            hard |= bit(TBASIS_ERROR_SIZE_OVERFLOW);
        }
        for b in &bufs {
            hard |= b.violations();
        }
        if bufs[L_TANGENT].null && vc == Some(0) {
            soft |= bit(TBASIS_ERROR_NULL_POINTER);
        }
        let valid = |k: usize| bufs[k].valid_footprint() && bufs[k].placed(LISTING_ARENA);
        if valid(L_TANGENT)
            && [L_VERTEX, L_NORMAL, L_TEXCOORD, L_TRIANGLE]
                .into_iter()
                .any(|k| valid(k) && bufs[L_TANGENT].shares_bytes(&bufs[k]))
        {
            hard |= bit(TBASIS_ERROR_OVERLAP);
        }
        if tri.placed(LISTING_ARENA) {
            let limit = vc.unwrap_or(0);
            if (0..tri.count)
                .any(|k| u16::from_le_bytes([arena[tri.element(k)], arena[tri.element(k) + 1]]) as usize >= limit)
            {
                hard |= bit(TBASIS_ERROR_INDEX_OUT_OF_RANGE);
            }
        }
    }
    for (k, b) in bufs.iter().enumerate() {
        if hard & bit(TBASIS_ERROR_INVALID_COUNT) == 0 && !b.null && !b.placed(LISTING_ARENA) {
            assert!(
                b.violations() != 0 || ic.is_none(),
                "harness: listing buffer {k} does not fit"
            );
        }
    }

    let before = arena.clone();
    let base = arena.as_mut_ptr();
    // SAFETY: every base is inside the arena; the spans the library may use are inside it too.
    let pointer = |b: &Buf| {
        if b.null {
            ptr::null_mut()
        } else {
            unsafe { base.add(b.base) }
        }
    };
    let status = unsafe {
        tbasis_calculate_tangent_array(
            vertex_count,
            pointer(&bufs[L_VERTEX]).cast::<f32>(),
            pointer(&bufs[L_NORMAL]).cast::<f32>(),
            pointer(&bufs[L_TEXCOORD]).cast::<f32>(),
            triangle_count,
            pointer(&bufs[L_TRIANGLE]).cast::<u16>(),
            pointer(&bufs[L_TANGENT]).cast::<f32>(),
        )
    };
    let expect = Expect { hard, soft };
    check_status(status, &expect, 0, "tbasis_calculate_tangent_array");
    assert_ne!(
        status, TBASIS_ERROR_DEGENERATE_UV,
        "tbasis_calculate_tangent_array: DEGENERATE_UV"
    );
    if hard == 0 && soft == 0 {
        assert_eq!(
            status, TBASIS_OK,
            "tbasis_calculate_tangent_array failed on valid input"
        );
    }

    let tangent = bufs[L_TANGENT];
    let ok = status == TBASIS_OK;
    let writable = if ok && tangent.placed(LISTING_ARENA) {
        vec![(tangent.base, tangent.base + tangent.extent().unwrap_or(0))]
    } else {
        Vec::new()
    };
    if let Some(at) = first_change_outside(&before, &arena, writable) {
        panic!("tbasis_calculate_tangent_array returned {status} and changed byte {at} outside its output");
    }
    if ok {
        let vc = vc.unwrap();
        let triangles: Vec<[usize; 3]> = (0..tri.count / 3)
            .map(|t| {
                core::array::from_fn(|c| {
                    u16::from_le_bytes([before[tri.element(3 * t + c)], before[tri.element(3 * t + c) + 1]]) as usize
                })
            })
            .collect();
        let expected = listing(
            vc,
            &triangles,
            |i| vec_at(&before, bufs[L_VERTEX].element(i)),
            |i| vec_at(&before, bufs[L_NORMAL].element(i)),
            |i| vec_at(&before, bufs[L_TEXCOORD].element(i)),
        );
        for (i, want) in expected.iter().enumerate() {
            let got: [f32; 4] = vec_at(&arena, tangent.element(i));
            assert!(
                (0..4).all(|k| same(got[k], want[k])),
                "tbasis_calculate_tangent_array: tangent {i} is {got:?}, the listing gives {want:?}"
            );
        }
    }
    Ok(())
}
