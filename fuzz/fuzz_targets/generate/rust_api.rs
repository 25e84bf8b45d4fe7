//! The Rust API on the mesh of a C call that ran (`TBASIS_OK`, or `TBASIS_ERROR_DEGENERATE_UV`
//! from policy REJECT), with the same options: `generate` (per vertex, bitangents when the call
//! wrote them) or `generate_corners` (per corner), the same in a `ScratchBuffer` that every call
//! of one input reuses (so it starts with what the previous call left in it), and, per vertex,
//! `generate_interleaved` over an interleaved copy of the mesh whose layout the plan picks. Each
//! must give the C call's bits and report, or refuse the mesh as it did, with the report it wrote
//! and nothing written.

use tbasis::{
    generate, generate_corners, generate_interleaved, scratch_size_for, Error, Mesh, Options, Output, Report,
    ScratchBuffer, StridedMut, VertexLayout,
};

use crate::call::describe_report;
use crate::frames::show;
use crate::packed::Packed;
use crate::plan::Plan;

/// What the C call gave.
pub struct CResult<'a> {
    /// The frames it wrote, per vertex or per corner; `None`: it refused with DEGENERATE_UV.
    pub tangents: Option<&'a [[f32; 4]]>,
    /// The bitangents it wrote (per vertex, when asked for).
    pub bitangents: Option<&'a [[f32; 3]]>,
    /// The report it wrote, unless the report pointer was NULL.
    pub report: Option<String>,
}

/// Bits no call writes: outputs start as this NaN, so an untouched element is told apart.
const UNWRITTEN: u32 = 0x7fc0_5a5a;

fn bits<const N: usize>(frames: &[[f32; N]]) -> Vec<[u32; N]> {
    frames.iter().map(|f| f.map(f32::to_bits)).collect()
}

fn report_text(report: Report) -> String {
    describe_report(&report.into())
}

/// `result` (with the frames it left) is what the C call gave.
fn check_against_c(
    what: &str,
    options: &Options,
    c: &CResult,
    result: &Result<Report, Error>,
    tangents: &[[f32; 4]],
    bitangents: Option<&[[f32; 3]]>,
) {
    let report = match (c.tangents, result) {
        (Some(expected), Ok(report)) => {
            for (i, (got, want)) in tangents.iter().zip(expected).enumerate() {
                assert!(
                    got.map(f32::to_bits) == want.map(f32::to_bits),
                    "{what}, {options:?}: element {i} is {}, the C call wrote {}",
                    show(*got),
                    show(*want)
                );
            }
            if let (Some(got), Some(want)) = (bitangents, c.bitangents) {
                assert!(
                    bits(got) == bits(want),
                    "{what}, {options:?}: the bitangents differ from the C call's"
                );
            }
            *report
        }
        (None, Err(Error::DegenerateUv { triangle, report })) => {
            assert_eq!(
                Some(*triangle), report.first_degenerate_triangle,
                "{what}, {options:?}: DegenerateUv names another triangle than its report"
            );
            let untouched = tangents.iter().all(|t| t.map(f32::to_bits) == [UNWRITTEN; 4]);
            let untouched =
                untouched && bitangents.is_none_or(|b| b.iter().all(|t| t.map(f32::to_bits) == [UNWRITTEN; 3]));
            assert!(untouched, "{what}, {options:?}: refused the mesh and wrote output");
            *report
        }
        (c_frames, _) => panic!(
            "{what}, {options:?}: the C call {}, the Rust API gave {result:?}",
            if c_frames.is_some() {
                "succeeded"
            } else {
                "refused with DEGENERATE_UV"
            }
        ),
    };
    if let Some(c_report) = &c.report {
        assert_eq!(
            report_text(report),
            *c_report,
            "{what}, {options:?}: the report differs from the C call's"
        );
    }
}

/// The per-vertex C call of `plan` against `generate`, `ScratchBuffer::generate` and
/// `generate_interleaved` on `mesh`.
pub fn check_vertices(plan: &Plan, mesh: &Packed, options: &Options, c: &CResult, scratch: &mut ScratchBuffer) {
    let vc = mesh.vertex_count();
    let with_bitangents = c.bitangents.is_some();
    let view = mesh.mesh();
    check_scratch_size(plan, &view, options);

    let run = |call: &mut dyn FnMut(&mut Output) -> Result<Report, Error>| {
        let mut tangents = vec![[f32::from_bits(UNWRITTEN); 4]; vc];
        let mut bitangents = vec![[f32::from_bits(UNWRITTEN); 3]; vc];
        let mut output = Output::new(&mut tangents[..]);
        if with_bitangents {
            output = output.with_bitangents(&mut bitangents[..]);
        }
        let result = call(&mut output);
        (result, tangents, with_bitangents.then_some(bitangents))
    };

    let (result, tangents, bitangents) = run(&mut |output| generate(&view, options, output));
    check_against_c("generate", options, c, &result, &tangents, bitangents.as_deref());

    let (reused, reused_tangents, reused_bitangents) = run(&mut |output| scratch.generate(&view, options, output));
    check_same(
        "ScratchBuffer::generate",
        options,
        &result,
        &reused,
        &tangents,
        &reused_tangents,
    );
    assert!(
        bitangents.as_deref().map(bits) == reused_bitangents.as_deref().map(bits),
        "ScratchBuffer::generate, {options:?}: the bitangents differ from generate's"
    );
    check_scratch_grown(&view, options, scratch);

    check_interleaved(plan, mesh, options, &result, &tangents);
}

/// One per-corner entry point, writing into the view it is given.
type CornerCall<'a> = dyn FnMut(&mut StridedMut<[f32; 4]>) -> Result<Report, Error> + 'a;

