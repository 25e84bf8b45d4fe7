//! What one call is made of, decoded from the fuzzer's bytes: the vertex count, where each buffer
//! sits in the arena, its stride, which pointers are NULL, the options and the caller scratch; and
//! the rules the header gives for each of them.

use core::ptr;

use crate::ffi::*;

use crate::arena::{f32_at, fill_vectors, Buf};
use crate::call::debugging;
use crate::input::{index_value, pick_encoding, shuffle, Encoding, Input};

/// Bytes of the arena holding every buffer of a call.
pub const ARENA: usize = 12 * 1024;
/// Bytes of a caller scratch in its own arena, at most (method MIKKTSPACE asks for about 125 per
/// corner).
const OWN_SCRATCH_MAX: usize = 64 * 1024;
pub const MAX_VERTICES: usize = 64;
pub const MAX_TRIANGLES: usize = 96;

// Buffers of a call (`tbasis_generate_corners` has no bitangents; its tangents are per corner).
pub const POS: usize = 0;
pub const NRM: usize = 1;
pub const UV: usize = 2;
pub const TAN: usize = 3;
pub const BIT: usize = 4;
pub const IDX: usize = 5;
pub const NAMES: [&str; 6] = ["positions", "normals", "texcoords", "tangents", "bitangents", "indices"];

/// Where the caller scratch is, if any.
#[derive(Clone, Copy, Debug, Default)]
pub struct ScratchPlan {
    /// NULL pointer (then `claimed` is any value and must be ignored).
    pub null: bool,
    /// In the main arena at `base`; otherwise in its own arena at `base`.
    pub in_main: bool,
    pub base: usize,
    /// `scratch_size` as passed.
    pub claimed: usize,
    /// Bytes of its own arena.
    pub arena_len: usize,
}

impl ScratchPlan {
    pub fn buf(&self) -> Buf {
        Buf {
            null: self.null,
            base: self.base,
            stride: 1,
            size: 1,
            count: self.claimed,
        }
    }
}

/// Everything one `tbasis_generate` or `tbasis_generate_corners` call is made of.
#[derive(Clone, Debug)]
pub struct Plan {
    /// `tbasis_generate_corners`: `bufs[TAN]` holds a frame per corner, `bufs[BIT]` is unused and
    /// there is no output struct.
    pub corners: bool,
    pub vertex_count: usize,
    pub bufs: [Buf; 6],
    pub index_type: u32,
    pub mesh_null: bool,
    pub output_null: bool,
    pub options_null: bool,
    pub report_null: bool,
    pub method: u32,
    pub policy: u32,
    pub flags: u32,
    pub threads: u32,
    pub threshold: f32,
    pub scratch: ScratchPlan,
    /// What `tbasis_scratch_size` asks for this mesh and these options.
    pub scratch_needed: usize,
    /// Unaligned offsets of the mesh, options, output and report structs in their buffers.
    pub struct_offsets: [usize; 4],
    pub arena_fill: u8,
    pub scratch_fill: u8,
    pub encodings: [Encoding; 3],
}

impl Plan {
    /// The method the call runs (for a known method code).
    pub fn resolved_method(&self) -> u32 {
        match self.method {
            _ if self.options_null => TBASIS_METHOD_ANGLE,
            0 => TBASIS_METHOD_ANGLE,
            m => m,
        }
    }
    /// The policy the call runs: 0 is LEGACY for MIKKTSPACE, INHERIT for the other methods.
    pub fn resolved_policy(&self) -> u32 {
        match self.policy {
            _ if self.options_null => TBASIS_DEGENERATE_INHERIT,
            0 if self.resolved_method() == TBASIS_METHOD_MIKKTSPACE => TBASIS_DEGENERATE_LEGACY,
            0 => TBASIS_DEGENERATE_INHERIT,
            p => p,
        }
    }
    pub fn mikktspace(&self) -> bool {
        self.resolved_method() == TBASIS_METHOD_MIKKTSPACE
    }
    pub fn flip_v(&self) -> bool {
        !self.options_null && self.flags & TBASIS_FLAG_FLIP_V != 0
    }
    /// Elements of `bufs[TAN]`: a frame per vertex, or per corner.
    pub fn outputs(&self) -> usize {
        self.bufs[TAN].count
    }
    pub fn index_type_valid(&self) -> bool {
        self.index_type == TBASIS_INDEX_U16 || self.index_type == TBASIS_INDEX_U32
    }
    pub fn uses_scratch(&self) -> bool {
        !self.options_null && !self.scratch.null
    }
}

