//! Welding by value in linear time: the vertices mikktspace.c's weld finds equal, without its
//! splitting.
//!
//! `MergeVertsFast` (see [`super::weld`]) welds two corners exactly when their position, normal and
//! texture coordinate compare equal with `==`, provided every part it splits has a finite midpoint
//! and no float is `NaN`: equal positions always fall in one grid cell and on one side of every
//! split, and the final search compares all eight floats. So where no attribute is `NaN` and every
//! position coordinate stays below `1e38` (twice it is still finite), its welded vertices are the
//! classes of equal attributes, which a hash table finds in linear time. Its representative's bits
//! are read downstream; where a class holds attributes that compare equal but differ in bits (a -0
//! against a +0), the weld by value gives up. Only the representative's index (`values` in
//! [`super::weld`]) still depends on the splitting: see [`super::last_run`].
#![forbid(unsafe_code)]

use core::sync::atomic::{AtomicU32, Ordering::Relaxed};

use super::attributes::Attributes;
use super::weld::{canonical_bits, hash_of};
use super::NONE;
use crate::kernel::parallel;
use crate::kernel::simd;
use crate::kernel::views::pod::atomic_words;

/// Coordinates at or beyond this could make mikktspace.c's midpoint `0.5 * (max + min)` infinite.
const LARGEST_COORDINATE: f32 = 1e38;

/// Vertices read ahead: their table slots are fetched together.
const BATCH: usize = 16;

/// What `class` holds for a vertex along the way: [`NONE`] (unused), then [`USED`], then its hash
/// (below [`WRITTEN`]), then its class with [`WRITTEN`] set (a class is below the vertex count,
/// at most a quarter of the range: the flag never meets [`USED`]).
const USED: u32 = NONE - 1;
const WRITTEN: u32 = 1 << 31;

/// Replaces each corner's vertex in `corners` (indices already checked) by its welded vertex,
/// numbered in order of first use; writes each vertex's welded vertex to `class` ([`NONE`] for
/// unused ones) and the first vertex of each welded vertex to `source`, using `table` (at least
/// two words per vertex) as the hash table, on up to `workers` threads. Returns the welded vertex
/// count, or `None`, with `corners` untouched, where mikktspace.c's weld could differ (see the
/// module).
///
/// A class is named by its first vertex, whatever the table's layout, so the workers may share the
/// table: each takes a region of it and the vertices whose hash falls there, in vertex order.
pub(crate) fn weld(
    attributes: &Attributes,
    workers: usize,
    corners: &mut [u32],
    class: &mut [u32],
    source: &mut [u32],
    table: &mut [u32],
) -> Option<usize> {
    let classes = atomic_words(class);
    match classify(attributes, workers, corners, classes, table) {
        Classified::Done => {}
        Classified::Unusable => return None,
        // One region, the whole table, always has room: at most one class per vertex.
        Classified::RegionFull => match classify(attributes, 1, corners, classes, table) {
            Classified::Done => {}
            _ => return None,
        },
    }

    // 4. Renumber in order of first use by the corners, as the replayed weld numbers them.
    let number = &mut table[..class.len()];
    number.fill(NONE);
    let mut next = 0u32;
    for corner in corners.iter_mut() {
        let first = class[*corner as usize] & !WRITTEN;
        if number[first as usize] == NONE {
            number[first as usize] = next;
            source[next as usize] = first;
            next += 1;
        }
        *corner = number[first as usize];
    }
    for id in class.iter_mut().filter(|id| **id != NONE) {
        *id = number[(*id & !WRITTEN) as usize];
    }
    Some(next as usize)
}

/// How [`classify`] ended.
#[derive(Clone, Copy)]
enum Classified {
    /// Every used vertex's class is in `class`, with [`WRITTEN`] set.
    Done,
    /// An attribute is `NaN` or huge, or a class's members differ in bits.
    Unusable,
    /// A worker's region of the table filled up.
    RegionFull,
}

