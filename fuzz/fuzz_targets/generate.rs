//! Fuzzes the C ABI, every entry point of `include/tbasis.h` but `tbasis_version` (compiled in
//! here, it carries this crate's version): `tbasis_generate`, `tbasis_generate_corners` (and, for
//! some inputs, `tbasis_calculate_tangent_array`), `tbasis_scratch_size`, `tbasis_split_corners`,
//! `tbasis_copy_split_vertices`, `tbasis_to_tangent_space`, `tbasis_from_tangent_space` and
//! `tbasis_status_string`; the Rust API against it; and method MIKKTSPACE against mikktspace.c
//! itself. The C library (`tbasis-ffi`) builds no rlib: its boundary, `src/ffi.rs` and
//! `src/status.rs`, is compiled into this binary as the modules `ffi` and `status`.
//!
//! The input is read through `arbitrary`'s `Unstructured` (`generate/input.rs`): derived
//! `Arbitrary` types for the parts of fixed shape (the NULL pointers, option codes, layouts of the
//! smaller calls), `Unstructured` directly where a value depends on earlier ones. Past its end it
//! reads zeros, and every choice puts its ordinary case first, so a short input stays ordinary.
//! It chooses a vertex count (mostly up to 64, about one input in fifty up to 4096, rarely one
//! whose spans overflow), strides, where each buffer sits inside one byte arena (unaligned,
//! interleaved, overlapping on purpose), which pointers are NULL, the indices (drawn one by one,
//! near each other, or a grid), the options, an optional caller scratch, and the float contents
//! (small values, unit vectors, edge cases, any bits, a palette of a few vectors, or a grid with
//! mirror seams: a large mesh from a few bytes) (`generate/plan.rs`). Every pointer stays inside
//! memory this harness owns, and every span the library may touch lies inside it, so a sanitizer
//! report or a failed check is the library's fault.
//!
//! Each input first makes a `tbasis_status_string` probe of any value and a pair of tangent-space
//! transforms (`generate/transform.rs`), then a `tbasis_generate` call, then a
//! `tbasis_generate_corners` call on the same mesh whose options, per-corner tangent buffer and
//! scratch come from the bytes left over (none left: the same options, the tangents after the
//! inputs), then `tbasis_split_corners` on that call's tangents when it succeeded and on tangents
//! drawn from the bytes, each successful split followed by `tbasis_copy_split_vertices`
//! (`generate/split.rs`, `generate/copy_split.rs`). After each call the harness checks,
//! independently of the library's code (`generate/call.rs`, `generate/outputs.rs`,
//! `generate/statuses.rs`):
//!
//! - the status is one the library defines, `tbasis_status_string` gives its message, and it is
//!   one the description allows (an error the inputs really contain; OK when they contain none);
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
//!   writes no byte but the tangents; `scratch_size_for` agrees with `tbasis_scratch_size`;
//! - `tbasis_split_corners`: on OK only the new indices, the first `*appended_count` sources and
//!   the count written; corners of a vertex share an output vertex exactly when their tangents
//!   have the same bits, the first tangent of each vertex keeps its index, further ones append
//!   vertices in order of first appearance whose sources point back; the same split as
//!   `tbasis::split_corners`; after method MIKKTSPACE, as many vertices split as the report's
//!   `split_vertices`;
//! - `tbasis_copy_split_vertices`: on OK exactly the appended elements written, each a copy of its
//!   source element, the same bytes as `tbasis::copy_split_vertices`;
//! - `tbasis_to_tangent_space`, `tbasis_from_tangent_space` (on frames and directions from the
//!   bytes and on the first frames `tbasis_generate` wrote): on OK a finite result, the only bytes
//!   written, equal to the Rust API's whatever input the result overlaps; the same frames
//!   accepted by both; on well-conditioned frames each undoes the other within a rounding bound
//!   derived in `generate/transform.rs`.
//!
//! Then, whenever the bytes make a mesh the library must accept (whatever the calls above were
//! asked), method MIKKTSPACE with policy LEGACY, `flip_v` off and on, one and two threads, runs
//! through the Rust API (`generate/mikktspace.rs`): every corner must have the bits mikktspace.c
//! gives (built from `mikktspace-sys` by `crates/test-support/src/mikktspace_reference.rs`), a NaN matching
//! any NaN (which NaN an operation on NaN operands returns is fixed neither by C nor by Rust);
//! every vertex its first corner's frame; the report's split, mirrored and unreferenced vertices
//! those of the corners. The same runs on two meshes made from the decoded one: every value
//! snapped to one of a few (equal corners, shared edges, collapsed triangles and exact mirror
//! seams become common), and its corners unindexed. Built with `--cfg fuzzing`, the library takes
//! its rarer routes to mikktspace.c's edge pairing on these small meshes too (the last-run probe
//! and its narrowed replay, `pipelines/mikktspace/last_run.rs`). The library starts a worker per 16384
//! triangles at most, for every method, beyond the fuzzer's meshes (8192 triangles, 4096
//! vertices): the thread counts only check that asking for a second thread
//! changes nothing.
//!
//! `FUZZ_DEBUG=1` prints the decoded calls, the mesh and the reports of each input run; a
//! mismatch against mikktspace.c prints the mesh, bits included. `FUZZ_DESCRIBE=1` prints what
//! each input decodes to, every value included (`generate/describe.rs`).
//!
//! `fuzz/regressions/` holds the inputs of past findings, all fixed: `.ci/fuzz.sh` runs each alone
//! and checks that it still decodes to its case, `fuzz/regression_cases/NAME.txt` (`FUZZ_DESCRIBE=1`
//! prints what an input decodes to: `generate/describe.rs`). All but the last were found in the
//! byte format this target read before it used `arbitrary`; each case is what that format's
//! decoder read from the old input (the last one's, what the current format decodes), and
//! `fuzz/examples/regressions.rs` writes each input in the current format from its case. The
//! named ones:
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
//!   normals);
//! - `mikktspace-inherit-off-plane-donor` (found in the current format): method MIKKTSPACE with
//!   policy INHERIT gave a corner without a tangent the tangent of its vertex's first usable
//!   corner, which mikktspace.c had left 6.6e-4 off the plane of a normal 1.0005 long: the
//!   repaired corner was not orthogonal to the normal.
//!
//! The other 134, named by their hash as libFuzzer names what it finds, came without a note; the
//! comment of each case says which calls it makes.
#![no_main]

