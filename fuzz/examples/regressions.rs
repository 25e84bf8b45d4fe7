//! Writes the regression inputs of the fuzz target `generate` from their cases: for each
//! `fuzz/regression_cases/NAME.txt`, the bytes `fuzz/regressions/NAME` that the target's input
//! format (`fuzz_targets/generate/`, read through `arbitrary`'s `Unstructured`) decodes to that
//! case, and checks that they do: the target's own code decodes them, describes what it decoded
//! (`fuzz_targets/generate/describe.rs`), and the description must equal the case line for line.
//!
//! ```text
//! cargo run --manifest-path fuzz/Cargo.toml --example regressions             # write every input
//! cargo run --manifest-path fuzz/Cargo.toml --example regressions -- --check  # compare instead
//! ```
//!
//! A case file holds `#` comments (what the finding was), the description lines the target
//! prints with `FUZZ_DESCRIBE=1`, and `hint` lines this writer needs beyond them (how the listing
//! call's buffers were packed). The inputs choose, where the format offers a choice, the form
//! that gives each value exactly: the buffers placed anywhere with their own strides, every float
//! as its bits, every index drawn alone. Only the cases' calls need bytes: the transforms and
//! the status probe before them, and the splits after them, read zeros (their ordinary cases).
//! When the input format changes, this writer changes with it, and `--check` (which
//! `.ci/fuzz.sh` does through the target itself) fails until it does.
#![allow(dead_code, clippy::type_complexity)]

#[path = "../fuzz_targets/generate/arena.rs"]
mod arena;
#[path = "../fuzz_targets/generate/call.rs"]
mod call;
#[allow(non_camel_case_types, dead_code)]
#[rustfmt::skip]
#[path = "../../src/codes.rs"]
mod codes;
#[path = "../fuzz_targets/generate/copy_split.rs"]
mod copy_split;
#[path = "../fuzz_targets/generate/describe.rs"]
mod describe;
#[allow(unexpected_cfgs)]
#[rustfmt::skip]
#[path = "../../src/fault.rs"]
mod fault;
#[allow(non_camel_case_types, dead_code, unsafe_op_in_unsafe_fn, unexpected_cfgs)]
#[rustfmt::skip]
#[path = "../../src/ffi.rs"]
mod ffi;
#[path = "../fuzz_targets/generate/frames.rs"]
mod frames;
#[rustfmt::skip]
#[path = "../../src/guard.rs"]
mod guard;
#[path = "../fuzz_targets/generate/input.rs"]
mod input;
#[path = "../../c_tests/listing.rs"]
mod listing;
#[path = "../fuzz_targets/generate/listing_entry.rs"]
mod listing_entry;
#[path = "../fuzz_targets/generate/mikktspace.rs"]
mod mikktspace;
#[path = "../fuzz_targets/generate/mikktspace_cost.rs"]
mod mikktspace_cost;
#[path = "../../crates/test-support/src/mikktspace_reference.rs"]
mod mikktspace_reference;
#[path = "../fuzz_targets/generate/outputs.rs"]
mod outputs;
#[path = "../fuzz_targets/generate/packed.rs"]
mod packed;
#[path = "../fuzz_targets/generate/plan.rs"]
mod plan;
#[path = "../fuzz_targets/generate/run.rs"]
mod run;
#[path = "../fuzz_targets/generate/rust_api.rs"]
mod rust_api;
#[path = "../fuzz_targets/generate/split.rs"]
mod split;
#[allow(non_camel_case_types, dead_code)]
#[rustfmt::skip]
#[path = "../../src/status.rs"]
mod status;
#[path = "../fuzz_targets/generate/statuses.rs"]
mod statuses;
#[path = "../fuzz_targets/generate/transform.rs"]
mod transform;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use arbitrary::Unstructured;

use crate::arena::Buf;
use crate::codes::TBASIS_INDEX_U16;
use crate::plan::{arena_len, scratch_needed, OWN_SCRATCH_MAX, SMALL_VERTICES};

/// The bytes `Unstructured` turns into the values asked for, one call at a time.
#[derive(Default)]
struct Writer {
    bytes: Vec<u8>,
}

