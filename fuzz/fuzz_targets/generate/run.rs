//! One input of the fuzz target `generate`, from its first byte to its last check (the target's
//! documentation, `fuzz_targets/generate.rs`, says what it does).

use arbitrary::{Arbitrary, Unstructured};
use tbasis::ScratchBuffer;

use crate::arena::vec_at;
use crate::describe;
use crate::input::one_in;
use crate::packed::Packed;
use crate::plan::{decode_corners_plan, decode_plan, write_inputs, TAN};
use crate::status::TBASIS_OK;
use crate::{call, listing_entry, mikktspace, split, statuses, transform};

/// Frames of a successful `tbasis_generate` call that also go through the tangent-space
/// transforms.
const GENERATED_FRAMES: usize = 4;

/// One input: every call it makes, and every check.
pub fn run(u: &mut Unstructured) -> arbitrary::Result<()> {
    // The cheap, fixed-size checks first, so the mesh gets whatever bytes are left.
    let status_probe = if one_in::<4>(u)? {
        u32::arbitrary(u)?
    } else {
        u.int_in_range(0..=31)?
    };
    statuses::check_any_status_string(status_probe);
    transform::check(u)?;

    let also_listing = one_in::<4>(u)?;
    let plan = decode_plan(u)?;
    let mut arena = vec![plan.arena_fill; plan.arena];
    write_inputs(u, &plan, &mut arena)?;
    let pristine = arena.clone();
    describe::generate_call(&plan, &pristine);
    let mesh = Packed::of(&plan, &pristine);
    if let (true, Some(mesh)) = (call::debugging(), &mesh) {
        mesh.describe();
    }
    let mut scratch_arena = vec![plan.scratch_fill; plan.scratch.arena_len];
    // Reused by both calls' Rust API checks, so the second starts with what the first left.
    let mut rust_scratch = ScratchBuffer::new();
    let (status, _) = call::check_call(&plan, &mut arena, &mut scratch_arena, mesh.as_ref(), &mut rust_scratch);
    if let (TBASIS_OK, Some(mesh)) = (status, &mesh) {
        let frames = GENERATED_FRAMES.min(plan.vertex_count);
        let tangents: Vec<[f32; 4]> = (0..frames).map(|i| vec_at(&arena, plan.bufs[TAN].element(i))).collect();
        transform::check_generated(&mesh.normals, &tangents, &mesh.positions);
    }
    if also_listing {
        listing_entry::check_listing_entry(u)?;
    }

    let corners = decode_corners_plan(u, &plan)?;
    describe::corners_call(&corners);
    let mut arena = pristine.clone();
    let mut scratch_arena = vec![corners.scratch_fill; corners.scratch.arena_len];
    let (status, report) = call::check_call(
        &corners,
        &mut arena,
        &mut scratch_arena,
        mesh.as_ref(),
        &mut rust_scratch,
    );
    if status == TBASIS_OK {
        split::check_generated(u, &corners, &arena, report.as_ref())?;
    }
    split::check_arbitrary(u, &plan, &pristine)?;

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
    Ok(())
}
