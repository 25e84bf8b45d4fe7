//! One call through the C ABI, `tbasis_generate` or `tbasis_generate_corners`, made from a plan
//! and checked: the status against what the inputs call for, every byte the call could touch,
//! the report, then (on success) the outputs.

use core::ffi::c_void;
use core::mem::size_of;
use core::ptr;

use tbasis::ScratchBuffer;

use crate::codes::*;
use crate::ffi::*;
use crate::status::*;

use crate::arena::{bit, first_change_outside, vec_at, Buf};
use crate::frames::length;
use crate::outputs::{check_corner_outputs, check_vertex_outputs, options};
use crate::packed::Packed;
use crate::plan::{
    assert_harness_sound, describe, mesh_descriptor, mesh_violations, read_indices, triangles_of, Footprints, Plan,
    BIT, IDX, NAMES, NRM, TAN, UV,
};
use crate::rust_api::{self, CResult};
use crate::statuses::{check_status, Expect};

const REPORT_BYTES: usize = size_of::<tbasis_report>();

/// The report goes at an unaligned offset inside a larger buffer, to catch writes beside it.
const REPORT_BUFFER: usize = REPORT_BYTES + 16;

const REPORT_FILL: u8 = 0x5a;

fn expect_call(plan: &Plan, arena: &[u8], footprints: &Footprints) -> Expect {
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
        // LEGACY reproduces the listing (LENGYEL) and mikktspace.c (MIKKTSPACE) only.
        let legacy_forms = [TBASIS_METHOD_LENGYEL, TBASIS_METHOD_MIKKTSPACE];
        let method = plan.resolved_method();
        if plan.resolved_policy() == TBASIS_DEGENERATE_LEGACY && known(Field::Method, method) && !legacy_forms.contains(&method) {
            hard |= bit(TBASIS_ERROR_NO_LEGACY_FORM);
        }
    }
    let b = &plan.bufs;
    hard |= mesh_violations(plan, arena) | b[TAN].violations();
    // The header lists the tangents as required; with no elements the call may accept NULL.
    if b[TAN].null && plan.outputs() == 0 {
        soft |= bit(TBASIS_ERROR_NULL_POINTER);
    }
    if b[UV].null && (plan.resolved_policy() == TBASIS_DEGENERATE_LEGACY || plan.mikktspace()) {
        // The listing and mikktspace.c both need texture coordinates.
        hard |= bit(TBASIS_ERROR_NULL_POINTER);
    }
    if !b[BIT].null {
        hard |= b[BIT].violations();
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
        Field::Method => value <= TBASIS_METHOD_MIKKTSPACE,
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

/// Makes the plan's call with its descriptors built over `arena`; the report buffer comes back
/// whole.
fn call(plan: &Plan, arena: &mut [u8], scratch_arena: &mut [u8], with_scratch: bool) -> (tbasis_status, Vec<u8>) {
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
    let mesh = mesh_descriptor(plan, arena_ptr);
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
        let mesh = if plan.mesh_null { ptr::null() } else { mesh_ptr };
        let options = if plan.options_null { ptr::null() } else { options_ptr };
        let report = if plan.report_null { ptr::null_mut() } else { report_ptr };
        if plan.corners {
            tbasis_generate_corners(mesh, options, output.tangents, output.tangents_stride, report)
        } else {
            tbasis_generate(
                mesh,
                options,
                if plan.output_null { ptr::null() } else { output_ptr },
                report,
            )
        }
    };
    (status, report_bytes)
}

/// `FUZZ_DEBUG=1` prints each decoded plan, to read a reproduced failure.
pub fn debugging() -> bool {
    static DEBUG: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *DEBUG.get_or_init(|| std::env::var_os("FUZZ_DEBUG").is_some())
}

/// What a call is called in messages.
fn name(plan: &Plan) -> &'static str {
    if plan.corners {
        "tbasis_generate_corners"
    } else {
        "tbasis_generate"
    }
}