impl Writer {
    /// `int_in_range(start..=end)` on an integer of `size` bytes giving `value`: as many bytes as
    /// the range needs, big-endian, the offset from `start`.
    fn int_in_range(&mut self, start: i128, end: i128, value: i128, size: usize) {
        assert!(start <= value && value <= end, "{value} outside {start}..={end}");
        let (delta, offset) = ((end - start) as u128, (value - start) as u128);
        let mut n = 0;
        while n < size && delta >> (8 * n) > 0 {
            n += 1;
        }
        for k in (0..n).rev() {
            self.bytes.push((offset >> (8 * k)) as u8);
        }
    }
    /// `input::weighted`: choice `index`.
    fn weighted(&mut self, weights: &[u16], index: usize) {
        let total: i128 = weights.iter().map(|&w| i128::from(w)).sum();
        let before: i128 = weights[..index].iter().map(|&w| i128::from(w)).sum();
        self.int_in_range(0, total - 1, before, 4);
    }
    /// `input::one_in::<N>`.
    fn one_in(&mut self, n: u8, value: bool) {
        self.int_in_range(0, i128::from(n) - 1, if value { i128::from(n) - 1 } else { 0 }, 1);
    }
    /// `input::below(n)`.
    fn below(&mut self, n: usize, value: usize) {
        if n > 0 {
            self.int_in_range(0, n as i128 - 1, value as i128, 8);
        } else {
            assert_eq!(value, 0);
        }
    }
    /// `input::nudge(n)`.
    fn nudge(&mut self, n: isize, value: isize) {
        self.int_in_range(-(n as i128 - 1), n as i128 - 1, value as i128, 8);
    }
    fn le(&mut self, value: u64, size: usize) {
        self.bytes.extend_from_slice(&value.to_le_bytes()[..size]);
    }
    fn bool(&mut self, value: bool) {
        self.bytes.push(u8::from(value));
    }
    /// A derived `Arbitrary` enum: variant `index` of `count`.
    fn variant(&mut self, index: u64, count: u64) {
        let x = (index << 32).div_ceil(count);
        assert_eq!((x * count) >> 32, index);
        self.le(x, 4);
    }
    fn zeros(&mut self, n: usize) {
        self.bytes.resize(self.bytes.len() + n, 0);
    }
    /// `input::pick_encoding` giving `Encoding::Raw`: each float its bits.
    fn raw_encoding(&mut self) {
        self.weighted(&[5, 2, 2, 1], 3);
        self.variant(6, 8);
    }
    /// `input::index_value` giving `value`.
    fn index_value(&mut self, value: u32, vertex_count: usize) {
        if (value as usize) < vertex_count {
            self.weighted(&[250, 6], 0);
            self.below(vertex_count, value as usize);
        } else {
            self.weighted(&[250, 6], 1);
            self.int_in_range(0, 3, 3, 1);
            self.le(u64::from(value), 4);
        }
    }
    /// `plan::pick_stride` giving `stride`.
    fn stride(&mut self, size: usize, count: usize, arena: usize, stride: usize) -> Result<(), String> {
        let fit = if count <= 1 {
            arena - size
        } else {
            ((arena - size) / (count - 1)).max(size)
        };
        let weights = [8, 3, 1, 1, 1, 1, 1];
        if stride == size {
            self.weighted(&weights, 0);
        } else if stride < size {
            self.weighted(&weights, 2);
            self.below(size, stride);
        } else if stride <= fit {
            self.weighted(&weights, 3);
            self.below(fit - size + 1, stride - size);
        } else if (count <= 1 && stride & size == size) || (count > 1 && stride >> 63 == 1) {
            self.weighted(&weights, 5);
            self.le(stride as u64, 8);
        } else {
            return Err(format!("stride {stride} of {count} elements of {size} bytes"));
        }
        Ok(())
    }
}

/// A case file: its description lines by key (the line up to `=`, or its first three words).
struct Case {
    lines: Vec<String>,
    hints: Vec<String>,
}

