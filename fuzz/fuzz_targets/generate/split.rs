//! `tbasis_split_corners`, on the per-corner tangents a successful `tbasis_generate_corners` call
//! wrote and on tangents drawn from the fuzzer's bytes, with its outputs packed in an arena of
//! their own, near each other, or moved over (or after) the mesh's buffers. Checked against the
//! header: the status the inputs call for (and its string); on an error no byte written; on OK
//! only the outputs written (of `sources`, only the first `*appended_count`), two corners of a
//! vertex sharing an output vertex exactly when their tangents have the same bits, the corners
//! of each vertex's first tangent keeping its index, each further tangent appending a vertex
//! `vertex_count + j` in the order of first appearance whose source is that vertex; the same
//! result as `tbasis::split_corners`; and, after `tbasis_generate_corners` with method
//! MIKKTSPACE, as many split vertices as its report counts. Each successful split then feeds
//! `tbasis_copy_split_vertices` (`generate/copy_split.rs`).

use core::ffi::c_void;
use core::mem::size_of;
use core::ptr;
use std::collections::HashMap;

use arbitrary::{Arbitrary, Result, Unstructured};
use tbasis::{SeamSplit, Strided};

use crate::ffi::*;
use crate::status::*;

use crate::arena::{bit, first_change_outside, put_f32, vec_at, Buf};
use crate::call::debugging;
use crate::copy_split;
use crate::input::{below, mixed, nudge, one_in, shuffle, special, weighted};
use crate::packed::Packed;
use crate::plan::{end_of, mesh_descriptor, mesh_violations, pick_stride, Plan, IDX, NRM, POS, TAN, UV};
use crate::statuses::{check_status, Expect};

/// The arena a buffer of a split call sits in: the mesh's, or the call's own.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Arena {
    Main,
    Side,
}

#[derive(Clone, Copy, Debug)]
struct Placed {
    buf: Buf,
    arena: Arena,
}

impl Placed {
    fn main(buf: Buf) -> Placed {
        Placed {
            buf,
            arena: Arena::Main,
        }
    }
}

/// Everything one `tbasis_split_corners` call is made of (its mesh is a plan's).
#[derive(Debug)]
struct SplitPlan {
    mesh_null: bool,
    /// The corner tangents (16 bytes a corner).
    tangents: Placed,
    /// `new_indices` and `sources`: room for a `uint32_t` a corner.
    new_indices: Placed,
    sources: Placed,
    /// `appended_count`: one `size_t`.
    count: Placed,
    main_len: usize,
    side_len: usize,
    side_fill: u8,
    /// Unaligned offset of the mesh descriptor in its buffer.
    mesh_offset: usize,
}

impl SplitPlan {
    fn len(&self, arena: Arena) -> usize {
        match arena {
            Arena::Main => self.main_len,
            Arena::Side => self.side_len,
        }
    }
    fn placed(&self, p: &Placed) -> bool {
        p.buf.placed(self.len(p.arena))
    }
    /// `p` when the library sees it as a footprint and the harness placed it.
    fn footprint(&self, p: &Placed) -> Option<Placed> {
        (p.buf.valid_footprint() && self.placed(p)).then_some(*p)
    }
    fn outputs(&self) -> [Placed; 3] {
        [self.new_indices, self.sources, self.count]
    }
}

fn meet(a: &Placed, b: &Placed) -> bool {
    a.arena == b.arena && a.buf.shares_bytes(&b.buf)
}

#[derive(Arbitrary, Debug)]
struct SplitNulls {
    #[arbitrary(with = one_in::<64>)]
    mesh: bool,
    #[arbitrary(with = one_in::<32>)]
    tangents: bool,
    #[arbitrary(with = one_in::<32>)]
    new_indices: bool,
    #[arbitrary(with = one_in::<32>)]
    sources: bool,
    #[arbitrary(with = one_in::<64>)]
    appended_count: bool,
}

/// Most extents the side arena makes room for; a larger buffer (only with a corner count whose
/// mesh the library must refuse first) is left unplaced.
const SIDE_MAX: usize = 1 << 22;

