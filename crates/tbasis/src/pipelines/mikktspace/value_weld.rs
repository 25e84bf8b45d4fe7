//! Welding by value in linear time: the vertices mikktspace.c's weld finds equal, without its
//! splitting.
//!
//! `MergeVertsFast` (see [`super::weld`]) welds two corners exactly when their position, normal
//! and texture coordinate compare equal with `==`, provided every part it splits has a finite
//! midpoint and no float is `NaN`: equal positions always fall in one grid cell and on one side of
//! every split, and the final search compares all eight floats. So where no attribute is `NaN`
//! and every coordinate stays below `1e38` (twice it is still finite), its welded vertices are the
//! classes of equal attributes, which a hash table finds in one pass. Its representative's bits
//! are read downstream; where a class holds attributes that compare equal but differ in bits (a
//! -0 against a +0), this pass gives up. Only the representative's index (`values` in
//! [`super::weld`]) still depends on the splitting: see [`super::last_run`].
#![forbid(unsafe_code)]

use super::attributes::Attributes;
use super::weld::{canonical_bits, hash_of};
use super::NONE;
use crate::kernel::simd;

/// Coordinates at or beyond this could make mikktspace.c's midpoint `0.5 * (max + min)` infinite.
const LARGEST_COORDINATE: f32 = 1e38;

/// Corners read ahead: their new vertices' table slots are fetched together.
const BATCH: usize = 16;

/// Numbers each vertex's class of equal attributes in order of first use by `corners` (vertices
/// already checked), into `class` (per vertex, [`NONE`] for unused ones), and writes one vertex
/// of each class into `source`; `table` (at least two words per vertex) is the hash table.
/// Returns the class count, or `None` where mikktspace.c's weld could differ (see the module).
pub(crate) fn classes(
    attributes: &Attributes,
    corners: &[u32],
    class: &mut [u32],
    source: &mut [u32],
    table: &mut [u32],
) -> Option<usize> {
    class.fill(NONE);
    table.fill(NONE);
    let capacity = table.len() as u64;
    let mut count = 0u32;
    // Per batch: each new vertex, its attributes, their bits with -0 as +0, and its first slot.
    let mut new = [(0u32, [0.0f32; 8], [0u32; 8], 0usize); BATCH];
    for batch in corners.chunks(BATCH) {
        let mut pending = 0;
        for &v in batch {
            if class[v as usize] != NONE {
                continue;
            }
            let key = attributes.key(v);
            let usable = key.iter().all(|x| !x.is_nan()) && key[..3].iter().all(|x| x.abs() < LARGEST_COORDINATE);
            if !usable {
                return None;
            }
            let canonical = key.map(canonical_bits);
            // Multiply-shift onto the table: any capacity works.
            let slot = ((u64::from(hash_of(&canonical)) * capacity) >> 32) as usize;
            simd::prefetch(table, slot);
            new[pending] = (v, key, canonical, slot);
            pending += 1;
        }
        for &(v, key, canonical, mut slot) in &new[..pending] {
            if class[v as usize] != NONE {
                // Twice in this batch.
                continue;
            }
            let id = loop {
                let id = table[slot];
                if id == NONE {
                    table[slot] = count;
                    source[count as usize] = v;
                    count += 1;
                    break count - 1;
                }
                let other = attributes.key(source[id as usize]);
                if other.map(canonical_bits) == canonical {
                    if other.map(f32::to_bits) != key.map(f32::to_bits) {
                        // Equal under `==`, different bits: the representative's would matter.
                        return None;
                    }
                    break id;
                }
                slot = if slot + 1 == table.len() { 0 } else { slot + 1 };
            };
            class[v as usize] = id;
        }
    }
    Some(count as usize)
}