/// `key=value` pairs of a line.
fn fields(line: &str) -> HashMap<&str, &str> {
    line.split_whitespace()
        .filter_map(|word| word.split_once('='))
        .collect()
}

impl Case {
    fn parse(text: &str) -> Case {
        let mut case = Case {
            lines: Vec::new(),
            hints: Vec::new(),
        };
        for line in text
            .lines()
            .filter(|line| !line.trim().is_empty() && !line.starts_with('#'))
        {
            if let Some(hint) = line.strip_prefix("hint ") {
                case.hints.push(hint.to_string());
            } else {
                case.lines.push(line.to_string());
            }
        }
        case
    }
    /// The line starting with `prefix` (followed by a space).
    fn line(&self, prefix: &str) -> Option<&str> {
        self.lines
            .iter()
            .find(|line| line.strip_prefix(prefix).is_some_and(|rest| rest.starts_with(' ')))
            .map(String::as_str)
    }
    fn field<T: std::str::FromStr>(&self, prefix: &str, name: &str) -> T
    where
        T::Err: std::fmt::Debug,
    {
        let line = self.line(prefix).unwrap_or_else(|| panic!("no line {prefix}"));
        fields(line)[name]
            .parse()
            .unwrap_or_else(|e| panic!("{prefix} {name}: {e:?}"))
    }
    /// The words after `prefix K =` of each element line, in order of `K`.
    fn elements(&self, prefix: &str) -> Vec<Vec<String>> {
        let mut found = Vec::new();
        for line in &self.lines {
            let Some(rest) = line.strip_prefix(prefix).and_then(|r| r.strip_prefix(' ')) else {
                continue;
            };
            let (k, values) = rest.split_once(" = ").unwrap();
            assert_eq!(k.parse::<usize>().unwrap(), found.len(), "{prefix} out of order");
            found.push(values.split_whitespace().map(str::to_string).collect());
        }
        found
    }
    fn hint(&self, prefix: &str) -> Option<HashMap<String, String>> {
        let hint = self.hints.iter().find(|h| h.starts_with(prefix))?;
        Some(
            fields(hint)
                .into_iter()
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .collect(),
        )
    }
}

fn flag(value: &str) -> bool {
    value == "1"
}

/// Buffer `name` of the `generate` call: null, base, stride.
fn buffer(case: &Case, name: &str) -> (bool, usize, usize) {
    let line = case
        .line(&format!("generate buffer {name}"))
        .unwrap_or_else(|| panic!("no buffer {name}"));
    let f = fields(line);
    (
        flag(f["null"]),
        f["base"].parse().unwrap(),
        f["stride"].parse().unwrap(),
    )
}

/// `plan::pick_scratch` giving the scratch of line `line` for `needed` bytes.
fn scratch(w: &mut Writer, line: &str, needed: usize, arena: usize) -> Result<(), String> {
    let words: Vec<&str> = line.split_whitespace().collect();
    let f = fields(line);
    let get = |name: &str| -> i128 { f[name].parse().unwrap() };
    let weights = [4, 1, 1, 1, 1];
    match words[2] {
        "none" => {
            w.weighted(&weights, 0);
            let claimed = get("claimed");
            w.one_in(4, claimed != 0);
            if claimed != 0 {
                w.le(claimed as u64, 8);
            }
        }
        "exact" | "offset" if needed > OWN_SCRATCH_MAX => return Err(format!("scratch of {needed} bytes")),
        "exact" => {
            w.weighted(&weights, 1);
            w.below(4, get("base") as usize);
        }
        "offset" => {
            w.weighted(&weights, 2);
            let delta = get("delta");
            if delta < 0 {
                // claimed = needed - 1 - below(min(needed, 8))
                assert!(needed > 0);
                w.bool(true);
                w.below(needed.min(8), (-delta - 1) as usize);
            } else {
                if needed > 0 {
                    w.bool(false);
                }
                w.below(64, delta as usize);
            }
            w.below(4, get("base") as usize);
        }
        "main" if needed > arena - 16 => return Err(format!("scratch of {needed} bytes in an arena of {arena}")),
        "main" => {
            w.weighted(&weights, 3);
            let claimed = needed + get("delta") as usize;
            w.below(16, get("delta") as usize);
            w.bool(true);
            w.below(arena - claimed + 1, get("base") as usize);
        }
        "huge" => {
            w.weighted(&weights, 4);
            w.below(4, get("base") as usize);
            w.le(get("claimed") as u64, 8);
        }
        kind => panic!("scratch {kind}"),
    }
    Ok(())
}