/// Packs `bufs` into the side arena in some order, with small gaps or small overlaps, sometimes
/// one moved near another; returns them placed, and the arena's length.
fn pack_side(u: &mut Unstructured, bufs: &mut [Buf]) -> Result<usize> {
    let mut order: Vec<usize> = (0..bufs.len()).collect();
    shuffle(u, &mut order)?;
    let mut cursor = below(u, 8)?;
    let mut end = cursor;
    for k in order {
        bufs[k].base = cursor;
        let extent = bufs[k].extent().filter(|&e| e <= SIDE_MAX).unwrap_or(0);
        cursor += extent;
        end = end.max(cursor);
        if one_in::<16>(u)? {
            cursor = cursor.saturating_sub(1 + below(u, 16)?);
        } else {
            cursor += below(u, 8)?;
        }
    }
    let len = end + below(u, 8)? + 1;
    if one_in::<8>(u)? {
        let (target, source) = (below(u, bufs.len())?, below(u, bufs.len())?);
        bufs[target].base = (bufs[source].base as isize + nudge(u, 20)?).clamp(0, len as isize - 1) as usize;
    }
    for b in bufs {
        b.clamp_into(len);
    }
    Ok(len)
}

/// A base in the main arena for a buffer moved there: after the mesh's buffers (often free),
/// anywhere, or near (or on) one of them.
fn main_base(u: &mut Unstructured, plan: &Plan) -> Result<usize> {
    let b = &plan.bufs;
    Ok(match weighted(u, &[2, 1, 1])? {
        0 => end_of([&b[POS], &b[NRM], &b[UV], &b[IDX]], plan.arena) + below(u, 8)?,
        1 => below(u, plan.arena)?,
        _ => {
            let near = b[[POS, NRM, UV, IDX][below(u, 4)?]].base as isize;
            (near + nudge(u, 20)?).clamp(0, plan.arena as isize - 1) as usize
        }
    })
}

/// The outputs of a split over `corners` corners (and the tangents, when `tangents` still needs a
/// place), laid out from the bytes.
fn plan_split(u: &mut Unstructured, plan: &Plan, tangents: Option<Placed>, corners: usize) -> Result<SplitPlan> {
    let nulls = SplitNulls::arbitrary(u)?;
    let word = |null: bool, size: usize, count: usize| Buf {
        null,
        base: 0,
        stride: size,
        size,
        count,
    };
    let mut bufs = vec![
        word(nulls.new_indices, 4, corners),
        word(nulls.sources, 4, corners),
        word(nulls.appended_count, size_of::<usize>(), 1),
    ];
    if tangents.is_none() {
        let room = 16 * corners.min(SIDE_MAX / 16) + 4096;
        bufs.push(Buf {
            null: nulls.tangents,
            base: 0,
            stride: pick_stride(u, 16, corners, room)?,
            size: 16,
            count: corners,
        });
    }
    let side_len = pack_side(u, &mut bufs)?;
    let mut placed: Vec<Placed> = bufs
        .into_iter()
        .map(|buf| Placed {
            buf,
            arena: Arena::Side,
        })
        .collect();
    // Sometimes a buffer goes to the mesh's arena, where it may meet the mesh's buffers.
    if one_in::<8>(u)? {
        let k = below(u, placed.len())?;
        placed[k].arena = Arena::Main;
        placed[k].buf.base = main_base(u, plan)?;
        placed[k].buf.clamp_into(plan.arena);
    }
    let tangents = tangents.unwrap_or_else(|| placed.pop().expect("the tangents were placed last"));
    Ok(SplitPlan {
        mesh_null: nulls.mesh,
        tangents,
        new_indices: placed[0],
        sources: placed[1],
        count: placed[2],
        main_len: plan.arena,
        side_len,
        side_fill: u8::arbitrary(u)?,
        mesh_offset: below(u, 8)?,
    })
}

/// The statuses the inputs of the split call `sp` on the mesh of `plan` call for.
fn expect_split(plan: &Plan, sp: &SplitPlan, main: &[u8]) -> Expect {
    let null = Expect {
        hard: bit(TBASIS_ERROR_NULL_POINTER),
        soft: 0,
    };
    if sp.mesh_null || sp.count.buf.null {
        return null;
    }
    let mut hard = mesh_violations(plan, main);
    for p in [sp.tangents, sp.new_indices, sp.sources] {
        hard |= p.buf.violations();
    }
    // Each output against the mesh's inputs, the outputs after it and the tangents.
    let b = &plan.bufs;
    let mut inputs = vec![POS, NRM];
    if !b[UV].null {
        inputs.push(UV);
    }
    if !b[IDX].null && plan.index_type_valid() {
        inputs.push(IDX);
    }
    let mut others: Vec<Placed> = inputs
        .into_iter()
        .filter_map(|k| sp.footprint(&Placed::main(b[k])))
        .collect();
    others.extend(sp.footprint(&sp.tangents));
    let outputs: Vec<Option<Placed>> = sp.outputs().iter().map(|p| sp.footprint(p)).collect();
    let overlap = outputs.iter().enumerate().any(|(k, out)| {
        out.is_some_and(|out| {
            others
                .iter()
                .chain(outputs[k + 1..].iter().flatten())
                .any(|o| meet(&out, o))
        })
    });
    if overlap {
        hard |= bit(TBASIS_ERROR_OVERLAP);
    }
    Expect { hard, soft: 0 }
}

