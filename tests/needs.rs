//! A need that `build.rs` found missing compiled its tests as ignored (`tests/common/needs.rs`).
//! Installing it later does not run `build.rs` again, so those tests would stay ignored with a
//! reason that no longer holds: this test fails then, and says how to run them.

#[path = "common/needs.rs"]
#[allow(dead_code)]
mod needs;

#[test]
fn needs_found_missing_at_build_time_are_still_missing() {
    needs::assert_none_appeared_since(env!("TBASIS_MISSING_NEEDS"), "build.rs");
}