/// `plan::Codes`' method, policy, flags, threads and threshold giving these values.
fn codes(w: &mut Writer, method: u32, policy: u32, flags: u32, threads: u32, threshold: u32) {
    match method {
        0 => w.weighted(&[6, 4, 5, 1], 0),
        1..=8 => {
            w.weighted(&[6, 4, 5, 1], 2);
            w.int_in_range(0, 8, method.into(), 4);
        }
        _ => {
            w.weighted(&[6, 4, 5, 1], 3);
            w.le(method.into(), 4);
        }
    }
    let policy_weights = [3, 3, 3, 3, 2, 1, 1];
    match policy {
        0..=5 => w.weighted(&policy_weights, policy as usize),
        _ => {
            w.weighted(&policy_weights, 6);
            w.le(policy.into(), 4);
        }
    }
    match flags {
        0 => w.weighted(&[5, 2, 1], 0),
        _ => {
            w.weighted(&[5, 2, 1], 2);
            w.le(flags.into(), 4);
        }
    }
    match threads {
        0 => w.weighted(&[5, 1, 1, 1], 0),
        _ => {
            w.weighted(&[5, 1, 1, 1], 3);
            w.le(threads.into(), 4);
        }
    }
    let threshold_weights = [8, 1, 1, 1, 1, 1, 1, 1, 1];
    if threshold == 0 {
        w.weighted(&threshold_weights, 0);
    } else {
        w.weighted(&threshold_weights, 7);
        w.le(threshold.into(), 4);
    }
}

/// Floats given by their bits, element by element.
fn floats(w: &mut Writer, elements: &[Vec<String>]) {
    for element in elements {
        for bits in element {
            w.le(u32::from_str_radix(bits, 16).unwrap().into(), 4);
        }
    }
}

/// The calls of `run::run` before `decode_plan`, on zeros: how many bytes they read.
fn prefix_len() -> usize {
    let zeros = vec![0u8; 1 << 16];
    let mut u = Unstructured::new(&zeros);
    // The status probe (`one_in::<4>`, then `int_in_range(0..=31)`) and the transforms.
    let _ = input::one_in::<4>(&mut u);
    let _ = u.int_in_range(0..=31u32);
    transform::check(&mut u).unwrap();
    zeros.len() - u.len()
}

/// The `tbasis_calculate_tangent_array` call's part (`listing_entry::check_listing_entry`).
fn listing_call(w: &mut Writer, case: &Case) -> Result<(), String> {
    let long = |w: &mut Writer, value: i64, small_max: u8, huge_bit: u32| {
        if (0..=i64::from(small_max)).contains(&value) {
            w.weighted(&[14, 1, 1], 0);
            w.int_in_range(0, small_max.into(), value.into(), 1);
        } else if value < 0 {
            w.weighted(&[14, 1, 1], 1);
            w.one_in(4, value == i64::MIN);
            if value != i64::MIN {
                w.le(2 * (-1 - value) as u64, 4);
            }
        } else {
            assert!(value >> huge_bit != 0);
            w.weighted(&[14, 1, 1], 2);
            w.le(value as u64, 8);
        }
    };
    let vertex_count: i64 = case.field("listing counts", "vertices");
    let triangle_count: i64 = case.field("listing counts", "triangles");
    long(w, vertex_count, SMALL_VERTICES as u8, 60);
    long(w, triangle_count, 32, 61);
    let names = ["vertex", "normal", "texcoord", "triangle", "tangent"];
    for name in names {
        w.one_in(32, case.field::<u8>(&format!("listing buffer {name}"), "null") == 1);
    }
    let hint = case.hint("listing").ok_or("no hint for the listing call's buffers")?;
    let list = |key: &str| -> Vec<usize> {
        hint[key]
            .split(',')
            .filter(|s| !s.is_empty())
            .map(|s| s.parse().unwrap())
            .collect()
    };
    for (i, j) in (1..5usize).rev().zip(list("shuffle")) {
        w.below(i + 1, j);
    }
    w.below(8, hint["start"].parse().unwrap());
    for gap in list("gaps") {
        w.below(8, gap);
    }
    let near = &hint["near"];
    w.one_in(4, near != "none");
    if let Some((source, delta)) = near.split_once(',') {
        w.below(4, source.parse().unwrap());
        w.nudge(20, delta.parse().unwrap());
    }
    w.le(case.field::<u64>("listing fills", "arena"), 1);
    for _ in 0..3 {
        w.raw_encoding();
    }
    floats(w, &case.elements("listing vertex"));
    floats(w, &case.elements("listing normal"));
    floats(w, &case.elements("listing texcoord"));
    let vc = usize::try_from(vertex_count).unwrap_or(0);
    for value in case.elements("listing triangle") {
        w.index_value(value[0].parse().unwrap(), vc);
    }
    Ok(())
}

