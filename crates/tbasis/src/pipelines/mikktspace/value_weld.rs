//! Welding by value in linear time: the vertices mikktspace.c's weld finds equal, without its
//! splitting.
//!
//! `MergeVertsFast` (see [`super::weld`]) welds two corners exactly when their position, normal
//! and texture coordinate compare equal with `==`, provided every part it splits has a finite
//! midpoint and no float is `NaN`: equal positions always fall in one grid cell and on one side of
//! every split, and the final search compares all eight floats. So where no attribute is `NaN`
//! and every position coordinate stays below `1e38` (twice it is still finite), its welded
//! vertices are the classes of equal attributes, which a hash table finds in one pass. Its
//! representative's bits are read downstream; where a class holds attributes that compare equal
//! but differ in bits (a -0 against a +0), this pass gives up. Only the representative's index (`values` in
//! [`super::weld`]) still depends on the splitting: see [`super::last_run`].
#![forbid(unsafe_code)]

use super::attributes::Attributes;
use super::weld::{canonical_bits, hash_of};
use super::NONE;
use crate::kernel::simd;

/// Coordinates at or beyond this could make mikktspace.c's midpoint `0.5 * (max + min)` infinite.
const LARGEST_COORDINATE: f32 = 1e38;

/// Vertices read ahead: their table slots are fetched together.
const BATCH: usize = 16;

/// Marks a used vertex in `class` before it has a class.
const USED: u32 = NONE - 1;

/// Replaces each corner's vertex in `corners` (indices already checked) by its welded vertex,
/// numbered in order of first use; writes each vertex's welded vertex to `class` ([`NONE`] for
/// unused ones) and the first vertex of each welded vertex to `source`, using `table` (at least
/// two words per vertex) as the hash table. Returns the welded vertex count, or `None`, with
/// `corners` untouched, where mikktspace.c's weld could differ (see the module).
///
/// The vertices are hashed in their own order, so that their attributes stream from memory and
/// the table's probes are fetched a batch at a time; the corners then number the classes.
pub(crate) fn weld(
    attributes: &Attributes,
    corners: &mut [u32],
    class: &mut [u32],
    source: &mut [u32],
    table: &mut [u32],
) -> Option<usize> {
    class.fill(NONE);
    for &v in corners.iter() {
        class[v as usize] = USED;
    }

    // 1. Each used vertex's class, named for now by its first vertex, which the other members
    //    compare with. A table entry holds the class in its low `id_bits` and low bits of the hash above them,
    //    so that most entries of other classes are passed over without reading their attributes
    //    (a class is below the vertex count, so its field is never all ones: no entry is NONE).
    table.fill(NONE);
    let id_bits = u32::BITS - (class.len() as u32).leading_zeros();
    let id_mask = NONE.checked_shr(u32::BITS - id_bits).unwrap_or(0);
    let fingerprint = |hash: u32| hash.checked_shl(id_bits).unwrap_or(0);
    let capacity = table.len() as u64;
    let mut batch = [(0u32, [0u32; 8], [0u32; 8], 0usize, 0u32); BATCH];
    let mut v = 0;
    while v < class.len() {
        let mut pending = 0;
        while pending < BATCH && v < class.len() {
            if class[v] == USED {
                let key = attributes.key(v as u32);
                let usable = key.iter().all(|x| !x.is_nan()) && key[..3].iter().all(|x| x.abs() < LARGEST_COORDINATE);
                if !usable {
                    return None;
                }
                let canonical = key.map(canonical_bits);
                // Multiply-shift onto the table: any capacity works.
                let hash = hash_of(&canonical);
                let slot = ((u64::from(hash) * capacity) >> 32) as usize;
                simd::prefetch(table, slot);
                batch[pending] = (v as u32, key.map(f32::to_bits), canonical, slot, fingerprint(hash));
                pending += 1;
            }
            v += 1;
        }
        for &(vertex, bits, canonical, mut slot, print) in &batch[..pending] {
            class[vertex as usize] = loop {
                let entry = table[slot];
                if entry == NONE {
                    table[slot] = print | vertex;
                    break vertex;
                }
                let id = entry & id_mask;
                if entry & !id_mask == print {
                    let other = attributes.key(id);
                    if other.map(canonical_bits) == canonical {
                        if other.map(f32::to_bits) != bits {
                            // Equal under `==`, different bits: the representative's would matter.
                            return None;
                        }
                        break id;
                    }
                }
                slot = if slot + 1 == table.len() { 0 } else { slot + 1 };
            };
        }
    }

    // 2. Renumber in order of first use by the corners, as the replayed weld numbers them.
    let number = &mut table[..class.len()];
    number.fill(NONE);
    let mut next = 0u32;
    for corner in corners.iter_mut() {
        let first = class[*corner as usize];
        if number[first as usize] == NONE {
            number[first as usize] = next;
            source[next as usize] = first;
            next += 1;
        }
        *corner = number[first as usize];
    }
    for id in class.iter_mut().filter(|id| **id != NONE) {
        *id = number[*id as usize];
    }
    Some(next as usize)
}
