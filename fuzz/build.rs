//! Links the C port of the original listing (`c_tests/listing.c`), the oracle for LEGACY's bits.

fn main() {
    println!("cargo:rerun-if-changed=../c_tests/listing.c");
    println!("cargo:rerun-if-changed=../c_tests/listing.h");
    // The port matches the listing bit for bit only when no multiply-add is fused.
    cc::Build::new()
        .file("../c_tests/listing.c")
        .flag("-ffp-contract=off")
        .compile("tbasis_listing");
}