/// The bytes that decode to `case`.
fn encode(case: &Case) -> Result<Vec<u8>, String> {
    let mut w = Writer::default();
    w.zeros(prefix_len());
    w.one_in(4, case.line("listing counts").is_some());

    // decode_plan
    let vertex_count: usize = case.field("generate counts", "vertices");
    match vertex_count {
        0..=64 => {
            w.weighted(&[250, 4, 1, 1], 0);
            w.below(65, vertex_count);
        }
        65..=512 => {
            w.weighted(&[250, 4, 1, 1], 1);
            w.int_in_range(65, 512, vertex_count as i128, 8);
        }
        513..=4096 => {
            w.weighted(&[250, 4, 1, 1], 2);
            w.int_in_range(513, 4096, vertex_count as i128, 8);
        }
        _ => {
            assert!(vertex_count >> 60 & 1 == 1, "vertex count {vertex_count}");
            w.weighted(&[250, 4, 1, 1], 3);
            w.le(vertex_count as u64, 8);
        }
    }
    let names = ["positions", "normals", "texcoords", "tangents", "bitangents", "indices"];
    let bufs: Vec<(bool, usize, usize)> = names.iter().map(|name| buffer(case, name)).collect();
    for (k, n) in [(0, 32), (1, 32), (2, 8), (3, 32)] {
        w.one_in(n, bufs[k].0);
    }
    w.bool(bufs[4].0);
    w.one_in(3, bufs[5].0);
    let index_type: u32 = case.field("generate counts", "index_type");
    match index_type {
        1 => w.weighted(&[8, 6, 1, 1], 0),
        2 => w.weighted(&[8, 6, 1, 1], 1),
        0 | 3 => {
            w.weighted(&[8, 6, 1, 1], 2);
            w.int_in_range(0, 1, i128::from(index_type / 3), 8);
        }
        _ => {
            w.weighted(&[8, 6, 1, 1], 3);
            w.le(index_type.into(), 4);
        }
    }
    let index_size = if index_type == TBASIS_INDEX_U16 { 2 } else { 4 };
    let index_count: usize = case.field("generate counts", "indices");
    if bufs[5].0 {
        w.one_in(16, index_count != 0);
        if index_count != 0 {
            w.le(index_count as u64, 2);
        }
    } else {
        let triangles = (2 * vertex_count.min(4096)).clamp(96, 8192);
        if index_count % 3 == 0 && index_count / 3 <= triangles {
            w.weighted(&[28, 3, 1], 0);
            w.below(triangles + 1, index_count / 3);
        } else if index_count < 3 * triangles + 3 {
            w.weighted(&[28, 3, 1], 1);
            w.below(3 * triangles + 3, index_count);
        } else {
            assert!(index_count >> 62 & 1 == 1, "index count {index_count}");
            w.weighted(&[28, 3, 1], 2);
            w.le(index_count as u64, 8);
        }
    }
    let corner_count = if bufs[5].0 { vertex_count } else { index_count };
    let arena = arena_len(vertex_count, corner_count);
    // Layout::Anywhere: every stride, then every base.
    w.weighted(&[4, 2, 1, 1], 2);
    let sizes = [12, 12, 8, 16, 12, index_size];
    for k in 0..5 {
        w.stride(sizes[k], vertex_count, arena, bufs[k].2)?;
    }
    for k in 0..6 {
        let (count, stride) = if k == 5 {
            (index_count, index_size)
        } else {
            (vertex_count, bufs[k].2)
        };
        let b = Buf {
            null: bufs[k].0,
            base: 0,
            stride,
            size: sizes[k],
            count,
        };
        let room = b.extent().map_or(arena, |e| arena.saturating_sub(e) + 1);
        if bufs[k].1 >= room {
            return Err(format!("{} at {} past {room}", names[k], bufs[k].1));
        }
        w.below(room, bufs[k].1);
    }
    // No output moved near another buffer.
    w.one_in(16, false);
    let nulls = |prefix: &str, name: &str| case.field::<u8>(&format!("{prefix} nulls"), name) == 1;
    w.one_in(64, nulls("generate", "mesh"));
    w.one_in(64, nulls("generate", "output"));
    w.one_in(16, nulls("generate", "options"));
    w.one_in(8, nulls("generate", "report"));
    let code = |prefix: &str, name: &str| case.field::<u32>(&format!("{prefix} codes"), name);
    let (method, policy, flags, threads) = (
        code("generate", "method"),
        code("generate", "policy"),
        code("generate", "flags"),
        code("generate", "threads"),
    );
    let threshold = u32::from_str_radix(fields(case.line("generate codes").unwrap())["threshold"], 16).unwrap();
    codes(&mut w, method, policy, flags, threads, threshold);
    let indices = Buf {
        null: bufs[5].0,
        base: 0,
        stride: index_size,
        size: index_size,
        count: index_count,
    };
    let needed = scratch_needed(
        vertex_count,
        &indices,
        nulls("generate", "options"),
        [method, policy, flags, threads],
        f32::from_bits(threshold),
    );
    scratch(&mut w, case.line("generate scratch").unwrap(), needed, arena)?;
    let offsets = |w: &mut Writer, prefix: &str, corners: bool| {
        let line = case.line(&format!("{prefix} struct_offsets")).unwrap();
        let values: Vec<usize> = line.split_whitespace().skip(2).map(|v| v.parse().unwrap()).collect();
        w.below(8, values[0]);
        w.below(8, values[1]);
        if !corners {
            w.below(8, values[2]);
        }
        w.below(9, values[3]);
    };
    offsets(&mut w, "generate", false);
    w.le(case.field::<u64>("generate fills", "arena"), 1);
    w.le(case.field::<u64>("generate fills", "scratch"), 1);
    for _ in 0..3 {
        w.raw_encoding();
    }
    // IndexPattern::Random.
    w.variant(0, 3);

    // write_inputs
    floats(&mut w, &case.elements("generate positions"));
    floats(&mut w, &case.elements("generate normals"));
    floats(&mut w, &case.elements("generate texcoords"));
    for value in case.elements("generate indices") {
        w.index_value(value[0].parse().unwrap(), vertex_count);
    }

    if case.line("listing counts").is_some() {
        listing_call(&mut w, case)?;
    }

    // decode_corners_plan
    let (c_method, c_policy, c_flags, c_threads) = (
        code("corners", "method"),
        code("corners", "policy"),
        code("corners", "flags"),
        code("corners", "threads"),
    );
    if c_method == method {
        w.weighted(&[10, 5, 1], 0);
    } else if c_method <= 6 {
        w.weighted(&[10, 5, 1], 1);
        w.int_in_range(0, 6, c_method.into(), 4);
    } else {
        w.weighted(&[10, 5, 1], 2);
        w.le(c_method.into(), 4);
    }
    match (c_policy == policy, c_flags == flags) {
        (true, true) => w.weighted(&[6, 1, 1], 0),
        (false, true) if c_policy <= 5 => {
            w.weighted(&[6, 1, 1], 1);
            w.int_in_range(0, 5, c_policy.into(), 4);
        }
        (true, false) if c_flags == flags ^ codes::TBASIS_FLAG_FLIP_V => w.weighted(&[6, 1, 1], 2),
        _ => return Err("the corners call's policy and flags".into()),
    }
    w.one_in(8, c_threads != threads);
    if c_threads != threads {
        w.int_in_range(0, 3, c_threads.into(), 4);
    }
    w.one_in(64, nulls("corners", "mesh"));
    w.one_in(64, false);
    w.one_in(16, nulls("corners", "options"));
    w.one_in(8, nulls("corners", "report"));
    let tangents = fields(case.line("corners tangents").unwrap());
    let (t_null, t_base, t_stride): (bool, usize, usize) = (
        flag(tangents["null"]),
        tangents["base"].parse().unwrap(),
        tangents["stride"].parse().unwrap(),
    );
    w.stride(16, corner_count, arena, t_stride)?;
    // Anywhere in the arena.
    w.weighted(&[6, 1, 1], 1);
    w.below(arena, t_base);
    w.one_in(32, t_null);
    let needed = scratch_needed(
        vertex_count,
        &indices,
        nulls("corners", "options"),
        [c_method, c_policy, c_flags, c_threads],
        f32::from_bits(threshold),
    );
    scratch(&mut w, case.line("corners scratch").unwrap(), needed, arena)?;
    offsets(&mut w, "corners", true);
    w.le(case.field::<u64>("corners fills", "scratch"), 1);
    Ok(w.bytes)
}