/// The per-corner C call of `plan` against `generate_corners` and `ScratchBuffer::generate_corners`
/// on `mesh`.
pub fn check_corners(plan: &Plan, mesh: &Packed, options: &Options, c: &CResult, scratch: &mut ScratchBuffer) {
    let view = mesh.mesh();
    check_scratch_size(plan, &view, options);
    let run = |call: &mut CornerCall| {
        let mut corners = vec![[f32::from_bits(UNWRITTEN); 4]; mesh.corner_count()];
        let result = call(&mut StridedMut::from_slice(&mut corners));
        (result, corners)
    };
    let (result, corners) = run(&mut |out| generate_corners(&view, options, out));
    check_against_c("generate_corners", options, c, &result, &corners, None);
    let (reused, reused_corners) = run(&mut |out| scratch.generate_corners(&view, options, out));
    check_same(
        "ScratchBuffer::generate_corners",
        options,
        &result,
        &reused,
        &corners,
        &reused_corners,
    );
    check_scratch_grown(&view, options, scratch);
}

/// Another entry point gave `got` and `got_frames` where the plain call gave `want`, `frames`.
fn check_same(
    what: &str,
    options: &Options,
    want: &Result<Report, Error>,
    got: &Result<Report, Error>,
    frames: &[[f32; 4]],
    got_frames: &[[f32; 4]],
) {
    assert_eq!(got, want, "{what}, {options:?}: another result than the plain call's");
    assert!(
        bits(got_frames) == bits(frames),
        "{what}, {options:?}: the frames differ from the plain call's"
    );
}

/// `scratch_size_for` asks what `tbasis_scratch_size` asked for the plan (options NULL: the
/// defaults, which `options` then are).
fn check_scratch_size(plan: &Plan, mesh: &Mesh, options: &Options) {
    assert_eq!(
        scratch_size_for(mesh, options),
        Some(plan.scratch_needed),
        "scratch_size_for, {options:?}: not what tbasis_scratch_size asked"
    );
}

fn check_scratch_grown(mesh: &Mesh, options: &Options, scratch: &ScratchBuffer) {
    let needed = scratch_size_for(mesh, options).expect("the call ran, so its scratch size is a number");
    assert!(
        scratch.len() >= needed,
        "ScratchBuffer holds {} bytes after a call that needs {needed}",
        scratch.len()
    );
}

/// Where each attribute goes in the interleaved copy: an order, gaps of 0 to 3 bytes and a tail
/// after the last attribute, picked from the plan's bytes (the positions may start unaligned).
/// Returns the layout and how many bytes of a partial vertex follow the last one.
fn interleaved_layout(plan: &Plan, texcoords: bool) -> (VertexLayout, usize) {
    // (attribute: position, normal, texcoord, tangent; bytes)
    let mut order = vec![(0, 12), (1, 12), (3, 16)];
    if texcoords {
        order.push((2, 8));
    }
    let mut pick = plan.arena_fill as usize;
    for i in (1..order.len()).rev() {
        order.swap(i, pick % (i + 1));
        pick /= i + 1;
    }
    let mut offsets = [0usize; 4];
    let mut at = 0;
    for (n, &(attribute, size)) in order.iter().enumerate() {
        at += (plan.scratch_fill >> (2 * n)) as usize & 3;
        offsets[attribute] = at;
        at += size;
    }
    let stride = at + plan.struct_offsets[0] % 4;
    let mut layout = VertexLayout::new(stride, offsets[0], offsets[1], offsets[3]);
    if texcoords {
        layout = layout.with_texcoord(offsets[2]);
    }
    (layout, plan.struct_offsets[1] % stride)
}

/// `generate_interleaved` over an interleaved copy of `mesh` gives `generate`'s `result` and
/// tangents, and writes no byte but the tangents (none when it refuses).
fn check_interleaved(
    plan: &Plan,
    mesh: &Packed,
    options: &Options,
    result: &Result<Report, Error>,
    tangents: &[[f32; 4]],
) {
    let (layout, tail) = interleaved_layout(plan, mesh.texcoords.is_some());
    let stride = layout.stride;
    let vc = mesh.vertex_count();
    let mut bytes = vec![plan.arena_fill; vc * stride + tail];
    let mut put = |v: usize, offset: usize, values: &[f32]| {
        for (k, x) in values.iter().enumerate() {
            let at = v * stride + offset + 4 * k;
            bytes[at..at + 4].copy_from_slice(&x.to_ne_bytes());
        }
    };
    for v in 0..vc {
        put(v, layout.position, &mesh.positions[v]);
        put(v, layout.normal, &mesh.normals[v]);
        if let (Some(offset), Some(texcoords)) = (layout.texcoord, &mesh.texcoords) {
            put(v, offset, &texcoords[v]);
        }
    }
    let before = bytes.clone();
    let got = generate_interleaved(&mut bytes, &layout, mesh.mesh().indices, options);
    let what = "generate_interleaved";
    assert_eq!(
        &got, result,
        "{what}, {options:?}, {layout:?}: another result than generate's"
    );
    let mut expected = before;
    if got.is_ok() {
        for (v, t) in tangents.iter().enumerate() {
            for (k, x) in t.iter().enumerate() {
                let at = v * stride + layout.tangent + 4 * k;
                expected[at..at + 4].copy_from_slice(&x.to_ne_bytes());
            }
        }
    }
    if let Some(at) = (0..bytes.len()).find(|&i| bytes[i] != expected[i]) {
        panic!(
            "{what}, {options:?}, {layout:?}: byte {at} (vertex {}, offset {}) is {:#04x}, expected {:#04x}",
            at / stride,
            at % stride,
            bytes[at],
            expected[at]
        );
    }
}
