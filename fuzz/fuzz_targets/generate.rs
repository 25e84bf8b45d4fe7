//! Fuzzes the C ABI: `tbasis_generate` (and, for some inputs, `tbasis_calculate_tangent_array`).
//!
//! The input bytes choose a vertex count, strides, where each buffer sits inside one byte arena
//! (unaligned, interleaved, overlapping on purpose), which pointers are NULL, the indices, the
//! options, an optional caller scratch, and the float contents. Every pointer stays inside memory
//! this harness owns, and every span the library may touch lies inside it, so a sanitizer report
//! or a failed check is the library's fault. After each call the harness checks, independently of
//! the library's code:
//!
//! - the status is one the description allows (an error the inputs really contain; OK when they
//!   contain none);
//! - on an error, no byte changed (the caller scratch excepted: it is working memory), and the
//!   report is untouched unless the status is DEGENERATE_UV;
//! - on OK, only tangent and bitangent elements (and the scratch) changed, and the report adds up;
//! - on OK with method LENGYEL and policy LEGACY, the bits equal those of the C port of the
//!   original listing, `c_tests/listing.c` (as do those of `tbasis_calculate_tangent_array`);
//! - on OK with the other policies, tangents are finite unit vectors orthogonal to the normalized
//!   normal, `w` is exactly +1 or -1, bitangents are `w * cross(n, t)`, and the result is the same
//!   with or without caller scratch.
//!
//! `FUZZ_DEBUG=1` prints the decoded call, the mesh and the report of each input run.
//!
//! `fuzz/regressions/` holds the inputs of past findings (replayed by `.ci/fuzz.sh`), all fixed:
//! - `empty-mesh-unaligned-scratch`: no vertices, a non-NULL 0-byte scratch at an address 1 mod 4
//!   was refused with SCRATCH_TOO_SMALL;
//! - `tangent-not-orthogonal-near-normal`: a tangent sum nearly along the normal left the tangent
//!   1.7e-4 off orthogonal;
//! - `lengyel-tiny-tangent-not-orthogonal`, `lengyel-tiny-tangent-huge-uv`: method LENGYEL with
//!   position edges far smaller than UV edges (a subnormal-scale dP/du) left the tangent far off
//!   orthogonal.
#![no_main]

#[path = "../../c_tests/listing.rs"]
mod listing;

use core::ffi::{c_long, c_void, CStr};
use core::mem::size_of;
use core::ptr;

use libfuzzer_sys::fuzz_target;
use listing::listing_tangents;
use tbasis::ffi::*;

/// Bytes of the arena holding every buffer of a `tbasis_generate` call.
const ARENA: usize = 12 * 1024;
/// Bytes of the arena of a `tbasis_calculate_tangent_array` call.
const LISTING_ARENA: usize = 4 * 1024;
const MAX_VERTICES: usize = 64;
const MAX_TRIANGLES: usize = 96;
/// Tolerance on unit length and orthogonality for the robust policies.
const TOLERANCE: f64 = 1e-4;

// Buffers of a `tbasis_generate` call.
const POS: usize = 0;
const NRM: usize = 1;
const UV: usize = 2;
const TAN: usize = 3;
const BIT: usize = 4;
const IDX: usize = 5;
const NAMES: [&str; 6] = ["positions", "normals", "texcoords", "tangents", "bitangents", "indices"];

const REPORT_BYTES: usize = size_of::<tbasis_report>();
/// The report goes at an unaligned offset inside a larger buffer, to catch writes beside it.
const REPORT_BUFFER: usize = REPORT_BYTES + 16;
const REPORT_FILL: u8 = 0x5a;

fuzz_target!(|data: &[u8]| run(data));

fn run(data: &[u8]) {
    let mut input = Input { data, pos: 0 };
    let also_listing = input.u8() % 4 == 3;
    let plan = decode_plan(&mut input);
    let mut arena = vec![plan.arena_fill; ARENA];
    write_inputs(&mut input, &plan, &mut arena);
    let mut scratch_arena = vec![plan.scratch_fill; plan.scratch.arena_len];
    check_generate(&plan, &mut arena, &mut scratch_arena);
    if also_listing {
        check_listing_entry(&mut input);
    }
}

/// The fuzzer's bytes, read front to back; zeros once they run out.
struct Input<'a> {
    data: &'a [u8],
    pos: usize,
}

impl Input<'_> {
    fn u8(&mut self) -> u8 {
        let byte = self.data.get(self.pos).copied().unwrap_or(0);
        self.pos = self.pos.saturating_add(1);
        byte
    }
    fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }
    fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }
    fn u64(&mut self) -> u64 {
        u64::from(self.u32()) | (u64::from(self.u32()) << 32)
    }
    /// A value below `n` (0 when `n` is 0).
    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            self.u32() as usize % n
        }
    }
    /// True about once in `n`; false on exhausted input, so short inputs stay ordinary.
    fn rare(&mut self, n: u8) -> bool {
        self.u8() % n == n - 1
    }
}

/// One strided buffer in an arena: `count` elements of `size` bytes, `stride` apart from `base`.
#[derive(Clone, Copy, Debug, Default)]
struct Buf {
    null: bool,
    base: usize,
    stride: usize,
    size: usize,
    count: usize,
}

impl Buf {
    /// Bytes from the first element's start to the last one's end, if that is a number.
    fn extent(&self) -> Option<usize> {
        if self.count == 0 {
            return Some(0);
        }
        (self.count - 1).checked_mul(self.stride)?.checked_add(self.size)
    }

    /// The harness wrote (and the library may access) this buffer inside an arena of `len` bytes.
    /// A short stride can squeeze a huge count into a few bytes: such a buffer is not placed.
    fn placed(&self, len: usize) -> bool {
        !self.null && self.count <= len && self.extent().is_some_and(|e| e <= len.saturating_sub(self.base))
    }

