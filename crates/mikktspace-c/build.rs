//! Gives the Linux shared library its soname, `libtbasis_mikktspace.so.0.MINOR` (MAJOR from 1.0),
//! and the build tree a link of that name, as the root `build.rs` does for `libtbasis`.

#[path = "../../packaging/soname.rs"]
mod soname;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    soname::set_soname("tbasis_mikktspace");
}
