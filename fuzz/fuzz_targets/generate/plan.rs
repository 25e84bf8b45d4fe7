//! What one call is made of, drawn from the fuzzer's bytes: the vertex count, where each buffer
//! sits in the arena, its stride, which pointers are NULL, the options and the caller scratch; and
//! the rules the header gives for each of them.

use core::ffi::c_void;
use core::ptr;

use arbitrary::{Arbitrary, Result, Unstructured};

use crate::codes::*;
use crate::ffi::*;
use crate::status::*;

use crate::arena::{bit, f32_at, fill_vectors, Buf};
use crate::call::debugging;
use crate::input::{
    below, index_values, nudge, one_in, pick_encoding, shuffle, weighted, Attribute, Encoding, IndexPattern,
};

/// Bytes of the arena holding every buffer of a call, at least; a large mesh gets more
/// ([`arena_len`]).
const MIN_ARENA: usize = 12 * 1024;
/// Bytes of a caller scratch in its own arena, at most (method MIKKTSPACE asks for about 130 per
/// corner).
pub const OWN_SCRATCH_MAX: usize = 4 << 20;
/// Most meshes have at most this many vertices and triangles...
pub const SMALL_VERTICES: usize = 64;
pub const SMALL_TRIANGLES: usize = 96;
/// ...about one in fifty up to this many (with about two triangles a vertex): enough for the
/// library's tables and mikktspace.c's welding and grouping to grow well past the small cases,
/// and small enough that such an input runs in milliseconds.
pub const MAX_VERTICES: usize = 4096;
pub const MAX_TRIANGLES: usize = 2 * MAX_VERTICES;

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

/// Which buffers of a `tbasis_generate` call are NULL.
#[derive(Arbitrary, Clone, Copy, Debug)]
struct BufferNulls {
    #[arbitrary(with = one_in::<32>)]
    positions: bool,
    #[arbitrary(with = one_in::<32>)]
    normals: bool,
    #[arbitrary(with = one_in::<8>)]
    texcoords: bool,
    #[arbitrary(with = one_in::<32>)]
    tangents: bool,
    /// Half the calls ask for no bitangents.
    bitangents: bool,
    #[arbitrary(with = one_in::<3>)]
    indices: bool,
}

/// Which struct pointers of a call are NULL.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub struct StructNulls {
    #[arbitrary(with = one_in::<64>)]
    pub mesh: bool,
    #[arbitrary(with = one_in::<64>)]
    pub output: bool,
    #[arbitrary(with = one_in::<16>)]
    pub options: bool,
    #[arbitrary(with = one_in::<8>)]
    pub report: bool,
}

/// The option codes of a call: mostly defined values, sometimes the first undefined ones or any
/// value.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub struct Codes {
    #[arbitrary(with = method_code)]
    pub method: u32,
    #[arbitrary(with = policy_code)]
    pub policy: u32,
    #[arbitrary(with = flags_code)]
    pub flags: u32,
    #[arbitrary(with = threads_code)]
    pub threads: u32,
    #[arbitrary(with = threshold_value)]
    pub threshold: f32,
}

/// Method codes up to 8 cover the defined ones and the first undefined ones.
fn method_code(u: &mut Unstructured) -> Result<u32> {
    Ok(match weighted(u, &[6, 4, 5, 1])? {
        0 => 0,
        1 => TBASIS_METHOD_LENGYEL,
        2 => u.int_in_range(0..=8)?,
        _ => u32::arbitrary(u)?,
    })
}

fn policy_code(u: &mut Unstructured) -> Result<u32> {
    Ok(match weighted(u, &[3, 3, 3, 3, 2, 1, 1])? {
        0 => 0,
        1 => TBASIS_DEGENERATE_LEGACY,
        2 => TBASIS_DEGENERATE_SKIP,
        3 => TBASIS_DEGENERATE_INHERIT,
        4 => TBASIS_DEGENERATE_REJECT,
        5 => 5,
        _ => u32::arbitrary(u)?,
    })
}

fn flags_code(u: &mut Unstructured) -> Result<u32> {
    Ok(match weighted(u, &[5, 2, 1])? {
        0 => 0,
        1 => TBASIS_FLAG_FLIP_V,
        _ => u32::arbitrary(u)?,
    })
}

