//! A need that `build.rs` found missing compiled its tests as ignored (`tests/common/needs.rs` of
//! the repository). Installing it later does not run `build.rs` again: this test fails then.

#[path = "../../../tests/common/needs.rs"]
#[allow(dead_code)]
mod needs;

#[test]
fn needs_found_missing_at_build_time_are_still_missing() {
    needs::assert_none_appeared_since(env!("TBASIS_MISSING_NEEDS"), "tools/gltf/build.rs");
}