/// Each used vertex's class, named by its first vertex, into `class` (one word per vertex).
fn classify(
    attributes: &Attributes,
    workers: usize,
    corners: &[u32],
    class: &[AtomicU32],
    table: &mut [u32],
) -> Classified {
    // 1. The used vertices, on ranges of corners.
    class.iter().for_each(|c| c.store(NONE, Relaxed));
    let corner_ranges = parallel::range_ends(corners.len(), workers);
    let corner_starts = core::iter::once(0).chain(corner_ranges.ends().iter().copied());
    let mark = |(start, &end): (usize, &usize)| {
        for &v in &corners[start..end] {
            class[v as usize].store(USED, Relaxed);
        }
    };
    parallel::run(corner_starts.zip(corner_ranges.ends()), mark, |()| {});

    // 2. Each used vertex's hash, on ranges of vertices.
    let vertex_ranges = parallel::range_ends(class.len(), workers);
    let vertex_starts = core::iter::once(0).chain(vertex_ranges.ends().iter().copied());
    let hash = |(start, &end): (usize, &usize)| {
        for (v, class) in (start..end).zip(&class[start..end]) {
            if class.load(Relaxed) == USED {
                let key = attributes.key(v as u32);
                let usable = key.iter().all(|x| !x.is_nan()) && key[..3].iter().all(|x| x.abs() < LARGEST_COORDINATE);
                if !usable {
                    return false;
                }
                class.store(hash_of(&key.map(canonical_bits)) >> 1, Relaxed);
            }
        }
        true
    };
    let mut usable = true;
    parallel::run(vertex_starts.zip(vertex_ranges.ends()), hash, |ok| usable &= ok);
    if !usable {
        return Classified::Unusable;
    }

    // 3. The classes, each worker in its region of the table: a slot `s` of the whole table's
    //    `capacity` lies in region `s * workers / capacity`.
    let capacity = table.len();
    let bound = |region: usize| (region as u64 * capacity as u64).div_ceil(workers as u64) as usize;
    let region_ends = parallel::Ranges::from_ends((1..=workers).map(bound));
    let regions = parallel::split(table, region_ends.ends(), 1).enumerate();
    let mut outcome = Classified::Done;
    let find = |(region, table): (usize, &mut [u32])| {
        find_classes(attributes, class, (region, workers, bound(region)), capacity, table)
    };
    parallel::run(regions, find, |found| match (found, &outcome) {
        (Classified::Unusable, _) | (Classified::RegionFull, Classified::Done) => outcome = found,
        _ => {}
    });
    outcome
}

/// Step 3 of [`classify`] for one region of the table (`table`, from slot `first`): the class of
/// every vertex whose hash falls in it, in vertex order. A table entry holds the class in its low
/// `id_bits` and low bits of the hash above them, so that most entries of other classes are
/// passed over without reading their attributes (a class is below the vertex count, so its field
/// is never all ones: no entry is NONE).
fn find_classes(
    attributes: &Attributes,
    class: &[AtomicU32],
    (region, workers, first): (usize, usize, usize),
    capacity: usize,
    table: &mut [u32],
) -> Classified {
    table.fill(NONE);
    let id_bits = u32::BITS - (class.len() as u32).leading_zeros();
    let id_mask = NONE.checked_shr(u32::BITS - id_bits).unwrap_or(0);
    let fingerprint = |hash: u32| hash.checked_shl(id_bits).unwrap_or(0);
    let mut batch = [(0u32, [0u32; 8], [0u32; 8], 0usize, 0u32); BATCH];
    let mut filled = 0;
    let mut v = 0;
    while v < class.len() {
        let mut pending = 0;
        while pending < BATCH && v < class.len() {
            let hash = class[v].load(Relaxed);
            // Multiply-shift onto the table (the hash has 31 bits): any capacity works.
            let slot = ((u64::from(hash) * capacity as u64) >> 31) as usize;
            if hash < WRITTEN && (slot as u64 * workers as u64 / capacity as u64) as usize == region {
                let key = attributes.key(v as u32);
                simd::prefetch(table, slot - first);
                batch[pending] = (
                    v as u32,
                    key.map(f32::to_bits),
                    key.map(canonical_bits),
                    slot - first,
                    fingerprint(hash),
                );
                pending += 1;
            }
            v += 1;
        }
        for &(vertex, bits, canonical, mut slot, print) in &batch[..pending] {
            let found = loop {
                let entry = table[slot];
                if entry == NONE {
                    if filled + 1 == table.len() {
                        // The last empty slot stays empty, so that every probe ends.
                        return Classified::RegionFull;
                    }
                    table[slot] = print | vertex;
                    filled += 1;
                    break vertex;
                }
                let id = entry & id_mask;
                if entry & !id_mask == print {
                    let other = attributes.key(id);
                    if other.map(canonical_bits) == canonical {
                        if other.map(f32::to_bits) != bits {
                            // Equal under `==`, different bits: the representative's would matter.
                            return Classified::Unusable;
                        }
                        break id;
                    }
                }
                slot = if slot + 1 == table.len() { 0 } else { slot + 1 };
            };
            class[vertex as usize].store(found | WRITTEN, Relaxed);
        }
    }
    Classified::Done
}