/// A stride for `count` elements of `size` bytes: usually valid, sometimes too small, large,
/// or so large that the span overflows (only when that is certain, so nothing is ever read).
fn pick_stride(input: &mut Input, size: usize, count: usize) -> usize {
    let fit = if count <= 1 {
        ARENA - size
    } else {
        ((ARENA - size) / (count - 1)).max(size)
    };
    match input.u8() % 16 {
        0..=7 => size,
        8..=10 => (size + input.u8() as usize % 33).min(fit),
        11 => input.below(size),
        12 => size + input.below(fit - size + 1),
        13 => fit,
        14 if count <= 1 => input.u64() as usize | size,
        14 => (1usize << 63) | input.u64() as usize,
        _ => (size + 4 * (input.u8() as usize % 8)).min(fit),
    }
}

/// A stride (see [`pick_stride`]) for each of `bufs`, in order.
fn pick_strides(input: &mut Input, bufs: &mut [Buf], count: usize) {
    for b in bufs {
        b.stride = pick_stride(input, b.size, count);
    }
}

pub fn decode_plan(input: &mut Input) -> Plan {
    let vertex_count = match input.u8() {
        // Huge: every vertex span overflows, so the call must fail before reading anything.
        255 => (1usize << 60) | input.u64() as usize,
        b => b as usize % (MAX_VERTICES + 1),
    };
    let mut bufs = [Buf::default(); 6];
    let sizes = [12, 12, 8, 16, 12];
    for k in POS..=BIT {
        bufs[k].size = sizes[k];
        bufs[k].count = vertex_count;
    }
    bufs[POS].null = input.rare(32);
    bufs[NRM].null = input.rare(32);
    bufs[UV].null = input.rare(8);
    bufs[TAN].null = input.rare(32);
    bufs[BIT].null = input.u8() % 2 == 0;
    bufs[IDX].null = input.u8() % 3 == 2;

    let index_type = match input.u8() % 16 {
        0..=7 => TBASIS_INDEX_U16,
        8..=13 => TBASIS_INDEX_U32,
        14 => [0, 3][input.u8() as usize % 2],
        _ => input.u32(),
    };
    let index_size = if index_type == TBASIS_INDEX_U16 { 2 } else { 4 };
    let index_count = if bufs[IDX].null {
        if input.rare(16) {
            input.u16() as usize
        } else {
            0
        }
    } else {
        match input.u8() % 32 {
            // Huge: the index span overflows.
            31 => (1usize << 62) | input.u64() as usize,
            28..=30 => input.below(3 * MAX_TRIANGLES + 3),
            _ => 3 * (input.u8() as usize % (MAX_TRIANGLES + 1)),
        }
    };
    bufs[IDX].size = index_size;
    bufs[IDX].stride = index_size;
    bufs[IDX].count = index_count;

    let layout = input.u8() % 8;
    match layout {
        // Interleaved: one record per vertex holding every attribute, tangents included.
        4 | 5 => {
            let mut order = [POS, NRM, UV, TAN, BIT];
            shuffle(input, &mut order);
            let mut offsets = [0usize; 5];
            let mut at = 0;
            for k in order {
                offsets[k] = at;
                at += bufs[k].size + input.u8() as usize % 4;
            }
            let stride = if input.rare(16) {
                input.below(at)
            } else {
                at + input.below(16)
            };
            let start = input.below(8);
            for k in POS..=BIT {
                bufs[k].stride = stride;
                bufs[k].base = start + offsets[k];
            }
            if input.rare(8) {
                let k = input.below(5);
                bufs[k].stride = pick_stride(input, bufs[k].size, vertex_count);
            }
            let end = bufs[..IDX]
                .iter()
                .filter_map(|b| b.extent().filter(|&e| e <= ARENA).map(|e| b.base + e))
                .max()
                .unwrap_or(0);
            bufs[IDX].base = end + input.below(8);
        }
        // Anywhere: bases independent of each other.
        6 => {
            pick_strides(input, &mut bufs[POS..=BIT], vertex_count);
            for b in &mut bufs {
                let room = b.extent().map_or(ARENA, |e| ARENA.saturating_sub(e) + 1);
                b.base = input.below(room);
            }
        }
        // Packed one after another in some order, with small gaps (or small overlaps).
        _ => {
            pick_strides(input, &mut bufs[POS..=BIT], vertex_count);
            let mut order = [POS, NRM, UV, TAN, BIT, IDX];
            shuffle(input, &mut order);
            let mut cursor = input.below(8);
            for k in order {
                bufs[k].base = cursor;
                let extent = bufs[k].extent().filter(|&e| e <= ARENA).unwrap_or(0);
                cursor += extent;
                if input.rare(16) {
                    cursor = cursor.saturating_sub(1 + input.below(16));
                } else {
                    cursor += input.u8() as usize % 8;
                }
            }
        }
    }
    // Sometimes an output lands on purpose near (or on) another buffer.
    if layout == 7 || input.rare(16) {
        let target = if input.u8() % 2 == 0 { TAN } else { BIT };
        let source = input.below(6);
        let delta = (input.u8() as i8 as isize) % 20;
        bufs[target].base = (bufs[source].base as isize + delta).clamp(0, ARENA as isize - 1) as usize;
    }
    for b in &mut bufs {
        b.clamp_into(ARENA);
    }

    let mesh_null = input.rare(64);
    let output_null = input.rare(64);
    let options_null = input.rare(16);
    let report_null = input.rare(8);
    // Method codes up to 8 cover the defined ones and the first undefined ones.
    let method = match input.u8() % 16 {
        0..=5 => 0,
        6..=9 => TBASIS_METHOD_LENGYEL,
        10..=14 => u32::from(input.u8() % 9),
        _ => input.u32(),
    };
    let policy = match input.u8() % 16 {
        0..=2 => 0,
        3..=5 => TBASIS_DEGENERATE_LEGACY,
        6..=8 => TBASIS_DEGENERATE_SKIP,
        9..=11 => TBASIS_DEGENERATE_INHERIT,
        12 | 13 => TBASIS_DEGENERATE_REJECT,
        14 => 5,
        _ => input.u32(),
    };
    let flags = match input.u8() % 8 {
        0..=4 => 0,
        5 | 6 => TBASIS_FLAG_FLIP_V,
        _ => input.u32(),
    };
    let threads = match input.u8() % 8 {
        0..=4 => 0,
        5 => 1,
        6 => 4,
        _ => input.u32(),
    };
    let threshold = match input.u8() % 16 {
        0..=7 => 0.0,
        8 => -0.0,
        9 => 1e-5,
        10 => 0.1,
        11 => 1.0,
        12 => 2.0,
        13 => [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -1e-5, -0.5][input.u8() as usize % 5],
        14 => f32::from_bits(input.u32()),
        _ => [f32::from_bits(1), f32::MIN_POSITIVE, 0.999, f32::MAX, 1e-30][input.u8() as usize % 5],
    };

    let needed = scratch_needed(
        vertex_count,
        &bufs[IDX],
        options_null,
        [method, policy, flags, threads],
        threshold,
    );
    let scratch = pick_scratch(input, needed, &bufs);
    let struct_offsets = [input.below(8), input.below(8), input.below(8), input.below(9)];
    let arena_fill = input.u8();
    let scratch_fill = input.u8();
    let encodings = [pick_encoding(input), pick_encoding(input), pick_encoding(input)];
    Plan {
        corners: false,
        vertex_count,
        bufs,
        index_type,
        mesh_null,
        output_null,
        options_null,
        report_null,
        method,
        policy,
        flags,
        threads,
        threshold,
        scratch,
        scratch_needed: needed,
        struct_offsets,
        arena_fill,
        scratch_fill,
        encodings,
    }
}