fn threads_code(u: &mut Unstructured) -> Result<u32> {
    Ok(match weighted(u, &[5, 1, 1, 1])? {
        0 => 0,
        1 => 1,
        2 => 4,
        _ => u32::arbitrary(u)?,
    })
}

fn threshold_value(u: &mut Unstructured) -> Result<f32> {
    Ok(match weighted(u, &[8, 1, 1, 1, 1, 1, 1, 1, 1])? {
        0 => 0.0,
        1 => -0.0,
        2 => 1e-5,
        3 => 0.1,
        4 => 1.0,
        5 => 2.0,
        6 => *u.choose(&[f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -1e-5, -0.5])?,
        7 => f32::from_bits(u32::arbitrary(u)?),
        _ => *u.choose(&[f32::from_bits(1), f32::MIN_POSITIVE, 0.999, f32::MAX, 1e-30])?,
    })
}

/// Everything one `tbasis_generate` or `tbasis_generate_corners` call is made of.
#[derive(Clone, Debug)]
pub struct Plan {
    /// `tbasis_generate_corners`: `bufs[TAN]` holds a frame per corner, `bufs[BIT]` is unused and
    /// there is no output struct.
    pub corners: bool,
    pub vertex_count: usize,
    /// Bytes of the arena every buffer of the call sits in.
    pub arena: usize,
    pub bufs: [Buf; 6],
    pub index_type: u32,
    pub index_pattern: IndexPattern,
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
            // 0 is the listing's method with policy LEGACY, else ANGLE.
            0 if self.policy == TBASIS_DEGENERATE_LEGACY => TBASIS_METHOD_LENGYEL,
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
    /// Corners of the mesh as the descriptor gives them: the index count, or the vertex count
    /// when unindexed.
    pub fn corner_count(&self) -> usize {
        if self.bufs[IDX].null {
            self.vertex_count
        } else {
            self.bufs[IDX].count
        }
    }
}

/// A stride for `count` elements of `size` bytes in an arena of `arena` bytes: usually valid,
/// sometimes too small, large, or so large that the span overflows (only when that is certain,
/// so nothing is ever read).
pub fn pick_stride(u: &mut Unstructured, size: usize, count: usize, arena: usize) -> Result<usize> {
    let fit = if count <= 1 {
        arena - size
    } else {
        ((arena - size) / (count - 1)).max(size)
    };
    Ok(match weighted(u, &[8, 3, 1, 1, 1, 1, 1])? {
        0 => size,
        1 => (size + below(u, 33)?).min(fit),
        2 => below(u, size)?,
        3 => size + below(u, fit - size + 1)?,
        4 => fit,
        5 if count <= 1 => usize::arbitrary(u)? | size,
        5 => (1usize << 63) | usize::arbitrary(u)?,
        _ => (size + 4 * below(u, 8)?).min(fit),
    })
}

/// A stride (see [`pick_stride`]) for each of `bufs`, in order.
fn pick_strides(u: &mut Unstructured, bufs: &mut [Buf], count: usize, arena: usize) -> Result<()> {
    for b in bufs {
        b.stride = pick_stride(u, b.size, count, arena)?;
    }
    Ok(())
}

/// The vertex count: mostly small, sometimes hundreds or thousands, rarely so large that every
/// vertex span overflows (the call must fail before reading anything).
fn vertex_count(u: &mut Unstructured) -> Result<usize> {
    Ok(match weighted(u, &[250, 4, 1, 1])? {
        0 => below(u, SMALL_VERTICES + 1)?,
        1 => u.int_in_range(SMALL_VERTICES + 1..=512)?,
        2 => u.int_in_range(513..=MAX_VERTICES)?,
        _ => (1usize << 60) | usize::arbitrary(u)?,
    })
}

fn index_type(u: &mut Unstructured) -> Result<u32> {
    Ok(match weighted(u, &[8, 6, 1, 1])? {
        0 => TBASIS_INDEX_U16,
        1 => TBASIS_INDEX_U32,
        2 => *u.choose(&[0, 3])?,
        _ => u32::arbitrary(u)?,
    })
}