    /// Status bits for what the header says is wrong with this buffer on its own:
    /// a stride below the element size, a span that does not fit, NULL with elements.
    fn violations(&self) -> u32 {
        let mut bits = 0;
        if self.stride < self.size {
            bits |= bit(TBASIS_ERROR_INVALID_STRIDE);
        } else if self.count > 0 && self.extent().is_none_or(|e| e > isize::MAX as usize) {
            bits |= bit(TBASIS_ERROR_SIZE_OVERFLOW);
        }
        if self.null && self.count > 0 {
            bits |= bit(TBASIS_ERROR_NULL_POINTER);
        }
        bits
    }

    /// Whether the library may see the bytes of this buffer as a valid footprint.
    fn valid_footprint(&self) -> bool {
        !self.null && self.count > 0 && self.violations() == 0
    }

    fn element(&self, i: usize) -> usize {
        self.base + i * self.stride
    }

    /// Whether some element shares a byte with `lo..hi`: only the first element ending after
    /// `lo` can (element starts grow with the index, and the stride covers the size).
    fn hits(&self, lo: usize, hi: usize) -> bool {
        if lo >= hi || self.count == 0 || self.size == 0 {
            return false;
        }
        let first = if self.base + self.size > lo {
            0
        } else {
            (lo - self.base - self.size) / self.stride + 1
        };
        first < self.count && self.base + first * self.stride < hi
    }

    /// Whether the two buffers share a byte (both valid footprints).
    fn shares_bytes(&self, other: &Buf) -> bool {
        (0..self.count).any(|i| other.hits(self.element(i), self.element(i) + self.size))
    }

    /// The element byte ranges.
    fn ranges(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..self.count).map(|i| (self.element(i), self.element(i) + self.size))
    }

    /// Moves the base back so the buffer fits, when it can fit at all.
    fn clamp_into(&mut self, len: usize) {
        match self.extent() {
            Some(e) if e <= len => self.base = self.base.min(len - e),
            _ => self.base %= len,
        }
    }
}

fn bit(status: tbasis_status) -> u32 {
    1u32 << status.min(31)
}

/// Where the caller scratch is, if any.
#[derive(Clone, Copy, Debug, Default)]
struct ScratchPlan {
    /// NULL pointer (then `claimed` is any value and must be ignored).
    null: bool,
    /// In the main arena at `base`; otherwise in its own arena at `base`.
    in_main: bool,
    base: usize,
    /// `scratch_size` as passed.
    claimed: usize,
    /// Bytes of its own arena.
    arena_len: usize,
}

impl ScratchPlan {
    fn buf(&self) -> Buf {
        Buf {
            null: self.null,
            base: self.base,
            stride: 1,
            size: 1,
            count: self.claimed,
        }
    }
}

/// Everything one `tbasis_generate` call is made of.
#[derive(Debug)]
struct Plan {
    vertex_count: usize,
    bufs: [Buf; 6],
    index_type: u32,
    mesh_null: bool,
    output_null: bool,
    options_null: bool,
    report_null: bool,
    method: u32,
    policy: u32,
    flags: u32,
    threads: u32,
    threshold: f32,
    scratch: ScratchPlan,
    /// What `tbasis_scratch_size` asks for this mesh and these options.
    scratch_needed: usize,
    /// Unaligned offsets of the mesh, options, output and report structs in their buffers.
    struct_offsets: [usize; 4],
    arena_fill: u8,
    scratch_fill: u8,
    encodings: [Encoding; 3],
}