/// Bytes of caller scratch `tbasis_scratch_size` asks for this mesh and these options (`codes`:
/// method, policy, flags, threads); for NULL options checked against the documented formula
/// (MIKKTSPACE's is the library's unit test's to check: the calls use exactly the size asked
/// for, or a little less or more).
fn scratch_needed(vertex_count: usize, indices: &Buf, options_null: bool, codes: [u32; 4], threshold: f32) -> usize {
    let [method, policy, flags, threads] = codes;
    // Only the counts and whether `indices` is NULL are read (method MIKKTSPACE's size depends on
    // the index count); no pointer is followed.
    let probe = tbasis_mesh {
        vertex_count,
        positions: ptr::null(),
        positions_stride: 0,
        normals: ptr::null(),
        normals_stride: 0,
        texcoords: ptr::null(),
        texcoords_stride: 0,
        indices: if indices.null {
            ptr::null()
        } else {
            ptr::NonNull::<u32>::dangling().as_ptr().cast()
        },
        index_count: indices.count,
        index_type: 0,
    };
    let options = tbasis_options {
        method,
        degenerate_policy: policy,
        flags,
        threads,
        degenerate_threshold: threshold,
        scratch: ptr::null_mut(),
        scratch_size: 0,
    };
    // SAFETY: `probe` and `options` are readable descriptions; options may be NULL.
    let needed = unsafe { tbasis_scratch_size(&probe, if options_null { ptr::null() } else { &options }) };
    let for_null_options = unsafe { tbasis_scratch_size(&probe, ptr::null()) };
    // The defaults are policy INHERIT: `37 V + 4 C + 3`, or `45 V + 8 C + 3` once V or C passes
    // 32 bits (the header's formula).
    let corners = if indices.null { vertex_count } else { indices.count };
    let (per_vertex_bytes, per_corner_bytes) = if vertex_count.max(corners) > u32::MAX as usize {
        (45, 8)
    } else {
        (37, 4)
    };
    let per_vertex = if vertex_count == 0 {
        Some(0)
    } else {
        vertex_count
            .checked_mul(per_vertex_bytes)
            .and_then(|n| n.checked_add(corners.checked_mul(per_corner_bytes)?))
            .and_then(|n| n.checked_add(3))
    };
    assert_eq!(
        for_null_options,
        per_vertex.unwrap_or(usize::MAX),
        "tbasis_scratch_size({vertex_count})"
    );
    // SAFETY: NULL is allowed.
    assert_eq!(unsafe { tbasis_scratch_size(ptr::null(), ptr::null()) }, usize::MAX);
    needed
}