/// The index count: whole triangles (up to about two a vertex) mostly, sometimes any count,
/// rarely so large that the span overflows; with NULL indices, 0 but rarely.
fn index_count(u: &mut Unstructured, null: bool, vertex_count: usize) -> Result<usize> {
    if null {
        return Ok(if one_in::<16>(u)? {
            usize::from(u16::arbitrary(u)?)
        } else {
            0
        });
    }
    let triangles = (2 * vertex_count.min(MAX_VERTICES)).clamp(SMALL_TRIANGLES, MAX_TRIANGLES);
    Ok(match weighted(u, &[28, 3, 1])? {
        0 => 3 * below(u, triangles + 1)?,
        1 => below(u, 3 * triangles + 3)?,
        _ => (1usize << 62) | usize::arbitrary(u)?,
    })
}

/// Bytes of the arena of a mesh: room for every buffer twice over (each vertex has 60 bytes of
/// attributes, each corner up to 4 of index and 16 of per-corner tangent), at least [`MIN_ARENA`].
/// A count past the bounds is one whose spans overflow: nothing of it is placed.
pub fn arena_len(vertex_count: usize, corner_count: usize) -> usize {
    let placeable = |count: usize, max: usize| if count > max { 0 } else { count };
    let v = placeable(vertex_count, MAX_VERTICES);
    let c = placeable(corner_count, 3 * MAX_TRIANGLES + 2);
    MIN_ARENA.max(2 * (60 * v + 20 * c))
}

/// How the buffers of a call sit in the arena.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Layout {
    /// Packed one after another in some order, with small gaps (or small overlaps).
    Packed,
    /// Interleaved: one record per vertex holding every attribute, tangents included.
    Interleaved,
    /// Anywhere: bases independent of each other.
    Anywhere,
    /// Packed, then an output moved near (or onto) another buffer.
    Near,
}

