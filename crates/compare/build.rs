//! Compiles `c_tests/listing.c`, the C port of the original listing, into a static archive that
//! the examples link to compare against it.

use std::env;
use std::path::PathBuf;

fn main() {
    let listing = PathBuf::from(env::var("CARGO_MANIFEST_DIR").unwrap()).join("../../c_tests");
    println!("cargo:rerun-if-changed={}", listing.join("listing.c").display());
    println!("cargo:rerun-if-changed={}", listing.join("listing.h").display());
    let mut build = cc::Build::new();
    build.file(listing.join("listing.c")).cargo_metadata(false);
    // The port matches the listing bit for bit only when no multiply-add is fused.
    let msvc = build.get_compiler().is_like_msvc();
    build.flag(if msvc { "/fp:precise" } else { "-ffp-contract=off" });
    build.compile("tbasis_listing");
    let archive = PathBuf::from(env::var("OUT_DIR").unwrap()).join(if msvc {
        "tbasis_listing.lib"
    } else {
        "libtbasis_listing.a"
    });
    println!("cargo:rustc-link-arg-examples={}", archive.display());
}