/// Where the caller scratch goes, for `needed` bytes: usually none, sometimes exactly the size
/// asked for, a little less or more, inside the main arena (after the buffers or anywhere), or a
/// claimed size whose span overflows.
fn pick_scratch(input: &mut Input, needed: usize, bufs: &[Buf]) -> ScratchPlan {
    let mut scratch = ScratchPlan {
        null: true,
        claimed: 0,
        ..Default::default()
    };
    match input.u8() % 8 {
        0..=3 => {
            if input.rare(4) {
                scratch.claimed = input.u64() as usize;
            }
        }
        // Exactly the size asked for, at every alignment.
        4 if needed <= OWN_SCRATCH_MAX => {
            scratch = own_scratch(input.below(4), needed);
        }
        // A little too small, or larger.
        5 if needed <= OWN_SCRATCH_MAX => {
            let claimed = if needed > 0 && input.u8() % 2 == 0 {
                needed - 1 - input.below(needed.min(8))
            } else {
                needed + input.below(64)
            };
            scratch = own_scratch(input.below(4), claimed);
        }
        // Inside the main arena: after the buffers, or anywhere (likely overlapping them).
        6 if needed <= ARENA - 16 => {
            let claimed = needed + input.below(16);
            let base = if input.u8() % 2 == 0 {
                input.below(ARENA - claimed + 1)
            } else {
                (end_of(bufs) + input.below(8)).min(ARENA - claimed)
            };
            scratch = ScratchPlan {
                null: false,
                in_main: true,
                base,
                claimed,
                arena_len: 0,
            };
        }
        // A claimed size whose span overflows; never touched.
        _ => {
            scratch = ScratchPlan {
                null: false,
                in_main: false,
                base: input.below(4),
                claimed: (1usize << 63) | input.u64() as usize,
                arena_len: 8,
            };
        }
    }
    scratch
}

/// The end of the last of `bufs` placed in the main arena.
fn end_of<'a>(bufs: impl IntoIterator<Item = &'a Buf>) -> usize {
    bufs.into_iter()
        .filter(|b| b.placed(ARENA))
        .map(|b| b.base + b.extent().unwrap_or(0))
        .max()
        .unwrap_or(0)
}

