//! `tbasis_copy_split_vertices`, with the sources a successful `tbasis_split_corners` call wrote:
//! applied to an attribute buffer drawn from the bytes (its element size, stride, alignment and
//! contents), where they are or copied next to (or inside) the attribute, sometimes with another
//! vertex or appended count, or a NULL pointer. Checked against the header: the status the inputs
//! call for (and its string); on an error no byte written; on OK exactly the appended elements
//! written, each a copy of its source element, every other byte as it was; and the same bytes as
//! `tbasis::copy_split_vertices`.

use core::ptr;

use arbitrary::{Arbitrary, Result, Unstructured};
use tbasis::span_bytes;

use crate::status::*;

use crate::arena::{bit, first_change_outside};
use crate::call::debugging;
use crate::ffi::tbasis_copy_split_vertices;
use crate::input::{below, one_in, weighted};
use crate::split::Written;
use crate::statuses::{check_status, Expect};

/// The vertex count passed.
#[derive(Clone, Copy, Debug)]
enum VertexCount {
    /// The split mesh's.
    Same,
    /// Fewer: some sources may not be below it.
    Fewer,
    /// So many that adding the appended count overflows.
    TotalOverflow,
    /// So many that the attribute's span overflows.
    SpanOverflow,
}

/// The appended count passed.
#[derive(Clone, Copy, Debug)]
enum Appended {
    /// What the split returned.
    Same,
    Zero,
    Fewer,
    /// More, up to the room of the sources buffer (the extra sources are whatever bytes follow).
    More,
}

/// Where the sources are read from.
#[derive(Arbitrary, Clone, Copy, Debug)]
enum SourcesAt {
    /// Where the split wrote them.
    Returned,
    /// Copied after the attribute's span, in its arena.
    After,
    /// Copied inside the attribute's span: they overlap it.
    Inside,
}

/// The shape of one `tbasis_copy_split_vertices` call, apart from the split it applies.
#[derive(Arbitrary, Debug)]
struct Shape {
    #[arbitrary(with = element_size)]
    element_size: usize,
    /// 0: the element size; 1 to 15: that many bytes more; 16 and up: shorter than the element.
    #[arbitrary(with = stride_kind)]
    stride_kind: u8,
    #[arbitrary(with = vertex_count)]
    vertex_count: VertexCount,
    #[arbitrary(with = appended)]
    appended: Appended,
    #[arbitrary(with = sources_at)]
    sources_at: SourcesAt,
    #[arbitrary(with = one_in::<32>)]
    attribute_null: bool,
    #[arbitrary(with = one_in::<32>)]
    sources_null: bool,
    /// Where the attribute starts in its arena (unaligned), and bytes after its span.
    #[arbitrary(with = small_offset)]
    offset: usize,
    #[arbitrary(with = small_offset)]
    tail: usize,
    fill: u8,
}

/// An attribute's element: a position, a UV, a tangent, a colour..., any size, rarely 0.
fn element_size(u: &mut Unstructured) -> Result<usize> {
    Ok(match weighted(u, &[3, 2, 2, 1, 2, 1])? {
        0 => 12,
        1 => 8,
        2 => 16,
        3 => 4,
        4 => u.int_in_range(1..=32)?,
        _ => 0,
    })
}

fn stride_kind(u: &mut Unstructured) -> Result<u8> {
    Ok(match weighted(u, &[6, 3, 1])? {
        0 => 0,
        1 => u.int_in_range(1..=15)?,
        _ => 16,
    })
}

fn vertex_count(u: &mut Unstructured) -> Result<VertexCount> {
    Ok([
        VertexCount::Same,
        VertexCount::Fewer,
        VertexCount::TotalOverflow,
        VertexCount::SpanOverflow,
    ][weighted(u, &[12, 1, 1, 1])?])
}

fn appended(u: &mut Unstructured) -> Result<Appended> {
    Ok([Appended::Same, Appended::Zero, Appended::Fewer, Appended::More][weighted(u, &[12, 1, 1, 1])?])
}

fn sources_at(u: &mut Unstructured) -> Result<SourcesAt> {
    Ok([SourcesAt::Returned, SourcesAt::After, SourcesAt::Inside][weighted(u, &[6, 1, 1])?])
}

fn small_offset(u: &mut Unstructured) -> Result<usize> {
    below(u, 4)
}

/// Most bytes an attribute arena gets; a larger span (only with a vertex count the call must
/// refuse) is not placed.
const ATTRIBUTE_MAX: usize = 1 << 24;

fn u32_at(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
}