/// What the target decodes `bytes` to.
fn decoded(bytes: &[u8]) -> String {
    describe::start();
    let _ = run::run(&mut Unstructured::new(bytes));
    describe::take().unwrap()
}

fn main() {
    let check = std::env::args().any(|arg| arg == "--check");
    let fuzz = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut cases: Vec<PathBuf> = std::fs::read_dir(fuzz.join("regression_cases"))
        .expect("fuzz/regression_cases")
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "txt"))
        .collect();
    cases.sort();
    let mut failed = 0;
    for path in &cases {
        let name = path.file_stem().unwrap().to_str().unwrap();
        let case = Case::parse(&std::fs::read_to_string(path).unwrap());
        let input = fuzz.join("regressions").join(name);
        let bytes = match encode(&case) {
            Ok(bytes) => bytes,
            Err(why) => {
                eprintln!("{name}: cannot be written in the current input format: {why}");
                failed += 1;
                continue;
            }
        };
        let got = decoded(&bytes);
        let want: String = case.lines.iter().map(|line| format!("{line}\n")).collect();
        if got != want {
            let first = got.lines().zip(want.lines()).position(|(g, w)| g != w);
            eprintln!(
                "{name}: the bytes decode to another case (first difference at line {first:?}):\n{}",
                first.map_or(String::new(), |i| format!(
                    "  got  {}\n  want {}",
                    got.lines().nth(i).unwrap_or(""),
                    want.lines().nth(i).unwrap_or("")
                ))
            );
            failed += 1;
            continue;
        }
        if check {
            if std::fs::read(&input).ok().as_deref() != Some(&bytes[..]) {
                eprintln!("{name}: {} differs from what its case gives", input.display());
                failed += 1;
            }
        } else {
            std::fs::write(&input, &bytes).unwrap();
        }
    }
    // Every input has its case.
    for entry in std::fs::read_dir(fuzz.join("regressions")).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_str().unwrap().to_string();
        if !fuzz.join("regression_cases").join(format!("{name}.txt")).exists() {
            eprintln!("{name}: an input in fuzz/regressions without a case in fuzz/regression_cases");
            failed += 1;
        }
    }
    eprintln!(
        "{} cases, {} {}",
        cases.len(),
        cases.len() - failed.min(cases.len()),
        if check { "checked" } else { "written" }
    );
    if failed > 0 {
        std::process::exit(1);
    }
}