/// The `tbasis_generate_corners` call that follows the `tbasis_generate` call of `vertices`, on
/// the same mesh, decoded from the bytes left over (all zeros: the same options, the tangents
/// packed after the inputs, no caller scratch). Its tangents hold a frame per corner.
pub fn decode_corners_plan(input: &mut Input, vertices: &Plan) -> Plan {
    let mut plan = vertices.clone();
    plan.corners = true;
    plan.output_null = false;
    plan.bufs[BIT] = Buf {
        null: true,
        ..Buf::default()
    };
    // Another method or policy sometimes, so that every one meets every layout.
    match input.u8() % 16 {
        0..=9 => {}
        10..=14 => plan.method = u32::from(input.u8() % 7),
        _ => plan.method = input.u32(),
    }
    match input.u8() % 8 {
        0..=5 => {}
        6 => plan.policy = u32::from(input.u8() % 6),
        _ => plan.flags ^= TBASIS_FLAG_FLIP_V,
    }
    if input.rare(8) {
        plan.threads = u32::from(input.u8() % 4);
    }
    plan.options_null = input.rare(16);
    plan.report_null = input.rare(8);
    plan.mesh_null = input.rare(64);

    let indices = &plan.bufs[IDX];
    let corner_count = if indices.null { plan.vertex_count } else { indices.count };
    let tangents = &mut plan.bufs[TAN];
    *tangents = Buf {
        null: input.rare(32),
        base: 0,
        stride: 0,
        size: 16,
        count: corner_count,
    };
    tangents.stride = pick_stride(input, 16, corner_count);
    let inputs = [
        &vertices.bufs[POS],
        &vertices.bufs[NRM],
        &vertices.bufs[UV],
        &vertices.bufs[IDX],
    ];
    tangents.base = match input.u8() % 8 {
        // After the inputs, or anywhere, or near (or on) one of them.
        0..=5 => end_of(inputs) + input.u8() as usize % 8,
        6 => input.below(ARENA),
        _ => {
            let near = inputs[input.below(inputs.len())].base as isize;
            (near + (input.u8() as i8 as isize) % 20).clamp(0, ARENA as isize - 1) as usize
        }
    };
    tangents.clamp_into(ARENA);

    let codes = [plan.method, plan.policy, plan.flags, plan.threads];
    plan.scratch_needed = scratch_needed(
        plan.vertex_count,
        &plan.bufs[IDX],
        plan.options_null,
        codes,
        plan.threshold,
    );
    plan.scratch = pick_scratch(input, plan.scratch_needed, &plan.bufs);
    plan.struct_offsets = [input.below(8), input.below(8), 0, input.below(9)];
    plan.scratch_fill = input.u8();
    if debugging() {
        eprintln!("corners call: {plan:#?}");
    }
    plan
}

fn own_scratch(base: usize, claimed: usize) -> ScratchPlan {
    ScratchPlan {
        null: false,
        in_main: false,
        base,
        claimed,
        // Exactly as long as claimed, so the sanitizer sees a write past the end.
        arena_len: base + claimed,
    }
}

pub fn write_inputs(input: &mut Input, plan: &Plan, arena: &mut [u8]) {
    fill_vectors::<3>(input, plan.encodings[0], &plan.bufs[POS], ARENA, arena);
    fill_vectors::<3>(input, plan.encodings[1], &plan.bufs[NRM], ARENA, arena);
    fill_vectors::<2>(input, plan.encodings[2], &plan.bufs[UV], ARENA, arena);
    let indices = &plan.bufs[IDX];
    if indices.placed(ARENA) {
        for k in 0..indices.count {
            let value = index_value(input, plan.vertex_count);
            let at = indices.element(k);
            if plan.index_type == TBASIS_INDEX_U16 {
                arena[at..at + 2].copy_from_slice(&(value as u16).to_le_bytes());
            } else {
                arena[at..at + 4].copy_from_slice(&value.to_le_bytes());
            }
        }
    }
}

/// The index values as the library will read them (the arena as it was before the call).
pub fn read_indices(plan: &Plan, arena: &[u8]) -> Vec<usize> {
    let indices = &plan.bufs[IDX];
    (0..indices.count)
        .map(|k| {
            let at = indices.element(k);
            if plan.index_type == TBASIS_INDEX_U16 {
                u16::from_le_bytes([arena[at], arena[at + 1]]) as usize
            } else {
                u32::from_le_bytes(arena[at..at + 4].try_into().unwrap()) as usize
            }
        })
        .collect()
}

