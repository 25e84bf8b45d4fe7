//! Fuzzes the C ABI: `tbasis_generate`, `tbasis_generate_corners` (and, for some inputs,
//! `tbasis_calculate_tangent_array`), the Rust API against it, and method MIKKTSPACE against
//! mikktspace.c itself. The C library (`tbasis-ffi`) builds no rlib: its boundary, `src/ffi.rs`
//! and `src/status.rs`, is compiled into this binary as the modules `ffi` and `status`.
//!
//! The input bytes choose a vertex count, strides, where each buffer sits inside one byte arena
//! (unaligned, interleaved, overlapping on purpose), which pointers are NULL, the indices, the
//! options, an optional caller scratch, and the float contents (`generate/plan.rs`). Every pointer
//! stays inside memory this harness owns, and every span the library may touch lies inside it, so
//! a sanitizer report or a failed check is the library's fault. Each input makes a
//! `tbasis_generate` call, then a `tbasis_generate_corners` call on the same mesh whose options,
//! per-corner tangent buffer and scratch come from the bytes left over (none left: the same
//! options, the tangents after the inputs). After each call the harness checks, independently of
//! the library's code (`generate/call.rs`, `generate/outputs.rs`):
//!
//! - the status is one the library defines (`status.rs`, each with its message) and one the
//!   description allows (an error the inputs really contain; OK when they contain none);
//! - on an error, no byte changed (the caller scratch excepted: it is working memory), and the
//!   report is untouched unless the status is DEGENERATE_UV or INDEX_OUT_OF_RANGE (then it holds
//!   zero counts and the first triangle with an index out of range in `failed_triangle`);
//! - on OK, only tangent and bitangent elements (and the scratch) changed, and the report adds up;
//! - on OK with method LENGYEL and policy LEGACY, the bits equal those of the C port of the
//!   original listing, `c_tests/listing.c` (as do those of `tbasis_calculate_tangent_array`);
//! - on OK with method MIKKTSPACE, under LEGACY every corner has mikktspace.c's bits (as below);
//!   under SKIP, INHERIT and REJECT a corner whose mikktspace.c frame is usable keeps its bits and
//!   the others get a valid frame with mikktspace.c's sign, counted by `repaired_corners`; per
//!   vertex, each used vertex has its first corner's frame;
//! - on OK with the other policies, tangents are finite unit vectors orthogonal to the normalized
//!   normal, `w` is exactly +1 or -1, bitangents are `w * cross(n, t)`, and the result is the same
//!   with or without caller scratch;
//! - per corner, the per-vertex methods give each corner its vertex's bits from `tbasis_generate`
//!   (under LEGACY, and everywhere on a mesh without mirror folds) and the same report;
//! - on OK and on DEGENERATE_UV, the Rust API on the same mesh and options (`generate/rust_api.rs`)
//!   gives the same bits and report, or the same refusal: `generate` and `generate_corners`, the
//!   same in one `ScratchBuffer` reused by both calls of the input, and, per vertex,
//!   `generate_interleaved` over an interleaved copy of the mesh (a layout the bytes pick), which
//!   writes no byte but the tangents; `scratch_size_for` agrees with `tbasis_scratch_size`.
//!
//! Then, whenever the bytes make a mesh the library must accept (whatever the calls above were
//! asked), method MIKKTSPACE with policy LEGACY, `flip_v` off and on, one and two threads, runs
//! through the Rust API (`generate/mikktspace.rs`): every corner must have the bits mikktspace.c
//! gives (built from `mikktspace-sys` by `tests/common/mikktspace_reference.rs`), a NaN matching
//! any NaN (which NaN an operation on NaN operands returns is fixed neither by C nor by Rust);
//! every vertex its first corner's frame; the report's split, mirrored and unreferenced vertices
//! those of the corners. The same runs on two meshes made from the decoded one: every value
//! snapped to one of a few (equal corners, shared edges, collapsed triangles and exact mirror
//! seams become common), and its corners unindexed. The library starts a worker per 16384
//! triangles at most, far beyond the fuzzer's meshes: the thread counts only check that asking
//! for a second thread changes nothing.
//!
//! `FUZZ_DEBUG=1` prints the decoded calls, the mesh and the reports of each input run; a
//! mismatch against mikktspace.c prints the mesh, bits included.
//!
//! `fuzz/regressions/` holds the inputs of past findings (replayed by `.ci/fuzz.sh`), all fixed:
//! - `empty-mesh-unaligned-scratch`: no vertices, a non-NULL 0-byte scratch at an address 1 mod 4
//!   was refused with SCRATCH_TOO_SMALL;
//! - `tangent-not-orthogonal-near-normal`: a tangent sum nearly along the normal left the tangent
//!   1.7e-4 off orthogonal;
//! - `lengyel-tiny-tangent-not-orthogonal`, `lengyel-tiny-tangent-huge-uv`: method LENGYEL with
//!   position edges far smaller than UV edges (a subnormal-scale dP/du) left the tangent far off
//!   orthogonal;
//! - `mikktspace-scratch-size-overflow`: `tbasis_scratch_size` with method MIKKTSPACE and
//!   `SIZE_MAX` vertices, unindexed, overflowed adding one to the corner count (a panic where
//!   overflow is checked);
//! - `mikktspace-reject-report`: method MIKKTSPACE with policy REJECT filled only the degenerate
//!   counts of the report it returns with DEGENERATE_UV (`abnormal_normals` 0 with 4 abnormal
//!   normals).
#![no_main]