/// Makes the split call over the two arenas.
fn call_split(plan: &Plan, sp: &SplitPlan, main: &mut [u8], side: &mut [u8]) -> tbasis_status {
    let (main_ptr, side_ptr) = (main.as_mut_ptr(), side.as_mut_ptr());
    // SAFETY: every base is below its arena's length (clamped), so `add` stays in the allocation.
    let at = |p: &Placed| -> *mut u8 {
        match (p.buf.null, p.arena) {
            (true, _) => ptr::null_mut(),
            (false, Arena::Main) => unsafe { main_ptr.add(p.buf.base) },
            (false, Arena::Side) => unsafe { side_ptr.add(p.buf.base) },
        }
    };
    let mesh = mesh_descriptor(plan, main_ptr);
    let mut mesh_bytes = [0u8; size_of::<tbasis_mesh>() + 8];
    // SAFETY: the offset leaves room for the descriptor, written unaligned; every pointer the call
    // gets addresses owned memory, and every span it may use lies inside it (`assert_sound`).
    unsafe {
        let mesh_ptr = mesh_bytes.as_mut_ptr().add(sp.mesh_offset).cast::<tbasis_mesh>();
        ptr::write_unaligned(mesh_ptr, mesh);
        tbasis_split_corners(
            if sp.mesh_null { ptr::null() } else { mesh_ptr },
            at(&sp.tangents).cast::<c_void>(),
            sp.tangents.buf.stride,
            at(&sp.new_indices).cast::<u32>(),
            at(&sp.sources).cast::<u32>(),
            at(&sp.count).cast::<usize>(),
        )
    }
}

/// The harness's promise: a call the inputs allow to succeed only touches memory it owns (the
/// library reads the tangents and indices and writes the outputs only once every check passed).
fn assert_sound(sp: &SplitPlan, expect: &Expect) {
    if expect.hard != 0 {
        return;
    }
    for (name, p) in [
        ("tangents", sp.tangents),
        ("new_indices", sp.new_indices),
        ("sources", sp.sources),
        ("appended_count", sp.count),
    ] {
        assert!(
            p.buf.count == 0 || sp.placed(&p),
            "harness: split {name} does not fit and the call may succeed"
        );
    }
}

fn u32_at(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
}

/// The sources a successful split wrote, as `tbasis_copy_split_vertices` takes them: `appended`
/// of them at `sources_at` in `sources_arena`, which has room for `capacity`; and the vertex count
/// of the mesh split.
pub struct Written<'a> {
    pub vertex_count: usize,
    pub sources_arena: &'a [u8],
    pub sources_at: usize,
    pub capacity: usize,
    pub appended: usize,
}