#[path = "generate/arena.rs"]
mod arena;
#[path = "generate/call.rs"]
mod call;
#[path = "generate/copy_split.rs"]
mod copy_split;
// The C boundary (the `tbasis-ffi` crate has no rlib): its sources, compiled into this binary.
// Formatted and linted as part of the C crate; `cargo fmt` here leaves it (and status.rs) alone.
// Its features (`fault-injection`, for the C crate's tests) are never on here.
#[allow(non_camel_case_types, dead_code, unsafe_op_in_unsafe_fn, unexpected_cfgs)]
#[rustfmt::skip]
#[path = "../../src/ffi.rs"]
mod ffi;
#[allow(unexpected_cfgs)]
#[rustfmt::skip]
#[path = "../../src/fault.rs"]
mod fault;
#[rustfmt::skip]
#[path = "../../src/guard.rs"]
mod guard;
#[allow(dead_code)]
#[rustfmt::skip]
#[path = "../../src/codes.rs"]
mod codes;
#[path = "generate/describe.rs"]
mod describe;
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
#[path = "generate/mikktspace_cost.rs"]
mod mikktspace_cost;
#[allow(dead_code)]
#[path = "../../crates/test-support/src/mikktspace_reference.rs"]
mod mikktspace_reference;
#[path = "generate/outputs.rs"]
mod outputs;
#[path = "generate/packed.rs"]
mod packed;
#[path = "generate/plan.rs"]
mod plan;
#[path = "generate/run.rs"]
mod run;
#[path = "generate/rust_api.rs"]
mod rust_api;
#[path = "generate/split.rs"]
mod split;
#[allow(non_camel_case_types, dead_code)]
#[rustfmt::skip]
#[path = "../../src/status.rs"]
mod status;
#[path = "generate/statuses.rs"]
mod statuses;
#[path = "generate/transform.rs"]
mod transform;

use arbitrary::Unstructured;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if describe::requested() {
        describe::start();
    }
    // `Unstructured` reads zeros past the end, so an input is never refused for being short.
    if let Err(error) = run::run(&mut Unstructured::new(data)) {
        if call::debugging() {
            eprintln!("input ends the run early: {error}");
        }
    }
    if let Some(description) = describe::take() {
        eprint!("{description}");
    }
});
