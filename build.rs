//! Generates the C header from `src/ffi.rs` into `$OUT_DIR/tbasis.h`, with version macros from
//! Cargo.toml. The committed `include/tbasis.h` must equal it: a test compares the two, and
//! `TBASIS_WRITE_HEADER=1 cargo build` copies the generated one over the committed one.

use std::env;
use std::path::PathBuf;

fn main() {
    let crate_dir = PathBuf::from(env::var("CARGO_MANIFEST_DIR").unwrap());
    let out = PathBuf::from(env::var("OUT_DIR").unwrap()).join("tbasis.h");
    println!("cargo:rerun-if-changed=src");
    println!("cargo:rerun-if-changed=cbindgen.toml");
    println!("cargo:rerun-if-env-changed=TBASIS_WRITE_HEADER");

    let version = |part: &str| env::var(format!("CARGO_PKG_VERSION_{part}")).unwrap();
    let (major, minor, patch) = (version("MAJOR"), version("MINOR"), version("PATCH"));
    set_soname(&major, &minor);
    let mut config = cbindgen::Config::from_file(crate_dir.join("cbindgen.toml")).expect("cbindgen.toml");
    config.after_includes = Some(format!(
        "\n#define TBASIS_VERSION_MAJOR {major}\n#define TBASIS_VERSION_MINOR {minor}\n#define TBASIS_VERSION_PATCH {patch}\n\
         /* TBASIS_VERSION_MAJOR * 1000000 + TBASIS_VERSION_MINOR * 1000 + TBASIS_VERSION_PATCH; compare with tbasis_version(). */\n\
         #define TBASIS_VERSION ({major} * 1000000 + {minor} * 1000 + {patch})\n"
    ));
    cbindgen::Builder::new()
        .with_crate(&crate_dir)
        .with_config(config)
        .generate()
        .expect("cbindgen could not generate the header")
        .write_to_file(&out);

    if env::var_os("TBASIS_WRITE_HEADER").is_some() {
        std::fs::copy(&out, crate_dir.join("include/tbasis.h")).expect("copy header");
    }

    compile_listing(&crate_dir);
}

/// Compiles `c_tests/listing.c`, the C port of the original listing, into a static archive that
/// only examples and benches link (they compare against it). cc's own link metadata is turned off:
/// it would link the archive into the library too, whose exports must stay `tbasis_*` only.
fn compile_listing(crate_dir: &std::path::Path) {
    println!("cargo:rerun-if-changed=c_tests/listing.c");
    println!("cargo:rerun-if-changed=c_tests/listing.h");
    let mut build = cc::Build::new();
    build.file(crate_dir.join("c_tests/listing.c")).cargo_metadata(false);
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
    // Cargo refuses a bench link argument in a package without benches; benches/ is watched once
    // it exists (a new benches/ needs one rebuild of this script: touch build.rs).
    if crate_dir.join("benches").is_dir() {
        println!("cargo:rerun-if-changed=benches");
        println!("cargo:rustc-link-arg-benches={}", archive.display());
    }
}

/// Gives the Linux shared library the ABI name that executables record and later load:
/// `libtbasis.so.MAJOR`, or `libtbasis.so.0.MINOR` while MAJOR is 0, since Cargo treats a 0.x
/// minor release as breaking. `scripts/install.sh` creates the symlink of that name.
fn set_soname(major: &str, minor: &str) {
    if env::var("CARGO_CFG_TARGET_OS").as_deref() != Ok("linux") {
        return;
    }
    let soname = if major == "0" {
        format!("libtbasis.so.0.{minor}")
    } else {
        format!("libtbasis.so.{major}")
    };
    println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,{soname}");
}