/// The valid footprints the overlap rule compares, in the main arena.
pub struct Footprints {
    pub inputs: Vec<Buf>,
    pub tangents: Option<Buf>,
    pub bitangents: Option<Buf>,
    /// The caller scratch as one range (when it lies in the main arena).
    pub scratch: Option<Buf>,
}

impl Footprints {
    pub fn of(plan: &Plan) -> Footprints {
        let b = &plan.bufs;
        let valid = |k: usize| (b[k].valid_footprint() && b[k].placed(ARENA)).then_some(b[k]);
        let mut inputs: Vec<Buf> = [POS, NRM].into_iter().filter_map(valid).collect();
        if !b[UV].null {
            inputs.extend(valid(UV));
        }
        if !b[IDX].null && plan.index_type_valid() {
            inputs.extend(valid(IDX));
        }
        let s = plan.scratch.buf();
        let scratch = (plan.uses_scratch() && plan.scratch.in_main && s.valid_footprint() && s.placed(ARENA))
            .then_some(Buf {
                stride: s.count,
                size: s.count,
                count: 1,
                ..s
            });
        Footprints {
            inputs,
            tangents: valid(TAN),
            bitangents: if b[BIT].null { None } else { valid(BIT) },
            scratch,
        }
    }

    /// An output shares a byte with an input, the other output or the scratch, or the scratch
    /// shares one with an input.
    pub fn overlapping(&self) -> bool {
        let meets = |a: &Option<Buf>, others: &[Option<Buf>]| {
            a.is_some_and(|a| others.iter().flatten().any(|o| a.shares_bytes(o)))
        };
        let inputs: Vec<Option<Buf>> = self.inputs.iter().copied().map(Some).collect();
        let with = |extra: &[Option<Buf>]| inputs.iter().chain(extra).copied().collect::<Vec<_>>();
        meets(&self.tangents, &with(&[self.bitangents, self.scratch]))
            || meets(&self.bitangents, &with(&[self.scratch]))
            || meets(&self.scratch, &inputs)
    }
}

/// Checks the harness's own promise: whatever the library might touch lies in owned memory,
/// and whatever does not fit is something the library must refuse before touching it.
pub fn assert_harness_sound(plan: &Plan) {
    let b = &plan.bufs;
    let mut candidates = vec![POS, NRM, TAN];
    for k in [UV, BIT] {
        if !b[k].null {
            candidates.push(k);
        }
    }
    if !b[IDX].null && plan.index_type_valid() {
        candidates.push(IDX);
    }
    for k in candidates {
        if !b[k].null && !b[k].placed(ARENA) {
            assert!(
                b[k].violations() != 0,
                "harness: {} does not fit and is valid",
                NAMES[k]
            );
        }
    }
    if plan.uses_scratch() {
        let s = plan.scratch.buf();
        let len = if plan.scratch.in_main {
            ARENA
        } else {
            plan.scratch.arena_len
        };
        if !s.placed(len) {
            assert!(s.violations() != 0, "harness: the scratch does not fit and is valid");
        }
    }
}

/// Prints the mesh as the call read it (for `FUZZ_DEBUG=1`).
pub fn describe(plan: &Plan, arena: &[u8]) {
    let b = &plan.bufs;
    for i in 0..plan.vertex_count.min(MAX_VERTICES) {
        let get = |k: usize, n: usize| -> Vec<f32> {
            if b[k].placed(ARENA) {
                (0..n).map(|c| f32_at(arena, b[k].element(i) + 4 * c)).collect()
            } else {
                Vec::new()
            }
        };
        eprintln!("v{i}: p {:?} n {:?} uv {:?}", get(POS, 3), get(NRM, 3), get(UV, 2));
    }
    if b[IDX].placed(ARENA) {
        eprintln!("indices {:?}", read_indices(plan, arena));
    }
}

pub fn triangles_of(plan: &Plan, arena: &[u8]) -> Vec<[usize; 3]> {
    if plan.bufs[IDX].null {
        (0..plan.vertex_count / 3)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect()
    } else {
        read_indices(plan, arena)
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect()
    }
}