/// Makes the split call of `sp` over the mesh of `plan` in the arenas `(main, side)` and checks
/// it; on OK, the split against the header's contract and the Rust API, then
/// `tbasis_copy_split_vertices` with its sources. `split_vertices`: the count the report of a
/// MIKKTSPACE `tbasis_generate_corners` call gives for these tangents.
fn check_split(
    u: &mut Unstructured,
    plan: &Plan,
    sp: &SplitPlan,
    arenas: (&mut [u8], &mut [u8]),
    split_vertices: Option<usize>,
    what: &str,
) -> Result<()> {
    let (main, side) = arenas;
    let (main_before, side_before) = (main.to_vec(), side.to_vec());
    let expect = expect_split(plan, sp, &main_before);
    assert_sound(sp, &expect);
    if debugging() {
        eprintln!("{what}: {sp:#?}, expected {:#x} (or {:#x})", expect.hard, expect.soft);
    }
    let status = call_split(plan, sp, main, side);
    check_status(status, &expect, 0, what);
    if debugging() {
        eprintln!("{what}: status {status}");
    }
    let bytes_of = |arena: Arena| -> (&[u8], &[u8]) {
        match arena {
            Arena::Main => (&main_before, &*main),
            Arena::Side => (&side_before, &*side),
        }
    };
    if status != TBASIS_OK {
        for arena in [Arena::Main, Arena::Side] {
            let (before, after) = bytes_of(arena);
            if let Some(at) = first_change_outside(before, after, Vec::new()) {
                panic!("{what} returned {status} and changed byte {at} of the {arena:?} arena");
            }
        }
        return Ok(());
    }

    let corners = sp.new_indices.buf.count;
    let (_, count_bytes) = bytes_of(sp.count.arena);
    let at = sp.count.buf.base;
    let appended = usize::from_ne_bytes(count_bytes[at..at + size_of::<usize>()].try_into().unwrap());
    assert!(
        appended <= corners,
        "{what}: {appended} vertices appended for {corners} corners"
    );
    let written = |p: &Placed, count: usize| (p.arena, Buf { count, ..p.buf });
    let outputs = [
        written(&sp.new_indices, corners),
        written(&sp.sources, appended),
        written(&sp.count, 1),
    ];
    for arena in [Arena::Main, Arena::Side] {
        let ranges = outputs
            .iter()
            .filter(|(a, _)| *a == arena)
            .flat_map(|(_, b)| b.ranges())
            .collect();
        let (before, after) = bytes_of(arena);
        if let Some(at) = first_change_outside(before, after, ranges) {
            panic!("{what} changed byte {at} of the {arena:?} arena outside its outputs");
        }
    }

    let read = |p: &Placed, count: usize| -> Vec<u32> {
        let (_, after) = bytes_of(p.arena);
        (0..count).map(|k| u32_at(after, p.buf.element(k))).collect()
    };
    let split = SeamSplit {
        indices: read(&sp.new_indices, corners),
        sources: read(&sp.sources, appended),
    };
    let (tangents_before, _) = bytes_of(sp.tangents.arena);
    let tangents: Vec<[f32; 4]> = (0..corners)
        .map(|c| vec_at(tangents_before, sp.tangents.buf.element(c)))
        .collect();
    let mesh =
        Packed::of(plan, &main_before).unwrap_or_else(|| panic!("{what} accepted a mesh the harness finds invalid"));
    check_contract(&mesh, &tangents, &split, what);
    let rust = tbasis::split_corners(&mesh.mesh(), &Strided::from_slice(&tangents));
    assert!(
        rust.as_ref() == Ok(&split),
        "{what}: tbasis::split_corners gives {rust:?}, the C call {split:?}"
    );
    if let Some(expected) = split_vertices {
        let mut split_sources = split.sources.clone();
        split_sources.sort_unstable();
        split_sources.dedup();
        assert_eq!(
            split_sources.len(),
            expected,
            "{what}: vertices split, against split_vertices of the report of tbasis_generate_corners"
        );
    }

    let (_, sources_arena) = bytes_of(sp.sources.arena);
    copy_split::check(
        u,
        &Written {
            vertex_count: plan.vertex_count,
            sources_arena,
            sources_at: sp.sources.buf.base,
            capacity: corners,
            appended,
        },
    )
}

/// The split of `tangents` (a frame per corner of `mesh`) is the one the header describes.
fn check_contract(mesh: &Packed, tangents: &[[f32; 4]], split: &SeamSplit, what: &str) {
    let vc = mesh.vertex_count();
    let mut by_vertex_bits: HashMap<(usize, [u32; 4]), u32> = HashMap::new();
    let mut bits_of_output: HashMap<u32, [u32; 4]> = HashMap::new();
    let mut seen = vec![false; vc];
    let mut next_appended = 0usize;
    for (c, (&index, t)) in split.indices.iter().zip(tangents).enumerate() {
        let v = mesh.corner_vertex(c);
        let bits = t.map(f32::to_bits);
        let context = || format!("{what}: corner {c} (vertex {v}, tangent {t:?} {bits:08x?}) has new index {index}");
        // The first corner of a vertex keeps its index.
        if !seen[v] {
            seen[v] = true;
            assert_eq!(
                index as usize,
                v,
                "{}: the vertex's first corner must keep it",
                context()
            );
        }
        // A new index is the vertex itself or an appended copy of it, appended in order.
        if (index as usize) < vc {
            assert_eq!(index as usize, v, "{}: another vertex", context());
        } else {
            let j = index as usize - vc;
            assert!(j < split.sources.len(), "{}: past the appended vertices", context());
            assert_eq!(
                split.sources[j] as usize,
                v,
                "{}: its source is not the vertex",
                context()
            );
            assert!(
                j <= next_appended,
                "{}: appended vertex {j} appears before {next_appended}",
                context()
            );
            next_appended = next_appended.max(j + 1);
        }
        // Equal bits share an output vertex; different bits never do.
        let kept = *by_vertex_bits.entry((v, bits)).or_insert(index);
        assert_eq!(
            kept,
            index,
            "{}: an earlier corner with the same bits got {kept}",
            context()
        );
        let owner = *bits_of_output.entry(index).or_insert(bits);
        assert!(
            owner == bits,
            "{}: shared with a corner of other bits {owner:08x?}",
            context()
        );
    }
    assert_eq!(
        next_appended,
        split.sources.len(),
        "{what}: appended vertices that no corner uses"
    );
}

