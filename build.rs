//! Generates the C header from `src/` into `$OUT_DIR/tbasis.h`, with version macros from
//! Cargo.toml. The committed `include/tbasis.h` must equal it: a test compares the two, and
//! `TBASIS_WRITE_HEADER=1 cargo build` copies the generated one over the committed one.
//!
//! It also gives the Linux shared library its soname (and the build tree a link of that name).

use std::env;
use std::path::{Path, PathBuf};

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
    link_soname_in_build_tree(&soname);
}

/// A program linked with `-Ltarget/release -ltbasis` loads the soname, but cargo writes only
/// `libtbasis.so`: a relative `soname -> libtbasis.so` symlink beside it lets the program run from
/// the build tree with `LD_LIBRARY_PATH=target/release`. An rpath would not help: it belongs in the
/// program, which the user links. Links left by an older soname are removed, so that programs
/// built against it fail to start rather than load an incompatible library.
fn link_soname_in_build_tree(soname: &str) {
    // OUT_DIR is <profile dir>/build/tbasis-<hash>/out, and cargo puts libtbasis.so in the profile
    // dir; in any other layout there is nowhere certain to put the link.
    let out_dir = PathBuf::from(env::var("OUT_DIR").unwrap());
    let mut ancestors = out_dir.ancestors().skip(2);
    let (Some(build), Some(profile_dir)) = (ancestors.next(), ancestors.next()) else {
        return;
    };
    if build.file_name() != Some("build".as_ref()) {
        return;
    }
    let Ok(entries) = std::fs::read_dir(profile_dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let is_ours = name
            .to_str()
            .is_some_and(|n| n.starts_with("libtbasis.so.") && n != soname);
        if is_ours && std::fs::read_link(entry.path()).is_ok_and(|target| target == Path::new("libtbasis.so")) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
    let link = profile_dir.join(soname);
    match std::fs::read_link(&link) {
        Ok(target) if target == Path::new("libtbasis.so") => return,
        Ok(_) => {
            let _ = std::fs::remove_file(&link);
        }
        Err(_) if link.symlink_metadata().is_ok() => {
            println!("cargo:warning={} is not a symlink; left as it is", link.display());
            return;
        }
        Err(_) => {}
    }
    #[cfg(unix)]
    if let Err(e) = std::os::unix::fs::symlink("libtbasis.so", &link) {
        println!("cargo:warning=cannot create {}: {e}", link.display());
    }
}
