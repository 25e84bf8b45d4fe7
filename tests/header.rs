//! The committed header is the one the build generates from src/ffi.rs.

#[test]
fn committed_header_matches_the_generated_one() {
    let generated = std::fs::read_to_string(concat!(env!("OUT_DIR"), "/tbasis.h")).expect("generated header");
    let committed =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/include/tbasis.h")).expect("include/tbasis.h");
    assert!(
        generated == committed,
        "include/tbasis.h is stale: run `TBASIS_WRITE_HEADER=1 cargo build` and commit it"
    );
}