impl Plan {
    fn effective_policy(&self) -> u32 {
        if self.options_null {
            0
        } else {
            self.policy
        }
    }
    fn index_type_valid(&self) -> bool {
        self.index_type == TBASIS_INDEX_U16 || self.index_type == TBASIS_INDEX_U32
    }
    fn uses_scratch(&self) -> bool {
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

fn shuffle(input: &mut Input, items: &mut [usize]) {
    for i in (1..items.len()).rev() {
        let j = input.below(i + 1);
        items.swap(i, j);
    }
}

fn decode_plan(input: &mut Input) -> Plan {
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
            for k in POS..=BIT {
                bufs[k].stride = pick_stride(input, bufs[k].size, vertex_count);
            }
            for b in &mut bufs {
                let room = b.extent().map_or(ARENA, |e| ARENA.saturating_sub(e) + 1);
                b.base = input.below(room);
            }
        }
        // Packed one after another in some order, with small gaps (or small overlaps).
        _ => {
            for k in POS..=BIT {
                bufs[k].stride = pick_stride(input, bufs[k].size, vertex_count);
            }
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

    // The scratch size comes from the library, which must agree with the documented formula.
    let probe = tbasis_mesh {
        vertex_count,
        positions: ptr::null(),
        positions_stride: 0,
        normals: ptr::null(),
        normals_stride: 0,
        texcoords: ptr::null(),
        texcoords_stride: 0,
        // Only the counts matter (method MIKKTSPACE's size depends on the index count); the
        // pointer is never read.
        indices: if bufs[IDX].null {
            ptr::null()
        } else {
            ptr::NonNull::<u32>::dangling().as_ptr().cast()
        },
        index_count: bufs[IDX].count,
        index_type: 0,
    };
    // The size for these options (it may depend on them), and for NULL options (documented).
    let probe_options = tbasis_options {
        method,
        degenerate_policy: policy,
        flags,
        threads,
        degenerate_threshold: threshold,
        scratch: ptr::null_mut(),
        scratch_size: 0,
    };
    // SAFETY: `probe` and `probe_options` are readable descriptions; options may be NULL.
    let needed = unsafe { tbasis_scratch_size(&probe, if options_null { ptr::null() } else { &probe_options }) };
    let for_null_options = unsafe { tbasis_scratch_size(&probe, ptr::null()) };
    let documented = if vertex_count == 0 {
        0
    } else {
        vertex_count
            .checked_mul(29)
            .and_then(|n| n.checked_add(3))
            .unwrap_or(usize::MAX)
    };
    assert_eq!(for_null_options, documented, "tbasis_scratch_size({vertex_count})");
    // SAFETY: NULL is allowed.
    assert_eq!(unsafe { tbasis_scratch_size(ptr::null(), ptr::null()) }, usize::MAX);

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
        4 if needed <= ARENA => {
            scratch = own_scratch(input.below(4), needed);
        }
        // A little too small, or larger.
        5 if needed <= ARENA => {
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
                let end = bufs
                    .iter()
                    .filter(|b| b.placed(ARENA))
                    .map(|b| b.base + b.extent().unwrap_or(0))
                    .max()
                    .unwrap_or(0);
                (end + input.below(8)).min(ARENA - claimed)
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

    let struct_offsets = [input.below(8), input.below(8), input.below(8), input.below(9)];
    let arena_fill = input.u8();
    let scratch_fill = input.u8();
    let encodings = [pick_encoding(input), pick_encoding(input), pick_encoding(input)];
    Plan {
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

/// How float values are drawn from the input.
#[derive(Clone, Copy, Debug)]
enum Encoding {
    /// Small multiples of 1/8: ordinary meshes.
    Small,
    /// Small integers times a large or tiny scale.
    Scaled(f32),
    /// Small integers, each vector normalized (unit normals).
    Unit,
    /// Any bit pattern: NaN, inf, subnormals, huge values.
    Raw,
    /// Values from a table of edge cases.
    Special,
    /// A per-value mix of the above.
    Mixed,
}

const SCALES: [f32; 6] = [1e-30, 1e-20, 1e-6, 1e6, 1e20, 1e30];
const SPECIALS: [f32; 20] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    2.0,
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::MIN_POSITIVE,
    f32::from_bits(1),
    f32::MAX,
    -f32::MAX,
    1e-20,
    1e20,
    1e-7,
    1e7,
    3.0e38,
    -1e-38,
    0.1,
];

fn pick_encoding(input: &mut Input) -> Encoding {
    match input.u8() % 12 {
        0..=4 => Encoding::Small,
        5 | 6 => Encoding::Unit,
        7 => Encoding::Raw,
        8 => Encoding::Special,
        9 | 10 => Encoding::Mixed,
        _ => Encoding::Scaled(SCALES[input.u8() as usize % SCALES.len()]),
    }
}

fn small(input: &mut Input) -> f32 {
    f32::from(input.u8() as i8) / 8.0
}

fn scalar(input: &mut Input, encoding: Encoding) -> f32 {
    match encoding {
        Encoding::Small | Encoding::Unit => small(input),
        Encoding::Scaled(scale) => f32::from(input.u8() as i8) * scale,
        Encoding::Raw => f32::from_bits(input.u32()),
        Encoding::Special => SPECIALS[input.u8() as usize % SPECIALS.len()],
        Encoding::Mixed => match input.u8() {
            0..=159 => small(input),
            160..=223 => SPECIALS[input.u8() as usize % SPECIALS.len()],
            _ => f32::from_bits(input.u32()),
        },
    }
}

fn vector<const N: usize>(input: &mut Input, encoding: Encoding) -> [f32; N] {
    let mut v = [0.0f32; N];
    for x in &mut v {
        *x = scalar(input, encoding);
    }
    if let Encoding::Unit = encoding {
        let length = v.iter().map(|x| x * x).sum::<f32>().sqrt();
        if length > 0.0 {
            v.iter_mut().for_each(|x| *x /= length);
        }
    }
    v
}

fn put_f32(bytes: &mut [u8], at: usize, value: f32) {
    bytes[at..at + 4].copy_from_slice(&value.to_le_bytes());
}

fn f32_at(bytes: &[u8], at: usize) -> f32 {
    f32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
}

fn vec_at<const N: usize>(bytes: &[u8], at: usize) -> [f32; N] {
    core::array::from_fn(|k| f32_at(bytes, at + 4 * k))
}

/// Writes `count` vectors of `N` floats into `buf` (elements may overlap when the stride is short).
fn fill_vectors<const N: usize>(input: &mut Input, encoding: Encoding, buf: &Buf, len: usize, arena: &mut [u8]) {
    if !buf.placed(len) {
        return;
    }
    for i in 0..buf.count {
        let v: [f32; N] = vector(input, encoding);
        for (k, x) in v.into_iter().enumerate() {
            put_f32(arena, buf.element(i) + 4 * k, x);
        }
    }
}

/// An index value: usually in range, sometimes just past it, sometimes anything.
fn index_value(input: &mut Input, vertex_count: usize) -> u32 {
    let b = input.u8();
    if b < 250 && vertex_count > 0 {
        return (b as usize % vertex_count.min(256)) as u32;
    }
    match input.u8() % 4 {
        0 => vertex_count as u32,
        1 => (vertex_count as u32).wrapping_add(1 + input.u8() as u32),
        2 => u16::MAX as u32,
        _ => input.u32(),
    }
}

fn write_inputs(input: &mut Input, plan: &Plan, arena: &mut [u8]) {
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
fn read_indices(plan: &Plan, arena: &[u8]) -> Vec<usize> {
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

/// The statuses the inputs call for: `hard` are certain errors, `soft` are ones the header is
/// ambiguous about (the call may also succeed).
struct Expect {
    hard: u32,
    soft: u32,
}

/// The valid footprints the overlap rule compares, in the main arena.
struct Footprints {
    inputs: Vec<Buf>,
    tangents: Option<Buf>,
    bitangents: Option<Buf>,
    /// The caller scratch as one range (when it lies in the main arena).
    scratch: Option<Buf>,
}

impl Footprints {
    fn of(plan: &Plan) -> Footprints {
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
    fn overlapping(&self) -> bool {
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

/// The first byte outside the `writable` ranges that differs, if any.
fn first_change_outside(before: &[u8], after: &[u8], mut writable: Vec<(usize, usize)>) -> Option<usize> {
    writable.sort_unstable();
    let end = before.len();
    let mut at = 0;
    for (lo, hi) in writable.into_iter().chain([(end, end)]) {
        if lo > at && before[at..lo] != after[at..lo] {
            return (at..lo).find(|&i| before[i] != after[i]);
        }
        at = at.max(hi);
    }
    None
}

fn expect_generate(plan: &Plan, arena: &[u8], footprints: &Footprints) -> Expect {
    let mut hard = 0;
    let mut soft = 0;
    if plan.mesh_null || plan.output_null {
        return Expect {
            hard: bit(TBASIS_ERROR_NULL_POINTER),
            soft,
        };
    }
    if !plan.options_null {
        if !known(Field::Method, plan.method) {
            hard |= bit(TBASIS_ERROR_UNKNOWN_METHOD);
        }
        if !known(Field::Policy, plan.policy) {
            hard |= bit(TBASIS_ERROR_UNKNOWN_POLICY);
        }
        if !known(Field::Flags, plan.flags) {
            hard |= bit(TBASIS_ERROR_UNKNOWN_FLAGS);
        }
        if !plan.threshold.is_finite() || plan.threshold < 0.0 {
            hard |= bit(TBASIS_ERROR_INVALID_THRESHOLD);
        }
    }
    let b = &plan.bufs;
    let vc = plan.vertex_count;
    hard |= b[POS].violations() | b[NRM].violations() | b[TAN].violations();
    // The header lists `output->tangents` as required; with no vertices the call may accept NULL.
    if b[TAN].null && vc == 0 {
        soft |= bit(TBASIS_ERROR_NULL_POINTER);
    }
    if !b[UV].null {
        hard |= b[UV].violations();
    } else if plan.effective_policy() == TBASIS_DEGENERATE_LEGACY
        || (!plan.options_null && plan.method == TBASIS_METHOD_MIKKTSPACE)
    {
        // The listing and mikktspace.c both need texture coordinates.
        hard |= bit(TBASIS_ERROR_NULL_POINTER);
    }
    if !b[BIT].null {
        hard |= b[BIT].violations();
    }
    if !b[IDX].null {
        if !plan.index_type_valid() {
            hard |= bit(TBASIS_ERROR_INVALID_INDEX_TYPE);
        } else {
            hard |= b[IDX].violations();
            if b[IDX].count % 3 != 0 {
                hard |= bit(TBASIS_ERROR_INVALID_INDEX_COUNT);
            } else if b[IDX].placed(ARENA) && read_indices(plan, arena).iter().any(|&i| i >= vc) {
                hard |= bit(TBASIS_ERROR_INDEX_OUT_OF_RANGE);
            }
        }
    } else {
        // `index_count` "must be 0 when indices is NULL"; NULL_POINTER covers "an index buffer
        // whose count is nonzero".
        if b[IDX].count != 0 {
            hard |= bit(TBASIS_ERROR_NULL_POINTER);
        }
        if vc % 3 != 0 {
            hard |= bit(TBASIS_ERROR_INVALID_INDEX_COUNT);
        }
    }
    if plan.uses_scratch() {
        let claimed = plan.scratch.claimed;
        if plan.scratch_needed == usize::MAX {
            hard |= bit(TBASIS_ERROR_SIZE_OVERFLOW);
        } else if claimed < plan.scratch_needed {
            hard |= bit(TBASIS_ERROR_SCRATCH_TOO_SMALL);
        }
        if claimed > isize::MAX as usize {
            hard |= bit(TBASIS_ERROR_SIZE_OVERFLOW);
        }
    }
    if footprints.overlapping() {
        hard |= bit(TBASIS_ERROR_OVERLAP);
    }
    Expect { hard, soft }
}

/// Checks the harness's own promise: whatever the library might touch lies in owned memory,
/// and whatever does not fit is something the library must refuse before touching it.
fn assert_harness_sound(plan: &Plan) {
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

#[derive(Clone, Copy, PartialEq, Eq)]
enum Field {
    Method,
    Policy,
    Flags,
}

/// Whether the library knows this method, policy or flags value. The set of codes grows with the
/// library, so it is asked once per value (a call on an empty mesh with only that field set);
/// the values the header has always defined must be known.
fn known(field: Field, value: u32) -> bool {
    use std::sync::atomic::{AtomicU8, Ordering};
    const CACHED: usize = 64;
    static CACHE: [[AtomicU8; CACHED]; 3] = [const { [const { AtomicU8::new(0) }; CACHED] }; 3];
    let slot = (value as usize) < CACHED;
    let row = field as usize;
    if slot {
        match CACHE[row][value as usize].load(Ordering::Relaxed) {
            1 => return true,
            2 => return false,
            _ => {}
        }
    }
    let byte = [0u8; 16];
    let any = byte.as_ptr().cast::<c_void>();
    let mut out = [0u8; 16];
    let mesh = tbasis_mesh {
        vertex_count: 0,
        positions: any,
        positions_stride: 12,
        normals: any,
        normals_stride: 12,
        texcoords: any,
        texcoords_stride: 8,
        indices: ptr::null(),
        index_count: 0,
        index_type: 0,
    };
    let options = tbasis_options {
        method: if field == Field::Method { value } else { 0 },
        degenerate_policy: if field == Field::Policy { value } else { 0 },
        flags: if field == Field::Flags { value } else { 0 },
        threads: 0,
        degenerate_threshold: 0.0,
        scratch: ptr::null_mut(),
        scratch_size: 0,
    };
    let output = tbasis_output {
        tangents: out.as_mut_ptr().cast(),
        tangents_stride: 16,
        bitangents: ptr::null_mut(),
        bitangents_stride: 0,
    };
    // SAFETY: an empty mesh; every pointer addresses owned bytes.
    let status = unsafe { tbasis_generate(&mesh, &options, &output, ptr::null_mut()) };
    let refusal = match field {
        Field::Method => TBASIS_ERROR_UNKNOWN_METHOD,
        Field::Policy => TBASIS_ERROR_UNKNOWN_POLICY,
        Field::Flags => TBASIS_ERROR_UNKNOWN_FLAGS,
    };
    assert!(
        status == TBASIS_OK || status == refusal,
        "empty mesh with only {} = {value}: status {status}",
        ["method", "policy", "flags"][row]
    );
    let documented = match field {
        Field::Method => value <= TBASIS_METHOD_LENGYEL,
        Field::Policy => value <= TBASIS_DEGENERATE_REJECT,
        Field::Flags => value & !TBASIS_FLAG_FLIP_V == 0,
    };
    assert!(
        !documented || status == TBASIS_OK,
        "documented value refused: {} = {value}",
        ["method", "policy", "flags"][row]
    );
    if slot {
        CACHE[row][value as usize].store(if status == TBASIS_OK { 1 } else { 2 }, Ordering::Relaxed);
    }
    status == TBASIS_OK
}

/// Makes one `tbasis_generate` call with the plan's descriptors built over `arena`; the report
/// buffer comes back whole.
fn call_generate(
    plan: &Plan,
    arena: &mut [u8],
    scratch_arena: &mut [u8],
    with_scratch: bool,
) -> (tbasis_status, Vec<u8>) {
    let arena_ptr = arena.as_mut_ptr();
    let scratch_ptr = scratch_arena.as_mut_ptr();
    // SAFETY: every base is below the arena length (clamped), so `add` stays in the allocation.
    let at = |buf: &Buf| -> *mut c_void {
        if buf.null {
            ptr::null_mut()
        } else {
            unsafe { arena_ptr.add(buf.base).cast() }
        }
    };
    let b = &plan.bufs;
    let mesh = tbasis_mesh {
        vertex_count: plan.vertex_count,
        positions: at(&b[POS]),
        positions_stride: b[POS].stride,
        normals: at(&b[NRM]),
        normals_stride: b[NRM].stride,
        texcoords: at(&b[UV]),
        texcoords_stride: b[UV].stride,
        indices: at(&b[IDX]),
        index_count: b[IDX].count,
        index_type: plan.index_type,
    };
    let scratch = if plan.scratch.null || !with_scratch {
        ptr::null_mut()
    } else if plan.scratch.in_main {
        unsafe { arena_ptr.add(plan.scratch.base).cast() }
    } else {
        unsafe { scratch_ptr.add(plan.scratch.base).cast() }
    };
    let options = tbasis_options {
        method: plan.method,
        degenerate_policy: plan.policy,
        flags: plan.flags,
        threads: plan.threads,
        degenerate_threshold: plan.threshold,
        scratch,
        scratch_size: plan.scratch.claimed,
    };
    let output = tbasis_output {
        tangents: at(&b[TAN]),
        tangents_stride: b[TAN].stride,
        bitangents: at(&b[BIT]),
        bitangents_stride: b[BIT].stride,
    };
    // The descriptors sit at unaligned addresses: the library must read them unaligned.
    let mut mesh_bytes = [0u8; size_of::<tbasis_mesh>() + 8];
    let mut options_bytes = [0u8; size_of::<tbasis_options>() + 8];
    let mut output_bytes = [0u8; size_of::<tbasis_output>() + 8];
    let mut report_bytes = vec![REPORT_FILL; REPORT_BUFFER];
    let [mo, oo, po, ro] = plan.struct_offsets;
    // SAFETY: each offset leaves room for its struct in its buffer; the writes are unaligned.
    let status = unsafe {
        let mesh_ptr = mesh_bytes.as_mut_ptr().add(mo).cast::<tbasis_mesh>();
        let options_ptr = options_bytes.as_mut_ptr().add(oo).cast::<tbasis_options>();
        let output_ptr = output_bytes.as_mut_ptr().add(po).cast::<tbasis_output>();
        ptr::write_unaligned(mesh_ptr, mesh);
        ptr::write_unaligned(options_ptr, options);
        ptr::write_unaligned(output_ptr, output);
        let report_ptr = report_bytes.as_mut_ptr().add(ro).cast::<tbasis_report>();
        tbasis_generate(
            if plan.mesh_null { ptr::null() } else { mesh_ptr },
            if plan.options_null { ptr::null() } else { options_ptr },
            if plan.output_null { ptr::null() } else { output_ptr },
            if plan.report_null { ptr::null_mut() } else { report_ptr },
        )
    };
    (status, report_bytes)
}

fn check_status_string(status: tbasis_status) {
    // SAFETY: the library returns a static NUL-terminated string for every value.
    let text = unsafe { CStr::from_ptr(tbasis_status_string(status)) };
    assert!(!text.to_bytes().is_empty(), "empty status string for {status}");
}

/// `status` is allowed by `expect`.
fn check_status(status: tbasis_status, expect: &Expect, policy: u32, what: &str) {
    check_status_string(status);
    assert_ne!(status, TBASIS_ERROR_INTERNAL, "{what}: TBASIS_ERROR_INTERNAL");
    match status {
        TBASIS_OK => assert!(
            expect.hard == 0,
            "{what}: TBASIS_OK, but the inputs call for statuses {:#x}",
            expect.hard
        ),
        TBASIS_ERROR_DEGENERATE_UV => assert!(
            expect.hard == 0 && policy == TBASIS_DEGENERATE_REJECT,
            "{what}: DEGENERATE_UV with policy {policy}, statuses due {:#x}",
            expect.hard
        ),
        e => assert!(
            e < 32 && (expect.hard | expect.soft) & bit(e) != 0,
            "{what}: status {e}, but the inputs call for {:#x} (or {:#x})",
            expect.hard,
            expect.soft
        ),
    }
}

/// `FUZZ_DEBUG=1` prints each decoded plan, to read a reproduced failure.
fn debugging() -> bool {
    static DEBUG: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *DEBUG.get_or_init(|| std::env::var_os("FUZZ_DEBUG").is_some())
}

/// Prints the mesh as the call read it (for `FUZZ_DEBUG=1`).
fn describe(plan: &Plan, arena: &[u8]) {
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

fn check_generate(plan: &Plan, arena: &mut [u8], scratch_arena: &mut [u8]) {
    if debugging() {
        eprintln!("{plan:#?}");
    }
    assert_harness_sound(plan);
    let before = arena.to_vec();
    let scratch_before = scratch_arena.to_vec();
    let (status, report_bytes) = call_generate(plan, arena, scratch_arena, true);

    let footprints = Footprints::of(plan);
    let expect = expect_generate(plan, &before, &footprints);
    let policy = plan.effective_policy();
    check_status(status, &expect, policy, "tbasis_generate");
    if debugging() {
        eprintln!("status {status} policy {policy} vertices {}", plan.vertex_count);
        describe(plan, &before);
    }

    // Which bytes may have changed: outputs on success; the caller scratch ("working memory: its
    // contents after a call, successful or not, mean nothing") unless it shares bytes with another
    // buffer (then the call must refuse before using it).
    let ok = status == TBASIS_OK;
    let mut writable = Vec::new();
    if ok {
        for k in [TAN, BIT] {
            if plan.bufs[k].placed(ARENA) {
                writable.extend(plan.bufs[k].ranges());
            }
        }
    }
    if let Some(s) = footprints.scratch {
        let others = footprints
            .inputs
            .iter()
            .chain(footprints.tangents.iter())
            .chain(footprints.bitangents.iter());
        if ok || !others.clone().any(|o| o.shares_bytes(&s)) {
            writable.push((s.base, s.base + s.size));
        }
    }
    if let Some(at) = first_change_outside(&before, arena, writable) {
        panic!(
            "tbasis_generate returned {status} and changed arena byte {at} ({:#04x} -> {:#04x}) outside its outputs",
            before[at], arena[at]
        );
    }
    if !plan.scratch.in_main {
        let s = plan.scratch;
        let claimed_end = s.base.saturating_add(s.claimed);
        let claimed = (s.base.min(scratch_arena.len()), claimed_end.min(scratch_arena.len()));
        if let Some(at) = first_change_outside(&scratch_before, scratch_arena, vec![claimed]) {
            panic!("tbasis_generate returned {status} and changed scratch-arena byte {at}");
        }
    }

    let report = check_report_bytes(plan, status, &report_bytes);
    if let (true, Some(r)) = (debugging(), report) {
        eprintln!("report: {}", describe_report(&r));
    }
    if ok && plan.method == TBASIS_METHOD_MIKKTSPACE {
        // Its bits are mikktspace.c's, checked against it by tests/mikktspace.rs; here only that
        // caller scratch changes nothing.
        if plan.uses_scratch() && plan.vertex_count > 0 {
            check_without_scratch(plan, &before, arena, &report_bytes);
        }
    } else if ok {
        let triangles = triangles_of(plan, &before);
        if let Some(report) = report {
            check_report(plan, status, &report, &triangles, &before);
        }
        check_outputs(plan, &before, arena, &triangles);
        if plan.uses_scratch() && plan.vertex_count > 0 {
            check_without_scratch(plan, &before, arena, &report_bytes);
        }
    } else if status == TBASIS_ERROR_DEGENERATE_UV {
        if let Some(report) = report {
            let triangles = triangles_of(plan, &before);
            check_report(plan, status, &report, &triangles, &before);
        }
    }
}

/// The same call without caller scratch must give the same bytes.
fn check_without_scratch(plan: &Plan, before: &[u8], with_scratch: &[u8], report_with: &[u8]) {
    let mut arena = before.to_vec();
    let mut unused = vec![0u8; 1];
    let (status, report) = call_generate(plan, &mut arena, &mut unused, false);
    assert_eq!(
        status, TBASIS_OK,
        "the call succeeds with caller scratch but not without"
    );
    for k in [TAN, BIT] {
        if !plan.bufs[k].placed(ARENA) {
            continue;
        }
        for i in 0..plan.vertex_count {
            let at = plan.bufs[k].element(i);
            let range = at..at + plan.bufs[k].size;
            assert_eq!(
                arena[range.clone()],
                with_scratch[range],
                "{} of vertex {i} differ with and without caller scratch",
                NAMES[k]
            );
        }
    }
    if !plan.report_null {
        assert_eq!(
            report, report_with,
            "the report differs with and without caller scratch"
        );
    }
}

/// Checks the bytes around the report and returns its fields when the call should have filled it.
fn check_report_bytes(plan: &Plan, status: tbasis_status, bytes: &[u8]) -> Option<tbasis_report> {
    let ro = plan.struct_offsets[3];
    let filled = !plan.report_null && (status == TBASIS_OK || status == TBASIS_ERROR_DEGENERATE_UV);
    let untouched = vec![REPORT_FILL; REPORT_BUFFER];
    let writable = if filled {
        vec![(ro, ro + REPORT_BYTES)]
    } else {
        Vec::new()
    };
    if let Some(at) = first_change_outside(&untouched, bytes, writable) {
        panic!("report buffer byte {at} changed (status {status})");
    }
    // SAFETY: `bytes` holds a whole report at `ro`; the read is unaligned.
    filled.then(|| unsafe { ptr::read_unaligned(bytes.as_ptr().add(ro).cast::<tbasis_report>()) })
}

fn triangles_of(plan: &Plan, arena: &[u8]) -> Vec<[usize; 3]> {
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

/// The report's counts add up, and say what the header says they say.
fn check_report(plan: &Plan, status: tbasis_status, report: &tbasis_report, triangles: &[[usize; 3]], arena: &[u8]) {
    let vc = plan.vertex_count;
    let policy = plan.effective_policy();
    let mut used = vec![false; vc];
    for t in triangles {
        t.iter().for_each(|&v| used[v] = true);
    }
    let expected_unreferenced = used.iter().filter(|u| !**u).count();
    let r = report;
    let context = format!("report ({}), status {status}, policy {policy}", describe_report(&r));
    assert!(
        r.degenerate_triangles <= triangles.len(),
        "{context}: more degenerate triangles than triangles"
    );
    if r.degenerate_triangles == 0 {
        assert_eq!(
            r.first_degenerate_triangle,
            usize::MAX,
            "{context}: first_degenerate_triangle without any"
        );
    } else {
        assert!(
            r.first_degenerate_triangle < triangles.len(),
            "{context}: first_degenerate_triangle out of range"
        );
    }
    assert_eq!(
        r.unreferenced_vertices, expected_unreferenced,
        "{context}: unreferenced_vertices"
    );
    assert!(
        r.mirrored_vertices <= vc - expected_unreferenced,
        "{context}: mirrored_vertices"
    );
    assert!(
        r.fallback_vertices.saturating_add(r.inherited_vertices) <= vc,
        "{context}: fallback + inherited"
    );
    if policy == TBASIS_DEGENERATE_LEGACY {
        assert_eq!(r.fallback_vertices, 0, "{context}: fallback_vertices under LEGACY");
        assert_eq!(r.abnormal_normals, 0, "{context}: abnormal_normals under LEGACY");
    }
    if policy != 0 && policy != TBASIS_DEGENERATE_INHERIT {
        assert_eq!(r.inherited_vertices, 0, "{context}: inherited_vertices without INHERIT");
    }
    if status == TBASIS_ERROR_DEGENERATE_UV {
        assert!(
            r.degenerate_triangles > 0,
            "{context}: DEGENERATE_UV without a degenerate triangle"
        );
    } else if policy == TBASIS_DEGENERATE_REJECT {
        assert_eq!(
            r.degenerate_triangles, 0,
            "{context}: REJECT succeeded with degenerate triangles"
        );
    }
    if plan.bufs[UV].null && policy != TBASIS_DEGENERATE_LEGACY {
        assert_eq!(
            r.fallback_vertices, vc,
            "{context}: without texcoords every vertex falls back"
        );
        assert_eq!(r.mirrored_vertices, 0, "{context}: mirrored vertices without texcoords");
    }
    if policy != TBASIS_DEGENERATE_LEGACY {
        // "Off unit length by more than 1e-3": a margin either side absorbs f32 rounding.
        let (mut surely, mut maybe) = (0, 0);
        for i in 0..vc {
            let n: [f32; 3] = vec_at(arena, plan.bufs[NRM].element(i));
            let off = if n.iter().all(|x| x.is_finite()) {
                (length(n.map(f64::from)) - 1.0).abs()
            } else {
                f64::INFINITY
            };
            surely += usize::from(off > 1.01e-3);
            maybe += usize::from(off > 0.99e-3);
        }
        assert!(
            (surely..=maybe).contains(&r.abnormal_normals),
            "{context}: abnormal_normals should be in {surely}..={maybe}"
        );
    }
}

fn same(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

fn check_outputs(plan: &Plan, before: &[u8], after: &[u8], triangles: &[[usize; 3]]) {
    let b = &plan.bufs;
    let vc = plan.vertex_count;
    let tangent = |i: usize| -> [f32; 4] { vec_at(after, b[TAN].element(i)) };
    let bitangent = |i: usize| -> Option<[f32; 3]> { (!b[BIT].null).then(|| vec_at(after, b[BIT].element(i))) };
    let normal = |i: usize| -> [f32; 3] { vec_at(before, b[NRM].element(i)) };

    if plan.effective_policy() == TBASIS_DEGENERATE_LEGACY {
        // The header promises the listing's bits for method LENGYEL; FLIP_V is not the listing.
        let listing_exact = plan.method == TBASIS_METHOD_LENGYEL && plan.flags & TBASIS_FLAG_FLIP_V == 0;
        if listing_exact {
            let expected = listing(
                vc,
                triangles,
                |i| vec_at(before, b[POS].element(i)),
                normal,
                |i| vec_at(before, b[UV].element(i)),
            );
            for (i, want) in expected.iter().enumerate() {
                let got = tangent(i);
                assert!(
                    (0..4).all(|k| same(got[k], want[k])),
                    "LEGACY tangent {i} is {got:?}, the listing gives {want:?}"
                );
            }
        }
        for i in 0..vc {
            let [x, y, z, w] = tangent(i);
            assert!(w == 1.0 || w == -1.0, "LEGACY w of vertex {i} is {w}");
            if let Some(got) = bitangent(i) {
                let n = normal(i);
                let c = [n[1] * z - n[2] * y, n[2] * x - n[0] * z, n[0] * y - n[1] * x];
                let want = c.map(|c| c * w);
                assert!(
                    (0..3).all(|k| same(got[k], want[k])),
                    "LEGACY bitangent {i} is {got:?}, w * cross(n, t) is {want:?}"
                );
            }
        }
        return;
    }

    for i in 0..vc {
        let t4 = tangent(i);
        let [x, y, z, w] = t4.map(f64::from);
        let t = [x, y, z];
        let context = || {
            format!(
                "vertex {i}: tangent {t4:?}, normal {:?}, bitangent {:?}",
                normal(i),
                bitangent(i)
            )
        };
        assert!(t4.iter().all(|v| v.is_finite()), "{}: not finite", context());
        assert!((length(t) - 1.0).abs() <= TOLERANCE, "{}: not unit length", context());
        assert!(w == 1.0 || w == -1.0, "{}: w is not +1 or -1", context());
        let n_hat = unit(normal(i));
        if let Some(n) = n_hat {
            assert!(
                dot(t, n).abs() <= TOLERANCE,
                "{}: not orthogonal to the normal",
                context()
            );
        }
        if let Some(b3) = bitangent(i) {
            let bv = b3.map(f64::from);
            assert!(b3.iter().all(|v| v.is_finite()), "{}: bitangent not finite", context());
            match n_hat {
                Some(n) => {
                    let want = cross(n, t).map(|c| c * w);
                    assert!(
                        (0..3).all(|k| (bv[k] - want[k]).abs() <= TOLERANCE),
                        "{}: bitangent is not w * cross(n, t)",
                        context()
                    );
                }
                None => {
                    assert!(
                        (length(bv) - 1.0).abs() <= TOLERANCE,
                        "{}: bitangent not unit",
                        context()
                    );
                    assert!(dot(bv, t).abs() <= TOLERANCE, "{}: bitangent not orthogonal", context());
                }
            }
        }
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn length(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// The normalized normal, when the normal is finite and not zero (f64 holds any f32 square).
fn unit(n: [f32; 3]) -> Option<[f64; 3]> {
    if !n.iter().all(|x| x.is_finite()) || n.iter().all(|&x| x == 0.0) {
        return None;
    }
    let n = n.map(f64::from);
    let len = length(n);
    Some(n.map(|x| x / len))
}

/// Lengyel's `CalculateTangentArray` (2001) as the C port `c_tests/listing.c` computes it (linked
/// by `fuzz/build.rs`, built with `-ffp-contract=off`), on packed copies of the inputs.
fn listing(
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

// `tbasis_calculate_tangent_array`: packed arrays, `long` counts.
const L_VERTEX: usize = 0;
const L_NORMAL: usize = 1;
const L_TEXCOORD: usize = 2;
const L_TRIANGLE: usize = 3;
const L_TANGENT: usize = 4;

/// A `long` count: usually small, sometimes negative, sometimes so large every span overflows.
fn long_count(input: &mut Input, small_max: u8, huge_bit: u32) -> c_long {
    match input.u8() % 16 {
        0 => {
            if input.rare(4) {
                c_long::MIN
            } else {
                -1 - c_long::from(input.u32() >> 1)
            }
        }
        1 => ((1u64 << huge_bit) | (input.u64() & c_long::MAX as u64)) as c_long,
        _ => c_long::from(input.u8() % (small_max + 1)),
    }
}

fn check_listing_entry(input: &mut Input) {
    // Huge vertex counts start at 2^60 (12-byte spans overflow), triangle counts at 2^61.
    let vertex_count = long_count(input, MAX_VERTICES as u8, 60);
    let triangle_count = long_count(input, 32, 61);
    let vc = usize::try_from(vertex_count).ok();
    let ic = usize::try_from(triangle_count).ok().and_then(|t| t.checked_mul(3));
    let mut bufs = [Buf::default(); 5];
    for (k, size) in [12, 12, 8, 2, 16].into_iter().enumerate() {
        bufs[k] = Buf {
            null: input.rare(32),
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
    shuffle(input, &mut order);
    let mut cursor = input.below(8);
    for k in order {
        bufs[k].base = cursor;
        cursor += bufs[k].extent().filter(|&e| e <= LISTING_ARENA).unwrap_or(0) + input.u8() as usize % 8;
    }
    if input.rare(4) {
        let source = input.below(4);
        let delta = (input.u8() as i8 as isize) % 20;
        bufs[L_TANGENT].base = (bufs[source].base as isize + delta).clamp(0, LISTING_ARENA as isize - 1) as usize;
    }
    for b in &mut bufs {
        b.clamp_into(LISTING_ARENA);
    }

    let mut arena = vec![input.u8(); LISTING_ARENA];
    let encodings = [pick_encoding(input), pick_encoding(input), pick_encoding(input)];
    fill_vectors::<3>(input, encodings[0], &bufs[L_VERTEX], LISTING_ARENA, &mut arena);
    fill_vectors::<3>(input, encodings[1], &bufs[L_NORMAL], LISTING_ARENA, &mut arena);
    fill_vectors::<2>(input, encodings[2], &bufs[L_TEXCOORD], LISTING_ARENA, &mut arena);
    let tri = bufs[L_TRIANGLE];
    if tri.placed(LISTING_ARENA) {
        for k in 0..tri.count {
            let value = index_value(input, vc.unwrap_or(0)) as u16;
            arena[tri.element(k)..tri.element(k) + 2].copy_from_slice(&value.to_le_bytes());
        }
    }

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
}

/// Every field of a report, for failure messages and `FUZZ_DEBUG`.
fn describe_report(r: &tbasis_report) -> String {
    format!(
        "degenerate {}, first {}, fallback {}, mirrored {}, unreferenced {}, inherited {}, abnormal {}",
        r.degenerate_triangles,
        r.first_degenerate_triangle,
        r.fallback_vertices,
        r.mirrored_vertices,
        r.unreferenced_vertices,
        r.inherited_vertices,
        r.abnormal_normals
    )
}
