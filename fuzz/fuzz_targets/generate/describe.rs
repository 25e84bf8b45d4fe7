//! The decoded case as lines of text: what the calls are given (the counts, where each buffer
//! sits, the NULL pointers, the option codes, the caller scratch, and every value the harness
//! wrote into the arenas), so that a regression input can be checked to still decode to the case
//! it was made for (`fuzz/regression_cases/`, `.ci/fuzz.sh`) and rebuilt from its description
//! (`fuzz/examples/regressions.rs`).
//!
//! `FUZZ_DESCRIBE=1` prints the description of each input run. The lines, in order:
//!
//! ```text
//! generate counts vertices=V index_type=T indices=I
//! generate buffer NAME null=0|1 base=B stride=S        (positions normals texcoords tangents bitangents indices)
//! generate nulls mesh=0|1 output=0|1 options=0|1 report=0|1
//! generate codes method=M policy=P flags=F threads=N threshold=BITS
//! generate scratch none claimed=N | exact base=B | offset base=B delta=D | main base=B delta=D | huge base=B claimed=N
//! generate struct_offsets A B C D
//! generate fills arena=X scratch=Y
//! generate positions K = BITS BITS BITS                 (each element of each buffer the harness wrote)
//! generate normals K = ..., generate texcoords K = ..., generate indices K = VALUE
//! listing counts vertices=V triangles=T                   (when the input calls tbasis_calculate_tangent_array)
//! listing buffer NAME null=0|1 base=B                     (vertex normal texcoord triangle tangent)
//! listing fills arena=X
//! listing vertex K = ..., listing normal K = ..., listing texcoord K = ..., listing triangle K = VALUE
//! corners codes method=M policy=P flags=F threads=N
//! corners nulls mesh=0|1 options=0|1 report=0|1
//! corners tangents null=0|1 base=B stride=S
//! corners scratch ...                                     (as above)
//! corners struct_offsets A B C D
//! corners fills scratch=Y
//! ```
//!
//! Floats are their bits in hexadecimal. The caller scratch is told relative to the size
//! `tbasis_scratch_size` asks for (`delta`: claimed minus that size), so that a case keeps its
//! meaning when that size changes.

use core::ffi::c_long;
use std::cell::RefCell;

use crate::arena::{f32_at, Buf};
use crate::codes::TBASIS_INDEX_U16;
use crate::plan::{Plan, ScratchPlan, BIT, IDX, NRM, POS, TAN, UV};

