//! Generates the C header from `src/` into `$OUT_DIR/tbasis.h`, with version macros from
//! Cargo.toml. The committed `include/tbasis.h` must equal it: a test compares the two, and
//! `TBASIS_WRITE_HEADER=1 cargo build` copies the generated one over the committed one.
//!
//! It also gives the Linux shared library its soname (and the build tree a link of that name),
//! as `crates/mikktspace-c/build.rs` does for `libtbasis_mikktspace`: both through
//! `packaging/soname.rs`.

use std::env;
use std::path::PathBuf;

#[path = "packaging/soname.rs"]
mod soname;

fn main() {
    let crate_dir = PathBuf::from(env::var("CARGO_MANIFEST_DIR").unwrap());
    let out = PathBuf::from(env::var("OUT_DIR").unwrap()).join("tbasis.h");
    println!("cargo:rerun-if-changed=src");
    println!("cargo:rerun-if-changed=cbindgen.toml");
    println!("cargo:rerun-if-env-changed=TBASIS_WRITE_HEADER");

    let version = |part: &str| env::var(format!("CARGO_PKG_VERSION_{part}")).unwrap();
    let (major, minor, patch) = (version("MAJOR"), version("MINOR"), version("PATCH"));
    soname::set_soname("tbasis");
    let mut config = cbindgen::Config::from_file(crate_dir.join("cbindgen.toml")).expect("cbindgen.toml");
    config.after_includes = Some(format!(
        "\n#define TBASIS_VERSION_MAJOR {major}\n#define TBASIS_VERSION_MINOR {minor}\n#define TBASIS_VERSION_PATCH {patch}\n\
         /* TBASIS_VERSION_MAJOR * 1000000 + TBASIS_VERSION_MINOR * 1000 + TBASIS_VERSION_PATCH; compare with tbasis_version(). */\n\
         #define TBASIS_VERSION ({major} * 1000000 + {minor} * 1000 + {patch})\n\n\
         // A report's `first_degenerate_triangle` or `failed_triangle` when there is no such triangle.\n\
         #define TBASIS_NO_TRIANGLE SIZE_MAX\n"
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
}
