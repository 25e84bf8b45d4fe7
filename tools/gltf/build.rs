//! Tells the tests which of their needs (the mesh corpus, the glTF Validator) are missing, with
//! the repository's shared mechanism (`tests/common/needs.rs`): a need found missing sets the cfg
//! `tbasis_missing_<name>`, which compiles the tests that need it as ignored. Under CI (`CI` set)
//! nothing is probed, so such tests run and fail.

use std::env;

#[allow(dead_code)]
#[path = "../../tests/common/needs.rs"]
mod needs;

/// The needs of this crate's tests; the others are declared so that their cfgs are known.
const USED: [&needs::Need; 2] = [&needs::CORPUS, &needs::GLTF_VALIDATOR];

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=../../tests/common/needs.rs");
    println!("cargo:rerun-if-env-changed=CI");
    let manifest = needs::corpus_manifest();
    if manifest.is_file() {
        println!("cargo:rerun-if-changed={}", manifest.display());
    }
    let probe = env::var_os("CI").is_none();
    let mut missing = Vec::new();
    for need in needs::ALL {
        println!("cargo::rustc-check-cfg=cfg(tbasis_missing_{})", need.name);
        let used = USED.iter().any(|u| u.name == need.name);
        if probe && used && !need.found() {
            println!("cargo::rustc-cfg=tbasis_missing_{}", need.name);
            missing.push(need.name);
        }
    }
    println!("cargo::rustc-env=TBASIS_MISSING_NEEDS={}", missing.join(","));
}