pub fn decode_plan(u: &mut Unstructured) -> Result<Plan> {
    let vertex_count = vertex_count(u)?;
    let mut bufs = [Buf::default(); 6];
    let sizes = [12, 12, 8, 16, 12];
    for k in POS..=BIT {
        bufs[k].size = sizes[k];
        bufs[k].count = vertex_count;
    }
    let nulls = BufferNulls::arbitrary(u)?;
    bufs[POS].null = nulls.positions;
    bufs[NRM].null = nulls.normals;
    bufs[UV].null = nulls.texcoords;
    bufs[TAN].null = nulls.tangents;
    bufs[BIT].null = nulls.bitangents;
    bufs[IDX].null = nulls.indices;

    let index_type = index_type(u)?;
    let index_size = if index_type == TBASIS_INDEX_U16 { 2 } else { 4 };
    let index_count = index_count(u, bufs[IDX].null, vertex_count)?;
    bufs[IDX].size = index_size;
    bufs[IDX].stride = index_size;
    bufs[IDX].count = index_count;
    let corner_count = if bufs[IDX].null { vertex_count } else { index_count };
    let arena = arena_len(vertex_count, corner_count);

    let layout = [Layout::Packed, Layout::Interleaved, Layout::Anywhere, Layout::Near][weighted(u, &[4, 2, 1, 1])?];
    match layout {
        Layout::Interleaved => {
            let mut order = [POS, NRM, UV, TAN, BIT];
            shuffle(u, &mut order)?;
            let mut offsets = [0usize; 5];
            let mut at = 0;
            for k in order {
                offsets[k] = at;
                at += bufs[k].size + below(u, 4)?;
            }
            let stride = if one_in::<16>(u)? {
                below(u, at)?
            } else {
                at + below(u, 16)?
            };
            let start = below(u, 8)?;
            for k in POS..=BIT {
                bufs[k].stride = stride;
                bufs[k].base = start + offsets[k];
            }
            if one_in::<8>(u)? {
                let k = below(u, 5)?;
                bufs[k].stride = pick_stride(u, bufs[k].size, vertex_count, arena)?;
            }
            let end = bufs[..IDX]
                .iter()
                .filter_map(|b| b.extent().filter(|&e| e <= arena).map(|e| b.base + e))
                .max()
                .unwrap_or(0);
            bufs[IDX].base = end + below(u, 8)?;
        }
        Layout::Anywhere => {
            pick_strides(u, &mut bufs[POS..=BIT], vertex_count, arena)?;
            for b in &mut bufs {
                let room = b.extent().map_or(arena, |e| arena.saturating_sub(e) + 1);
                b.base = below(u, room)?;
            }
        }
        Layout::Packed | Layout::Near => {
            pick_strides(u, &mut bufs[POS..=BIT], vertex_count, arena)?;
            let mut order = [POS, NRM, UV, TAN, BIT, IDX];
            shuffle(u, &mut order)?;
            let mut cursor = below(u, 8)?;
            for k in order {
                bufs[k].base = cursor;
                let extent = bufs[k].extent().filter(|&e| e <= arena).unwrap_or(0);
                cursor += extent;
                if one_in::<16>(u)? {
                    cursor = cursor.saturating_sub(1 + below(u, 16)?);
                } else {
                    cursor += below(u, 8)?;
                }
            }
        }
    }
    // Sometimes an output lands on purpose near (or on) another buffer.
    if layout == Layout::Near || one_in::<16>(u)? {
        let target = if bool::arbitrary(u)? { BIT } else { TAN };
        let source = below(u, 6)?;
        let delta = nudge(u, 20)?;
        bufs[target].base = (bufs[source].base as isize + delta).clamp(0, arena as isize - 1) as usize;
    }
    for b in &mut bufs {
        b.clamp_into(arena);
    }

    let nulls = StructNulls::arbitrary(u)?;
    let codes = Codes::arbitrary(u)?;
    let needed = scratch_needed(
        vertex_count,
        &bufs[IDX],
        nulls.options,
        [codes.method, codes.policy, codes.flags, codes.threads],
        codes.threshold,
    );
    let scratch = pick_scratch(u, needed, &bufs, arena)?;
    let struct_offsets = [below(u, 8)?, below(u, 8)?, below(u, 8)?, below(u, 9)?];
    let arena_fill = u8::arbitrary(u)?;
    let scratch_fill = u8::arbitrary(u)?;
    let mut encodings = [pick_encoding(u)?, pick_encoding(u)?, pick_encoding(u)?];
    let mut index_pattern = IndexPattern::arbitrary(u)?;
    // One grid for the whole mesh: the texture coordinates and the indices follow the positions'.
    if let Some(grid) = encodings.iter().find_map(|e| match e {
        Encoding::Grid(grid) => Some(*grid),
        _ => None,
    }) {
        for e in &mut encodings {
            if let Encoding::Grid(g) = e {
                g.width = grid.width;
            }
        }
        if let IndexPattern::Grid(w) = &mut index_pattern {
            *w = grid.width;
        }
    }
    Ok(Plan {
        corners: false,
        vertex_count,
        arena,
        bufs,
        index_type,
        index_pattern,
        mesh_null: nulls.mesh,
        output_null: nulls.output,
        options_null: nulls.options,
        report_null: nulls.report,
        method: codes.method,
        policy: codes.policy,
        flags: codes.flags,
        threads: codes.threads,
        threshold: codes.threshold,
        scratch,
        scratch_needed: needed,
        struct_offsets,
        arena_fill,
        scratch_fill,
        encodings,
    })
}
/// Bytes of caller scratch `tbasis_scratch_size` asks for this mesh and these options (`codes`:
/// method, policy, flags, threads); for NULL options checked against the documented formula
/// (MIKKTSPACE's is the library's unit test's to check: the calls use exactly the size asked
/// for, or a little less or more).
pub fn scratch_needed(
    vertex_count: usize,
    indices: &Buf,
    options_null: bool,
    codes: [u32; 4],
    threshold: f32,
) -> usize {
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
/// asked for, a little less or more, inside the main arena of `arena` bytes (after the buffers or
/// anywhere), or a claimed size whose span overflows.
fn pick_scratch(u: &mut Unstructured, needed: usize, bufs: &[Buf], arena: usize) -> Result<ScratchPlan> {
    let none = ScratchPlan {
        null: true,
        claimed: 0,
        ..Default::default()
    };
    Ok(match weighted(u, &[4, 1, 1, 1, 1])? {
        // None (with any claimed size, which must be ignored).
        0 => ScratchPlan {
            claimed: if one_in::<4>(u)? { usize::arbitrary(u)? } else { 0 },
            ..none
        },
        // Exactly the size asked for, at every alignment.
        1 if needed <= OWN_SCRATCH_MAX => own_scratch(below(u, 4)?, needed),
        // A little too small, or larger.
        2 if needed <= OWN_SCRATCH_MAX => {
            let claimed = if needed > 0 && bool::arbitrary(u)? {
                needed - 1 - below(u, needed.min(8))?
            } else {
                needed + below(u, 64)?
            };
            own_scratch(below(u, 4)?, claimed)
        }
        // Inside the main arena: after the buffers, or anywhere (likely overlapping them).
        3 if needed <= arena - 16 => {
            let claimed = needed + below(u, 16)?;
            let base = if bool::arbitrary(u)? {
                below(u, arena - claimed + 1)?
            } else {
                (end_of(bufs, arena) + below(u, 8)?).min(arena - claimed)
            };
            ScratchPlan {
                null: false,
                in_main: true,
                base,
                claimed,
                arena_len: 0,
            }
        }
        // A claimed size whose span overflows; never touched.
        _ => ScratchPlan {
            null: false,
            in_main: false,
            base: below(u, 4)?,
            claimed: (1usize << 63) | usize::arbitrary(u)?,
            arena_len: 8,
        },
    })
}

/// The end of the last of `bufs` placed in the arena of `arena` bytes.
pub fn end_of<'a>(bufs: impl IntoIterator<Item = &'a Buf>, arena: usize) -> usize {
    bufs.into_iter()
        .filter(|b| b.placed(arena))
        .map(|b| b.base + b.extent().unwrap_or(0))
        .max()
        .unwrap_or(0)
}

