//! The soname of a C library's Linux shared object, for the build scripts of `libtbasis` (the
//! root `build.rs`) and `libtbasis_mikktspace` (`crates/mikktspace-c/build.rs`), which include this
//! file as a module. `scripts/install.sh` gives the installed files the same names.

use std::env;
use std::path::{Path, PathBuf};

/// Gives the Linux shared library `lib{name}.so` the ABI name that executables record and later
/// load: `lib{name}.so.MAJOR`, or `lib{name}.so.0.MINOR` while MAJOR is 0, since Cargo treats a
/// 0.x minor release as breaking (the package's version). `scripts/install.sh` creates the
/// symlink of that name.
pub fn set_soname(name: &str) {
    if env::var("CARGO_CFG_TARGET_OS").as_deref() != Ok("linux") {
        return;
    }
    let version = |part: &str| env::var(format!("CARGO_PKG_VERSION_{part}")).unwrap();
    let (major, minor) = (version("MAJOR"), version("MINOR"));
    let file = format!("lib{name}.so");
    let soname = if major == "0" {
        format!("{file}.0.{minor}")
    } else {
        format!("{file}.{major}")
    };
    println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,{soname}");
    link_soname_in_build_tree(&file, &soname);
}

/// A program linked with `-Ltarget/release -l{name}` loads the soname, but cargo writes only
/// `file` (`lib{name}.so`): a relative `soname -> file` symlink beside it lets the program run from
/// the build tree with `LD_LIBRARY_PATH=target/release`. An rpath would not help: it belongs in the
/// program, which the user links. Links to `file` left by an older soname are removed, so that
/// programs built against it fail to start rather than load an incompatible library.
fn link_soname_in_build_tree(file: &str, soname: &str) {
    // OUT_DIR is <profile dir>/build/<package>-<hash>/out, and cargo puts the library in the
    // profile dir; in any other layout there is nowhere certain to put the link.
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
    let older = format!("{file}.");
    for entry in entries.flatten() {
        let name = entry.file_name();
        let is_ours = name.to_str().is_some_and(|n| n.starts_with(&older) && n != soname);
        if is_ours && std::fs::read_link(entry.path()).is_ok_and(|target| target == Path::new(file)) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
    let link = profile_dir.join(soname);
    match std::fs::read_link(&link) {
        Ok(target) if target == Path::new(file) => return,
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
    if let Err(e) = std::os::unix::fs::symlink(file, &link) {
        println!("cargo:warning=cannot create {}: {e}", link.display());
    }
}