#[path = "generate/arena.rs"]
mod arena;
#[path = "generate/call.rs"]
mod call;
// The C boundary (the `tbasis-ffi` crate has no rlib): its sources, compiled into this binary.
// Formatted and linted as part of the C crate; `cargo fmt` here leaves it (and status.rs) alone.
// Its features (`fault-injection`, for the C crate's tests) are never on here.
#[allow(non_camel_case_types, dead_code, unsafe_op_in_unsafe_fn, unexpected_cfgs)]
#[rustfmt::skip]
#[path = "../../src/ffi.rs"]
mod ffi;
#[path = "generate/frames.rs"]
mod frames;
#[path = "generate/input.rs"]
mod input;
#[path = "../../c_tests/listing.rs"]
mod listing;
#[path = "generate/listing_entry.rs"]
mod listing_entry;
#[path = "generate/mikktspace.rs"]
mod mikktspace;
#[allow(dead_code)]
#[path = "../../tests/common/mikktspace_reference.rs"]
mod mikktspace_reference;
#[path = "generate/outputs.rs"]
mod outputs;
#[path = "generate/packed.rs"]
mod packed;
#[path = "generate/plan.rs"]
mod plan;
#[path = "generate/rust_api.rs"]
mod rust_api;
#[allow(non_camel_case_types, dead_code)]
#[rustfmt::skip]
#[path = "../../src/status.rs"]
mod status;

use libfuzzer_sys::fuzz_target;
use tbasis::ScratchBuffer;

use crate::input::Input;
use crate::packed::Packed;
use crate::plan::{decode_corners_plan, decode_plan, write_inputs, ARENA};

fuzz_target!(|data: &[u8]| run(data));

fn run(data: &[u8]) {
    let mut input = Input { data, pos: 0 };
    let also_listing = input.u8() % 4 == 3;
    let plan = decode_plan(&mut input);
    let mut arena = vec![plan.arena_fill; ARENA];
    write_inputs(&mut input, &plan, &mut arena);
    let pristine = arena.clone();
    let mesh = Packed::of(&plan, &pristine);
    if let (true, Some(mesh)) = (call::debugging(), &mesh) {
        mesh.describe();
    }
    let mut scratch_arena = vec![plan.scratch_fill; plan.scratch.arena_len];
    // Reused by both calls' Rust API checks, so the second starts with what the first left.
    let mut rust_scratch = ScratchBuffer::new();
    call::check_call(&plan, &mut arena, &mut scratch_arena, mesh.as_ref(), &mut rust_scratch);
    if also_listing {
        listing_entry::check_listing_entry(&mut input);
    }

    let corners = decode_corners_plan(&mut input, &plan);
    let mut arena = pristine;
    let mut scratch_arena = vec![corners.scratch_fill; corners.scratch.arena_len];
    call::check_call(
        &corners,
        &mut arena,
        &mut scratch_arena,
        mesh.as_ref(),
        &mut rust_scratch,
    );

    if let Some(mesh) = &mesh {
        mikktspace::check(mesh, &[1, 2]);
        for variant in mesh.variants() {
            if call::debugging() {
                eprintln!("variant:");
                variant.describe();
            }
            mikktspace::check(&variant, &[1]);
        }
    }
}