/// The `tbasis_generate_corners` call that follows the `tbasis_generate` call of `vertices`, on
/// the same mesh, drawn from the bytes left over (none left: the same options, the tangents
/// packed after the inputs, no caller scratch). Its tangents hold a frame per corner.
pub fn decode_corners_plan(u: &mut Unstructured, vertices: &Plan) -> Result<Plan> {
    let mut plan = vertices.clone();
    plan.corners = true;
    plan.output_null = false;
    plan.bufs[BIT] = Buf {
        null: true,
        ..Buf::default()
    };
    // Another method or policy sometimes, so that every one meets every layout.
    match weighted(u, &[10, 5, 1])? {
        0 => {}
        1 => plan.method = u.int_in_range(0..=6)?,
        _ => plan.method = u32::arbitrary(u)?,
    }
    match weighted(u, &[6, 1, 1])? {
        0 => {}
        1 => plan.policy = u.int_in_range(0..=5)?,
        _ => plan.flags ^= TBASIS_FLAG_FLIP_V,
    }
    if one_in::<8>(u)? {
        plan.threads = u.int_in_range(0..=3)?;
    }
    let nulls = StructNulls::arbitrary(u)?;
    plan.options_null = nulls.options;
    plan.report_null = nulls.report;
    plan.mesh_null = nulls.mesh;

    let arena = plan.arena;
    let corner_count = plan.corner_count();
    let stride = pick_stride(u, 16, corner_count, arena)?;
    let inputs = [
        &vertices.bufs[POS],
        &vertices.bufs[NRM],
        &vertices.bufs[UV],
        &vertices.bufs[IDX],
    ];
    let base = match weighted(u, &[6, 1, 1])? {
        // After the inputs, or anywhere, or near (or on) one of them.
        0 => end_of(inputs, arena) + below(u, 8)?,
        1 => below(u, arena)?,
        _ => {
            let near = inputs[below(u, inputs.len())?].base as isize;
            (near + nudge(u, 20)?).clamp(0, arena as isize - 1) as usize
        }
    };
    let tangents = &mut plan.bufs[TAN];
    *tangents = Buf {
        null: one_in::<32>(u)?,
        base,
        stride,
        size: 16,
        count: corner_count,
    };
    tangents.clamp_into(arena);

    let codes = [plan.method, plan.policy, plan.flags, plan.threads];
    plan.scratch_needed = scratch_needed(
        plan.vertex_count,
        &plan.bufs[IDX],
        plan.options_null,
        codes,
        plan.threshold,
    );
    plan.scratch = pick_scratch(u, plan.scratch_needed, &plan.bufs, arena)?;
    plan.struct_offsets = [below(u, 8)?, below(u, 8)?, 0, below(u, 9)?];
    plan.scratch_fill = u8::arbitrary(u)?;
    if debugging() {
        eprintln!("corners call: {plan:#?}");
    }
    Ok(plan)
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

/// Writes the mesh of `plan` (the vertex attributes, then the indices) into `arena`.
pub fn write_inputs(u: &mut Unstructured, plan: &Plan, arena: &mut [u8]) -> Result<()> {
    let [positions, normals, texcoords] = plan.encodings;
    fill_vectors::<3>(u, positions, Attribute::Position, &plan.bufs[POS], arena)?;
    fill_vectors::<3>(u, normals, Attribute::Normal, &plan.bufs[NRM], arena)?;
    fill_vectors::<2>(u, texcoords, Attribute::Texcoord, &plan.bufs[UV], arena)?;
    let indices = &plan.bufs[IDX];
    if indices.placed(arena.len()) {
        let values = index_values(u, plan.index_pattern, indices.count, plan.vertex_count)?;
        for (k, value) in values.into_iter().enumerate() {
            let at = indices.element(k);
            if plan.index_type == TBASIS_INDEX_U16 {
                arena[at..at + 2].copy_from_slice(&(value as u16).to_le_bytes());
            } else {
                arena[at..at + 4].copy_from_slice(&value.to_le_bytes());
            }
        }
    }
    Ok(())
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

/// The mesh descriptor of `plan` over the arena at `arena` (which the plan's bases index).
pub fn mesh_descriptor(plan: &Plan, arena: *const u8) -> tbasis_mesh {
    // SAFETY: every base is below the arena length (clamped), so `add` stays in the allocation.
    let at = |buf: &Buf| -> *const c_void {
        if buf.null {
            ptr::null()
        } else {
            unsafe { arena.add(buf.base).cast() }
        }
    };
    let b = &plan.bufs;
    tbasis_mesh {
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
    }
}

/// Status bits for what the header says is wrong with the mesh descriptor of `plan` itself (its
/// buffers, index type, count and values, read from `arena`), whatever the call and its options.
pub fn mesh_violations(plan: &Plan, arena: &[u8]) -> u32 {
    let b = &plan.bufs;
    let vc = plan.vertex_count;
    let mut hard = b[POS].violations() | b[NRM].violations();
    if !b[UV].null {
        hard |= b[UV].violations();
    }
    if !b[IDX].null {
        if !plan.index_type_valid() {
            hard |= bit(TBASIS_ERROR_INVALID_INDEX_TYPE);
        } else {
            hard |= b[IDX].violations();
            if b[IDX].count % 3 != 0 {
                hard |= bit(TBASIS_ERROR_INVALID_INDEX_COUNT);
            } else if b[IDX].placed(plan.arena) && read_indices(plan, arena).iter().any(|&i| i >= vc) {
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
    hard
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
        let valid = |k: usize| (b[k].valid_footprint() && b[k].placed(plan.arena)).then_some(b[k]);
        let mut inputs: Vec<Buf> = [POS, NRM].into_iter().filter_map(valid).collect();
        if !b[UV].null {
            inputs.extend(valid(UV));
        }
        if !b[IDX].null && plan.index_type_valid() {
            inputs.extend(valid(IDX));
        }
        let s = plan.scratch.buf();
        let scratch = (plan.uses_scratch() && plan.scratch.in_main && s.valid_footprint() && s.placed(plan.arena))
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
        if !b[k].null && !b[k].placed(plan.arena) {
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
            plan.arena
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
            if b[k].placed(plan.arena) {
                (0..n).map(|c| f32_at(arena, b[k].element(i) + 4 * c)).collect()
            } else {
                Vec::new()
            }
        };
        eprintln!("v{i}: p {:?} n {:?} uv {:?}", get(POS, 3), get(NRM, 3), get(UV, 2));
    }
    if b[IDX].placed(plan.arena) {
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
