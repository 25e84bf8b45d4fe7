//! Fuzzes `tbasis-gltf`'s reader and converter (`tools/gltf`): the input is a whole file, a .glb
//! when it starts with GLB's magic `glTF`, a .gltf otherwise, whose buffers come from its GLB
//! binary chunk, `data:` URIs, or the files of a fixed folder (`a.bin` of 4096 bytes, `b.bin` of
//! 12) that the URIs may name. The file is read ([`io::parse`]) and converted
//! ([`convert::convert_asset`]) with options its last byte picks, and the output is encoded but
//! not written (inputs with huge accessors of zeros stop after the reading). Any outcome but a
//! panic (or a sanitizer report) is fine: an error message is the tool's answer to a bad file.
//!
//! Seeds: written by `cargo run -p tbasis-gltf --example fuzz_seeds -- DIR` (`.ci/fuzz.sh` puts them
//! in `fuzz/corpus/gltf_tool_seeds`), a mirrored quad as .gltf and .glb, and one that also reads
//! `a.bin` and has sparse accessors and an existing TANGENT; all three convert. `fuzz/gltf_tool.dict`
//! holds the words of glTF for the mutator.
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use tbasis::{DegeneratePolicy, Method, Options};
use tbasis_gltf::{convert, io};

/// The folder the input lies in, with the files its URIs may name; made once per process.
fn folder() -> &'static PathBuf {
    static FOLDER: OnceLock<PathBuf> = OnceLock::new();
    FOLDER.get_or_init(|| {
        let dir = tempfile::Builder::new()
            .prefix("tbasis-gltf-fuzz-")
            .tempdir()
            .expect("a temporary folder")
            .keep();
        let pattern: Vec<u8> = (0..4096u32).map(|i| (i.wrapping_mul(2654435761) >> 24) as u8).collect();
        std::fs::write(dir.join("a.bin"), pattern).expect("write a.bin");
        std::fs::write(dir.join("b.bin"), [0u8; 12]).expect("write b.bin");
        dir
    })
}

/// The most elements of an accessor without a bufferView converted (see below).
const MAX_ZERO_FILLED_COUNT: u64 = 1 << 16;

const METHODS: [Method; 5] = [
    Method::Mikktspace,
    Method::Angle,
    Method::Lengyel,
    Method::Area,
    Method::Uniform,
];
const POLICIES: [DegeneratePolicy; 4] = [
    DegeneratePolicy::Skip,
    DegeneratePolicy::Legacy,
    DegeneratePolicy::Inherit,
    DegeneratePolicy::Reject,
];

fuzz_target!(|data: &[u8]| {
    let dir = folder();
    let pick = usize::from(data.last().copied().unwrap_or(0));
    let options = Options::default()
        .with_method(METHODS[pick % METHODS.len()])
        .with_policy(POLICIES[pick / METHODS.len() % POLICIES.len()])
        .with_flip_v(true)
        .with_threads(1);
    let settings = convert::Settings {
        options,
        overwrite: pick & 0x80 != 0,
        allow_outside_uris: false,
        replace_side_files: false,
        threads: 1,
        side_files: convert::SideFiles::default(),
    };
    let Ok(asset) = io::parse(data.to_vec(), dir.clone(), false) else {
        return;
    };
    // An accessor without a bufferView is zeros of any count the JSON says (up to
    // `accessor::MAX_ZEROS` elements): a mesh that large is slow, not wrong, and would only time out.
    let accessors = asset.json["accessors"].as_array().into_iter().flatten();
    if accessors
        .filter(|accessor| accessor.get("bufferView").is_none())
        .any(|accessor| {
            accessor["count"]
                .as_u64()
                .is_none_or(|count| count > MAX_ZERO_FILLED_COUNT)
        })
    {
        return;
    }
    let output = dir.join(if data.starts_with(b"glTF") {
        "out.glb"
    } else {
        "out.gltf"
    });
    let _ = convert::convert_asset(asset, Some(&output), &settings, |files| {
        // What a write would read: every piece, to the last byte.
        let bytes: usize = files.iter().flat_map(|(_, pieces)| pieces).map(|p| p.len()).sum();
        std::hint::black_box(bytes);
        Ok(())
    });
});
