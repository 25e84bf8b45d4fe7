//! The README's "Memory": on Linux (x86-64 and AArch64) the working memory the library allocates
//! asks for huge pages (`madvise(MADV_HUGEPAGE)` on its 2 MiB-aligned part) when it is 32 MiB or
//! more, and smaller memory does not. Seen through a `ScratchBuffer`, which keeps its memory
//! between calls: the kernel lists the advice as `hg` among a mapping's `VmFlags` in
//! `/proc/self/smaps`. One test in its own file, so that no other test allocates meanwhile.
#![cfg(all(target_os = "linux", any(target_arch = "x86_64", target_arch = "aarch64")))]

use tbasis::{scratch_size_for, Options, Output, ScratchBuffer};
use tbasis_test_support::needs;
use tbasis_test_support::shapes::flat_grid;

const MIB: usize = 1 << 20;

/// The mappings of this process advised for huge pages, as (start, length).
fn advised_mappings() -> Vec<(usize, usize)> {
    let smaps = std::fs::read_to_string("/proc/self/smaps").expect("/proc/self/smaps");
    let mut advised = Vec::new();
    let mut range = None;
    for line in smaps.lines() {
        let first = line.split_whitespace().next().unwrap_or("");
        if let Some((start, end)) = first.split_once('-').filter(|_| !first.ends_with(':')) {
            let parse = |hex| usize::from_str_radix(hex, 16).ok();
            range = parse(start).zip(parse(end));
        } else if let (Some(flags), Some((start, end))) = (line.strip_prefix("VmFlags:"), range) {
            if flags.split_whitespace().any(|flag| flag == "hg") {
                advised.push((start, end - start));
            }
        }
    }
    advised
}

/// The advised mappings of at least `len` bytes that `before` did not list.
fn new_advised(before: &[(usize, usize)], len: usize) -> Vec<(usize, usize)> {
    let after = advised_mappings();
    after
        .into_iter()
        .filter(|m| m.1 >= len && !before.contains(m))
        .collect()
}

#[test]
fn scratch_of_32_mib_or_more_asks_for_huge_pages_and_smaller_does_not() {
    if !needs::TRANSPARENT_HUGE_PAGES.found_or_skip() {
        return;
    }
    let options = Options::mikktspace();
    // Method MIKKTSPACE's scratch is about 125 bytes a corner: about 19 MB, then 49 MB.
    for (quads, large) in [(160, false), (256, true)] {
        let grid = flat_grid("grid", quads, quads, 1.0 / quads as f32);
        let mesh = grid.mesh();
        let needed = scratch_size_for(&mesh, &options).expect("a size");
        assert_eq!(
            needed >= 32 * MIB,
            large,
            "{needed} bytes of scratch for {quads} x {quads} quads"
        );
        let before = advised_mappings();
        let mut scratch = ScratchBuffer::new();
        let mut tangents = vec![[0.0f32; 4]; grid.vertex_count()];
        scratch
            .generate(&mesh, &options, &mut Output::new(tangents.as_mut_slice()))
            .expect("generated");
        assert_eq!(scratch.len(), needed);
        // The advised part starts and ends on 2 MiB boundaries inside the allocation; below
        // 32 MiB no new mapping of any size is advised.
        let advised = new_advised(&before, if large { needed - 4 * MIB } else { 0 });
        if large {
            assert_eq!(advised.len(), 1, "{needed} bytes: advised mappings {advised:x?}");
        } else {
            assert!(advised.is_empty(), "{needed} bytes: advised mappings {advised:x?}");
        }
        drop(scratch);
    }
}
