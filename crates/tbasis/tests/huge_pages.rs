//! The README's "Memory": on Linux (x86-64 and AArch64) the working memory the library allocates
//! for method MIKKTSPACE (a call's without caller scratch, and the callback interface's) and for a
//! `ScratchBuffer` asks for huge pages (`madvise(MADV_HUGEPAGE)` on its 2 MiB-aligned part) when it
//! is 32 MiB or more, and smaller memory does not. The kernel lists the advice as `hg` among a
//! mapping's `VmFlags` in `/proc/self/smaps`: read after a `ScratchBuffer`'s call, which keeps its
//! memory, and, for a call's own memory, by this file's allocator just before that memory is
//! freed. Its own file, so that no other test's allocations come in between.
#![cfg(all(target_os = "linux", any(target_arch = "x86_64", target_arch = "aarch64")))]

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

use tbasis::{generate, scratch_size_for, Options, Output, ScratchBuffer};
use tbasis_test_support::cases::Case;
use tbasis_test_support::face_meshes::{tbasis_calls, FaceMesh, Run};
use tbasis_test_support::needs;
use tbasis_test_support::shapes::flat_grid;

const MIB: usize = 1 << 20;

/// The smallest free the allocator looks at: below the smaller grid's scratch, so that both sides
/// of 32 MiB are seen.
const LOOKED_AT: usize = 8 * MIB;

/// Frees of at least [`LOOKED_AT`] while [`RECORDING`] is on: (bytes, whether the advice was on
/// them; `None` when `/proc/self/smaps` could not be read).
static FREED: Mutex<Vec<(usize, Option<bool>)>> = Mutex::new(Vec::new());
static RECORDING: AtomicBool = AtomicBool::new(false);
/// The tests take turns: each compares the mappings before and after its own allocations.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

thread_local! {
    /// Set while the allocator itself reads `/proc/self/smaps`, whose allocations it passes on.
    static INSIDE: Cell<bool> = const { Cell::new(false) };
}

/// The system's allocator, which looks at each large block's mappings before freeing it.
struct LooksBeforeFreeing;

// SAFETY: every call goes to `System` with the caller's arguments unchanged. Before a large free,
// `dealloc` reads `/proc/self/smaps` and records what it saw: its own allocations go to `System`
// (`INSIDE`), and nothing there can panic (a failed read or a poisoned lock is recorded as unknown
// or dropped), so no unwinding leaves the allocator.
unsafe impl GlobalAlloc for LooksBeforeFreeing {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        System.alloc(layout)
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        System.alloc_zeroed(layout)
    }
    unsafe fn dealloc(&self, pointer: *mut u8, layout: Layout) {
        if layout.size() >= LOOKED_AT && RECORDING.load(Ordering::SeqCst) && !INSIDE.with(Cell::get) {
            INSIDE.with(|inside| inside.set(true));
            let (start, end) = (pointer as usize, pointer as usize + layout.size());
            let advised = read_advised_mappings().map(|mappings| {
                mappings
                    .iter()
                    .any(|&(at, len)| at >= start && at + len <= end && len + 4 * MIB >= layout.size())
            });
            if let Ok(mut freed) = FREED.lock() {
                freed.push((layout.size(), advised));
            }
            INSIDE.with(|inside| inside.set(false));
        }
        System.dealloc(pointer, layout)
    }
    unsafe fn realloc(&self, pointer: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        System.realloc(pointer, layout, new_size)
    }
}

#[global_allocator]
static ALLOCATOR: LooksBeforeFreeing = LooksBeforeFreeing;

/// What `call` freed of [`LOOKED_AT`] bytes or more, and whether each was advised when it was
/// freed.
fn large_frees(call: impl FnOnce()) -> Vec<(usize, Option<bool>)> {
    FREED.lock().unwrap().clear();
    RECORDING.store(true, Ordering::SeqCst);
    call();
    RECORDING.store(false, Ordering::SeqCst);
    std::mem::take(&mut *FREED.lock().unwrap())
}

/// The mappings of this process advised for huge pages.
fn advised_mappings() -> Vec<(usize, usize)> {
    read_advised_mappings().expect("/proc/self/smaps")
}

/// The mappings of this process advised for huge pages, as (start, length); `None` when
/// `/proc/self/smaps` cannot be read.
fn read_advised_mappings() -> Option<Vec<(usize, usize)>> {
    let smaps = std::fs::read_to_string("/proc/self/smaps").ok()?;
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
    Some(advised)
}

/// The advised mappings of at least `len` bytes that `before` did not list.
fn new_advised(before: &[(usize, usize)], len: usize) -> Vec<(usize, usize)> {
    let after = advised_mappings();
    after
        .into_iter()
        .filter(|m| m.1 >= len && !before.contains(m))
        .collect()
}

/// Runs `test`, one test at a time, on two grids whose scratch for method MIKKTSPACE (about 125
/// bytes a corner) is about 19 MB, then 49 MB: each with that size and whether it is 32 MiB or more.
/// Where the kernel has no transparent huge pages, skips ([`needs`]).
fn on_grids_below_and_above_32_mib(mut test: impl FnMut(Case, usize, bool)) {
    if !needs::TRANSPARENT_HUGE_PAGES.found_or_skip() {
        return;
    }
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    for (quads, large) in [(160, false), (256, true)] {
        let grid = flat_grid(&format!("{quads} x {quads} quads"), quads, quads, 1.0 / quads as f32);
        let needed = scratch_size_for(&grid.mesh(), &Options::mikktspace()).expect("a size");
        assert_eq!(needed >= 32 * MIB, large, "{needed} bytes of scratch for {}", grid.name);
        test(grid, needed, large);
    }
}

#[test]
fn scratch_of_32_mib_or_more_asks_for_huge_pages_and_smaller_does_not() {
    let options = Options::mikktspace();
    on_grids_below_and_above_32_mib(|grid, needed, large| {
        let mesh = grid.mesh();
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
    });
}

#[test]
fn mikktspace_calls_without_scratch_ask_for_huge_pages_from_32_mib() {
    let options = Options::mikktspace();
    on_grids_below_and_above_32_mib(|grid, needed, large| {
        let mesh = grid.mesh();
        let mut tangents = vec![[0.0f32; 4]; grid.vertex_count()];
        let freed = large_frees(|| {
            generate(&mesh, &options, &mut Output::new(tangents.as_mut_slice())).expect("generated");
        });
        // The call's working memory is its one allocation of that size, advised on the large grid.
        let working = freed.iter().filter(|f| f.0 == needed).collect::<Vec<_>>();
        assert_eq!(working, [&(needed, Some(large))], "{}: frees {freed:?}", grid.name);

        // The callback interface, on the same triangles: its memory is sized per face vertex.
        let corners = grid.indices.as_deref().expect("indexed");
        let texcoords = grid.texcoords.as_deref().expect("texture coordinates");
        let faces = FaceMesh::from_triangles(
            "grid".into(),
            [&grid.positions, &grid.normals],
            texcoords,
            corners,
            true,
        );
        // Its working memory is its largest allocation, the only one advised on the large grid.
        let freed = large_frees(|| assert!(tbasis_calls(&faces, Run::Default).0));
        let largest = freed.iter().max_by_key(|f| f.0).map(|f| f.1);
        let advised = freed.iter().filter(|f| f.1 == Some(true)).count();
        assert!(
            largest == Some(Some(large)) && advised == usize::from(large),
            "{}, callbacks: frees {freed:?}",
            grid.name
        );
    });
}