thread_local! {
    static SINK: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Starts collecting the description of the next run.
pub fn start() {
    SINK.with(|sink| *sink.borrow_mut() = Some(String::new()));
}

/// The description collected since [`start`], and stops collecting.
pub fn take() -> Option<String> {
    SINK.with(|sink| sink.borrow_mut().take())
}

/// Whether a description is being collected.
pub fn active() -> bool {
    SINK.with(|sink| sink.borrow().is_some())
}

/// `FUZZ_DESCRIBE=1`: print the description of each input.
pub fn requested() -> bool {
    static DESCRIBE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *DESCRIBE.get_or_init(|| std::env::var_os("FUZZ_DESCRIBE").is_some())
}

fn line(text: String) {
    SINK.with(|sink| {
        if let Some(sink) = sink.borrow_mut().as_mut() {
            sink.push_str(&text);
            sink.push('\n');
        }
    });
}

fn flag(value: bool) -> u8 {
    u8::from(value)
}

fn floats(arena: &[u8], at: usize, n: usize) -> String {
    (0..n)
        .map(|k| format!("{:08x}", f32_at(arena, at + 4 * k).to_bits()))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The caller scratch of `plan`, relative to the size the library asks for.
fn scratch(prefix: &str, plan: &Plan) {
    let ScratchPlan {
        null,
        in_main,
        base,
        claimed,
        arena_len,
    } = plan.scratch;
    let delta = claimed as i128 - plan.scratch_needed as i128;
    line(match () {
        _ if null => format!("{prefix} scratch none claimed={claimed}"),
        _ if in_main => format!("{prefix} scratch main base={base} delta={delta}"),
        _ if arena_len == 8 && claimed >= 1 << 63 => format!("{prefix} scratch huge base={base} claimed={claimed}"),
        _ if delta == 0 => format!("{prefix} scratch exact base={base}"),
        _ => format!("{prefix} scratch offset base={base} delta={delta}"),
    });
}

/// The `tbasis_generate` call of `plan` on the arena as the harness wrote it.
pub fn generate_call(plan: &Plan, arena: &[u8]) {
    if !active() {
        return;
    }
    let b = &plan.bufs;
    line(format!(
        "generate counts vertices={} index_type={} indices={}",
        plan.vertex_count, plan.index_type, b[IDX].count
    ));
    let names = [
        (POS, "positions"),
        (NRM, "normals"),
        (UV, "texcoords"),
        (TAN, "tangents"),
        (BIT, "bitangents"),
        (IDX, "indices"),
    ];
    for (k, name) in names {
        line(format!(
            "generate buffer {name} null={} base={} stride={}",
            flag(b[k].null),
            b[k].base,
            b[k].stride
        ));
    }
    line(format!(
        "generate nulls mesh={} output={} options={} report={}",
        flag(plan.mesh_null),
        flag(plan.output_null),
        flag(plan.options_null),
        flag(plan.report_null)
    ));
    line(format!(
        "generate codes method={} policy={} flags={} threads={} threshold={:08x}",
        plan.method,
        plan.policy,
        plan.flags,
        plan.threads,
        plan.threshold.to_bits()
    ));
    scratch("generate", plan);
    let [a, o, c, d] = plan.struct_offsets;
    line(format!("generate struct_offsets {a} {o} {c} {d}"));
    line(format!(
        "generate fills arena={} scratch={}",
        plan.arena_fill, plan.scratch_fill
    ));
    for (k, name, n) in [(POS, "positions", 3), (NRM, "normals", 3), (UV, "texcoords", 2)] {
        if b[k].placed(arena.len()) {
            for i in 0..b[k].count {
                line(format!("generate {name} {i} = {}", floats(arena, b[k].element(i), n)));
            }
        }
    }
    if b[IDX].placed(arena.len()) {
        for i in 0..b[IDX].count {
            let at = b[IDX].element(i);
            let value = if plan.index_type == TBASIS_INDEX_U16 {
                u32::from(u16::from_le_bytes([arena[at], arena[at + 1]]))
            } else {
                u32::from_le_bytes(arena[at..at + 4].try_into().unwrap())
            };
            line(format!("generate indices {i} = {value}"));
        }
    }
}

/// The `tbasis_calculate_tangent_array` call: its counts, buffers (vertex, normal, texcoord,
/// triangle, tangent) and arena as the harness wrote it.
pub fn listing(vertex_count: c_long, triangle_count: c_long, bufs: &[Buf; 5], fill: u8, arena: &[u8]) {
    if !active() {
        return;
    }
    line(format!(
        "listing counts vertices={vertex_count} triangles={triangle_count}"
    ));
    let names = ["vertex", "normal", "texcoord", "triangle", "tangent"];
    for (b, name) in bufs.iter().zip(names) {
        line(format!("listing buffer {name} null={} base={}", flag(b.null), b.base));
    }
    line(format!("listing fills arena={fill}"));
    for (k, n) in [(0, 3), (1, 3), (2, 2)] {
        if bufs[k].placed(arena.len()) {
            for i in 0..bufs[k].count {
                line(format!(
                    "listing {} {i} = {}",
                    names[k],
                    floats(arena, bufs[k].element(i), n)
                ));
            }
        }
    }
    let tri = &bufs[3];
    if tri.placed(arena.len()) {
        for i in 0..tri.count {
            let at = tri.element(i);
            line(format!(
                "listing triangle {i} = {}",
                u16::from_le_bytes([arena[at], arena[at + 1]])
            ));
        }
    }
}

/// The `tbasis_generate_corners` call of `plan`.
pub fn corners_call(plan: &Plan) {
    if !active() {
        return;
    }
    line(format!(
        "corners codes method={} policy={} flags={} threads={}",
        plan.method, plan.policy, plan.flags, plan.threads
    ));
    line(format!(
        "corners nulls mesh={} options={} report={}",
        flag(plan.mesh_null),
        flag(plan.options_null),
        flag(plan.report_null)
    ));
    let t = &plan.bufs[TAN];
    line(format!(
        "corners tangents null={} base={} stride={}",
        flag(t.null),
        t.base,
        t.stride
    ));
    scratch("corners", plan);
    let [a, o, c, d] = plan.struct_offsets;
    line(format!("corners struct_offsets {a} {o} {c} {d}"));
    line(format!("corners fills scratch={}", plan.scratch_fill));
}