/// Applies the split `written` to an attribute drawn from the bytes with
/// `tbasis_copy_split_vertices`, and checks the call.
pub fn check(u: &mut Unstructured, written: &Written) -> Result<()> {
    let what = "tbasis_copy_split_vertices";
    let shape = Shape::arbitrary(u)?;
    let es = shape.element_size;
    let stride = match shape.stride_kind {
        0 => es,
        k @ 1..=15 => es + usize::from(k),
        _ => below(u, es)?,
    };
    let vertex_count = match shape.vertex_count {
        VertexCount::Same => written.vertex_count,
        VertexCount::Fewer => below(u, written.vertex_count + 1)?,
        VertexCount::TotalOverflow => usize::MAX - below(u, 4)?,
        VertexCount::SpanOverflow => (1usize << 63) | below(u, 1 << 20)?,
    };
    let appended = match shape.appended {
        Appended::Same => written.appended,
        Appended::Zero => 0,
        Appended::Fewer => below(u, written.appended + 1)?,
        Appended::More => written.appended + below(u, written.capacity - written.appended + 1)?,
    };
    let total = vertex_count.checked_add(appended);
    let span = total.and_then(|t| span_bytes(t, stride, es).ok());
    let placed_span = span.filter(|&s| s <= ATTRIBUTE_MAX);

    // The attribute's arena: the attribute at `offset`, the sources (when they move) after it or
    // inside it, then `tail` bytes.
    let base = shape.offset;
    let attribute_end = base + placed_span.unwrap_or(0);
    let sources_bytes = 4 * appended;
    let moved_sources = match shape.sources_at {
        SourcesAt::Returned => None,
        SourcesAt::After => Some(attribute_end + below(u, 8)?),
        SourcesAt::Inside => Some(base + below(u, placed_span.unwrap_or(0))?),
    };
    let len = attribute_end.max(moved_sources.map_or(0, |s| s + sources_bytes)) + shape.tail;
    let mut arena = vec![shape.fill; len];
    // Element i of the original vertices: bytes that tell the elements apart. (With a placed span
    // and elements of some bytes, the vertex count is bounded by the span.)
    if let (Some(_), true) = (placed_span, es > 0) {
        for i in 0..vertex_count {
            for k in 0..es {
                arena[base + i * stride + k] = (i as u8).wrapping_mul(31) ^ (k as u8).wrapping_mul(7) ^ (i >> 8) as u8;
            }
        }
    }
    let from_split = &written.sources_arena[written.sources_at..written.sources_at + 4 * written.capacity];
    if let Some(s) = moved_sources {
        arena[s..s + sources_bytes].copy_from_slice(&from_split[..sources_bytes]);
    }
    let before = arena.clone();
    let sources: Vec<u32> = match moved_sources {
        None => (0..appended).map(|j| u32_at(from_split, 4 * j)).collect(),
        Some(s) => (0..appended).map(|j| u32_at(&before, s + 4 * j)).collect(),
    };

    // What the inputs call for. The header lists no exception, but with nothing to copy (no
    // appended vertex, or 0-byte elements) the call may return before looking at the attribute
    // and the sources' values: the errors that depend on them are then allowed, not due.
    let mut hard = 0;
    if es > stride {
        hard |= bit(TBASIS_ERROR_INVALID_STRIDE);
    }
    if total.is_none() {
        hard |= bit(TBASIS_ERROR_SIZE_OVERFLOW);
    }
    if shape.sources_null && appended > 0 {
        hard |= bit(TBASIS_ERROR_NULL_POINTER);
    }
    let mut later = 0;
    if shape.attribute_null {
        later |= bit(TBASIS_ERROR_NULL_POINTER);
    }
    if total.is_some() && es <= stride && span.is_none() {
        later |= bit(TBASIS_ERROR_SIZE_OVERFLOW);
    }
    let overlapping = match (moved_sources, placed_span) {
        (Some(s), Some(span)) => {
            !shape.attribute_null && !shape.sources_null && s < base + span && base < s + sources_bytes
        }
        _ => false,
    };
    if overlapping {
        later |= bit(TBASIS_ERROR_OVERLAP);
    }
    if !shape.sources_null && sources.iter().any(|&s| s as usize >= vertex_count) {
        later |= bit(TBASIS_ERROR_INDEX_OUT_OF_RANGE);
    }
    let nothing_to_copy = es == 0 || appended == 0;
    let expect = if nothing_to_copy {
        Expect { hard, soft: later }
    } else {
        Expect {
            hard: hard | later,
            soft: 0,
        }
    };
    // The harness's promise: a call that may copy finds the whole span in the arena.
    if expect.hard == 0 && !nothing_to_copy {
        assert!(
            placed_span.is_some(),
            "harness: the attribute does not fit and the copy may run"
        );
    }
    if debugging() {
        eprintln!(
            "{what}: element {es} stride {stride} vertices {vertex_count} appended {appended} sources \
             {sources:?} at {moved_sources:?} {shape:?}: expected {:#x} (or {:#x})",
            expect.hard, expect.soft
        );
    }

    let arena_ptr = arena.as_mut_ptr();
    // SAFETY: the pointers address owned memory: the attribute's whole span when the call may
    // copy, the sources' `appended` elements (at most `capacity` from where the split wrote them).
    let status = unsafe {
        let attribute = if shape.attribute_null {
            ptr::null_mut()
        } else {
            arena_ptr.add(base).cast()
        };
        let sources_ptr: *const u32 = match (shape.sources_null, moved_sources) {
            (true, _) => ptr::null(),
            (false, None) => from_split.as_ptr().cast(),
            (false, Some(s)) => arena_ptr.add(s).cast_const().cast(),
        };
        tbasis_copy_split_vertices(attribute, stride, es, vertex_count, sources_ptr, appended)
    };
    check_status(status, &expect, 0, what);

    let mut expected = before.clone();
    if status == TBASIS_OK && !nothing_to_copy {
        for (j, &source) in sources.iter().enumerate() {
            let from = base + source as usize * stride;
            let to = base + (vertex_count + j) * stride;
            expected.copy_within(from..from + es, to);
        }
    }
    if let Some(at) = first_change_outside(&expected, &arena, Vec::new()) {
        panic!(
            "{what} returned {status}: byte {at} of the attribute's arena is {:#04x}, expected {:#04x} \
             (attribute at {base}, element {es}, stride {stride}, vertices {vertex_count}, sources {sources:?})",
            arena[at], expected[at]
        );
    }
    if status == TBASIS_OK && !nothing_to_copy {
        let span = span.expect("the copy ran, so the span is a number");
        let mut rust = before[base..base + span].to_vec();
        let result = tbasis::copy_split_vertices(&mut rust, stride, es, vertex_count, &sources);
        assert!(
            result.is_ok() && rust[..] == arena[base..base + span],
            "{what}: tbasis::copy_split_vertices gives {result:?} and other bytes"
        );
    }
    Ok(())
}