/// Splits the corner tangents that a successful `tbasis_generate_corners` call of `plan` wrote
/// into `arena`; `report`: the one it filled.
pub fn check_generated(u: &mut Unstructured, plan: &Plan, arena: &[u8], report: Option<&tbasis_report>) -> Result<()> {
    let tangents = Placed::main(plan.bufs[TAN]);
    let sp = plan_split(u, plan, Some(tangents), plan.corner_count())?;
    let split_vertices = report.filter(|_| plan.mikktspace()).map(|r| r.split_vertices);
    let mut main = arena.to_vec();
    let mut side = vec![sp.side_fill; sp.side_len];
    check_split(
        u,
        plan,
        &sp,
        (&mut main, &mut side),
        split_vertices,
        "tbasis_split_corners (generated tangents)",
    )
}

/// A corner tangent for the palette of [`check_arbitrary`]: a frame, any floats, or an earlier
/// entry changed only in bits (the split compares bits, not float values).
fn palette_entry(u: &mut Unstructured, earlier: &[[f32; 4]]) -> Result<[f32; 4]> {
    Ok(match weighted(u, &[3, 1, 1, 1])? {
        0 => {
            let w = if bool::arbitrary(u)? { 1.0 } else { -1.0 };
            [mixed(u)?, mixed(u)?, mixed(u)?, w]
        }
        1 => [mixed(u)?, mixed(u)?, mixed(u)?, mixed(u)?],
        2 => [special(u)?, special(u)?, special(u)?, special(u)?],
        _ if earlier.is_empty() => [0.0; 4],
        _ => {
            let mut t = *u.choose(earlier)?;
            let k = below(u, 4)?;
            t[k] = match u.int_in_range(0..=2u8)? {
                // 0.0 and -0.0 compare equal, NaNs of other payloads are all NaN: other bits.
                0 => -t[k],
                1 => f32::from_bits(0x7fc0_0000 | (u32::arbitrary(u)? & 0x003f_ffff)),
                _ => f32::from_bits(t[k].to_bits() ^ 1),
            };
            t
        }
    })
}

/// Splits tangents drawn from the bytes (a few distinct ones, so that vertices split) over the
/// mesh of `plan` as written in `pristine`.
pub fn check_arbitrary(u: &mut Unstructured, plan: &Plan, pristine: &[u8]) -> Result<()> {
    let sp = plan_split(u, plan, None, plan.corner_count())?;
    let mut palette = Vec::new();
    // Mostly more than one, so that vertices split.
    for _ in 0..[2, 3, 4, 1][weighted(u, &[3, 2, 2, 1])?] {
        let mut entry = palette_entry(u, &palette)?;
        // Distinct bits (exhausted input draws the same entry every time).
        if palette
            .iter()
            .any(|p: &[f32; 4]| p.map(f32::to_bits) == entry.map(f32::to_bits))
        {
            entry[0] = f32::from_bits(entry[0].to_bits().wrapping_add(palette.len() as u32));
        }
        palette.push(entry);
    }
    let mut main = pristine.to_vec();
    let mut side = vec![sp.side_fill; sp.side_len];
    let t = sp.tangents;
    if sp.placed(&t) {
        // Written in order, so with a short stride (refused) later corners overwrite earlier
        // ones; the checks read what the call will read.
        let arena = match t.arena {
            Arena::Main => &mut main,
            Arena::Side => &mut side,
        };
        // A byte a corner while there are bytes; past the end (a short input), picks from the
        // seed, so that the corners still differ.
        let mut state = u64::arbitrary(u)? | 1;
        for c in 0..t.buf.count {
            let v = if u.is_empty() {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                palette[(state >> 32) as usize % palette.len()]
            } else {
                *u.choose(&palette)?
            };
            for (k, x) in v.into_iter().enumerate() {
                put_f32(arena, t.buf.element(c) + 4 * k, x);
            }
        }
    }
    check_split(
        u,
        plan,
        &sp,
        (&mut main, &mut side),
        None,
        "tbasis_split_corners (arbitrary tangents)",
    )
}