/// Makes the plan's call over `arena` and checks everything about it; `mesh` is the mesh as the
/// library reads it, when it can.
/// `rust_scratch` is the `ScratchBuffer` every call of the input reuses (`generate/rust_api.rs`).
/// Returns the status and the report the call filled (none when NULL or not filled).
pub fn check_call(
    plan: &Plan,
    arena: &mut [u8],
    scratch_arena: &mut [u8],
    mesh: Option<&Packed>,
    rust_scratch: &mut ScratchBuffer,
) -> (tbasis_status, Option<tbasis_report>) {
    if debugging() {
        eprintln!("{plan:#?}");
    }
    assert_harness_sound(plan);
    let what = name(plan);
    let before = arena.to_vec();
    let scratch_before = scratch_arena.to_vec();
    let (status, report_bytes) = call(plan, arena, scratch_arena, true);

    let footprints = Footprints::of(plan);
    let expect = expect_call(plan, &before, &footprints);
    let policy = plan.resolved_policy();
    check_status(status, &expect, policy, what);
    if debugging() {
        eprintln!("{what}: status {status} policy {policy} vertices {}", plan.vertex_count);
        describe(plan, &before);
    }

    // Which bytes may have changed: outputs on success; the caller scratch ("working memory: its
    // contents after a call, successful or not, mean nothing") unless it shares bytes with another
    // buffer (then the call must refuse before using it).
    let ok = status == TBASIS_OK;
    let mut writable = Vec::new();
    if ok {
        for k in [TAN, BIT] {
            if plan.bufs[k].placed(plan.arena) {
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
            "{what} returned {status} and changed arena byte {at} ({:#04x} -> {:#04x}) outside its outputs",
            before[at], arena[at]
        );
    }
    if !plan.scratch.in_main {
        let s = plan.scratch;
        let claimed_end = s.base.saturating_add(s.claimed);
        let claimed = (s.base.min(scratch_arena.len()), claimed_end.min(scratch_arena.len()));
        if let Some(at) = first_change_outside(&scratch_before, scratch_arena, vec![claimed]) {
            panic!("{what} returned {status} and changed scratch-arena byte {at}");
        }
    }

    let report = check_report_bytes(plan, status, &report_bytes);
    if let (true, Some(r)) = (debugging(), report) {
        eprintln!("report: {}, failed triangle {}", describe_report(&r), r.failed_triangle);
    }
    if let (TBASIS_ERROR_INDEX_OUT_OF_RANGE, Some(report)) = (status, report) {
        check_index_report(plan, &report, &before);
    }
    if ok || status == TBASIS_ERROR_DEGENERATE_UV {
        let triangles = triangles_of(plan, &before);
        if let Some(report) = report {
            check_report(plan, status, &report, &triangles, &before);
        }
        // The call accepted the mesh, so the harness can read it too.
        let mesh = mesh.unwrap_or_else(|| panic!("{what} accepted a mesh the harness finds invalid"));
        check_rust_api(plan, arena, report.as_ref(), ok, mesh, rust_scratch);
        if ok {
            if plan.corners {
                check_corner_outputs(plan, &before, arena, report.as_ref(), mesh);
            } else {
                check_vertex_outputs(plan, &before, arena, &triangles, report.as_ref(), mesh);
            }
            if plan.uses_scratch() && plan.outputs() > 0 {
                check_without_scratch(plan, &before, arena, &report_bytes);
            }
        }
    }
    (status, report)
}

/// The Rust API on the same mesh and options gives what the call gave (`ok`: its outputs in
/// `arena`; otherwise DEGENERATE_UV) and the same `report`.
fn check_rust_api(
    plan: &Plan,
    arena: &[u8],
    report: Option<&tbasis_report>,
    ok: bool,
    mesh: &Packed,
    rust_scratch: &mut ScratchBuffer,
) {
    let b = &plan.bufs;
    let tangents: Vec<[f32; 4]> = (0..plan.outputs()).map(|i| vec_at(arena, b[TAN].element(i))).collect();
    let bitangents: Option<Vec<[f32; 3]>> = (!plan.corners && !b[BIT].null)
        .then(|| (0..plan.outputs()).map(|i| vec_at(arena, b[BIT].element(i))).collect());
    let c = CResult {
        tangents: ok.then_some(&tangents[..]),
        bitangents: bitangents.as_deref(),
        report: report.map(describe_report),
    };
    let options = options(plan);
    if plan.corners {
        rust_api::check_corners(plan, mesh, &options, &c, rust_scratch);
    } else {
        rust_api::check_vertices(plan, mesh, &options, &c, rust_scratch);
    }
}

/// The same call without caller scratch must give the same bytes.
fn check_without_scratch(plan: &Plan, before: &[u8], with_scratch: &[u8], report_with: &[u8]) {
    let mut arena = before.to_vec();
    let mut unused = vec![0u8; 1];
    let (status, report) = call(plan, &mut arena, &mut unused, false);
    assert_eq!(
        status, TBASIS_OK,
        "the call succeeds with caller scratch but not without"
    );
    for k in [TAN, BIT] {
        if !plan.bufs[k].placed(plan.arena) {
            continue;
        }
        for i in 0..plan.outputs() {
            let at = plan.bufs[k].element(i);
            let range = at..at + plan.bufs[k].size;
            assert_eq!(
                arena[range.clone()],
                with_scratch[range],
                "{} {i} differ with and without caller scratch",
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
    let filled = !plan.report_null
        && matches!(
            status,
            TBASIS_OK | TBASIS_ERROR_DEGENERATE_UV | TBASIS_ERROR_INDEX_OUT_OF_RANGE
        );
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

/// INDEX_OUT_OF_RANGE: the report names the first triangle with an index not below the vertex
/// count in `failed_triangle`, and every count is 0.
fn check_index_report(plan: &Plan, report: &tbasis_report, arena: &[u8]) {
    assert!(
        !plan.bufs[IDX].null && plan.bufs[IDX].placed(plan.arena),
        "INDEX_OUT_OF_RANGE without indices the harness can read"
    );
    let indices = read_indices(plan, arena);
    let whole = indices.len() - indices.len() % 3;
    let first = indices[..whole]
        .iter()
        .position(|&i| i >= plan.vertex_count)
        .map(|k| k / 3)
        .expect("INDEX_OUT_OF_RANGE, yet every index is in range");
    let counts = tbasis_report::from(tbasis::Report::default());
    assert_eq!(
        (describe_report(report), report.failed_triangle),
        (describe_report(&counts), first),
        "INDEX_OUT_OF_RANGE: the report is not zero counts and the first bad triangle"
    );
}

/// The report's counts add up, and say what the header says they say.
fn check_report(plan: &Plan, status: tbasis_status, report: &tbasis_report, triangles: &[[usize; 3]], arena: &[u8]) {
    let vc = plan.vertex_count;
    let policy = plan.resolved_policy();
    let mut used = vec![false; vc];
    for t in triangles {
        t.iter().for_each(|&v| used[v] = true);
    }
    let expected_unreferenced = used.iter().filter(|u| !**u).count();
    let r = report;
    let context = format!("report ({}), status {status}, policy {policy}", describe_report(r));
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
    if plan.mikktspace() {
        // The per-vertex call gives a vertex no triangle uses the fallback frame, whatever the
        // policy; the per-corner call has no such vertex to write.
        let fallback = if plan.corners || status != TBASIS_OK {
            0
        } else {
            expected_unreferenced
        };
        assert_eq!(r.fallback_vertices, fallback, "{context}: fallback_vertices");
        assert_eq!(r.inherited_vertices, 0, "{context}: inherited_vertices");
        let corners = 3 * triangles.len();
        assert!(r.repaired_corners <= corners, "{context}: repaired_corners");
        assert!(
            r.split_vertices <= vc - expected_unreferenced,
            "{context}: split_vertices"
        );
    } else {
        assert_eq!(r.repaired_corners, 0, "{context}: repaired_corners without MIKKTSPACE");
        assert_eq!(r.split_vertices, 0, "{context}: split_vertices without MIKKTSPACE");
    }
    if policy == TBASIS_DEGENERATE_LEGACY {
        if !plan.mikktspace() {
            assert_eq!(r.fallback_vertices, 0, "{context}: fallback_vertices under LEGACY");
        }
        assert_eq!(r.abnormal_normals, 0, "{context}: abnormal_normals under LEGACY");
        assert_eq!(r.repaired_corners, 0, "{context}: repaired_corners under LEGACY");
    }
    if policy != TBASIS_DEGENERATE_INHERIT {
        assert_eq!(r.inherited_vertices, 0, "{context}: inherited_vertices without INHERIT");
    }
    let failed = if status == TBASIS_ERROR_DEGENERATE_UV {
        r.first_degenerate_triangle
    } else {
        usize::MAX
    };
    assert_eq!(r.failed_triangle, failed, "{context}: failed_triangle");
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

/// Every field of a report, for failure messages and `FUZZ_DEBUG`.
pub fn describe_report(r: &tbasis_report) -> String {
    format!(
        "degenerate {}, first {}, fallback {}, mirrored {}, unreferenced {}, inherited {}, abnormal {}, \
         repaired {}, split {}",
        r.degenerate_triangles,
        r.first_degenerate_triangle,
        r.fallback_vertices,
        r.mirrored_vertices,
        r.unreferenced_vertices,
        r.inherited_vertices,
        r.abnormal_normals,
        r.repaired_corners,
        r.split_vertices
    )
}
