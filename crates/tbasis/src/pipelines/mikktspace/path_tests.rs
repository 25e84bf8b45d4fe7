//! Which way each corpus mesh's weld and groups take ([`super::Routes`]), so that a fast path no
//! mesh uses shows up.
#![forbid(unsafe_code)]

use super::{components, compute, fans, scratch_bytes, GroupRoute, Routes, WeldPath};
use crate::kernel::mesh::Mesh;
use crate::kernel::options::Options;
use crate::kernel::report::Report;
use crate::kernel::simd::tests::{along, supported_paths};
use crate::kernel::simd::Path;
use crate::kernel::test_rng::TestRng;
use crate::StridedMut;
use tbasis_test_support::mikktspace_reference::reference_corners;
use tbasis_test_support::{load, needs, scenes};

/// The routes `compute` took on one mesh.
fn routes_of(
    positions: &[[f32; 3]],
    normals: &[[f32; 3]],
    texcoords: &[[f32; 2]],
    indices: &[u32],
    flip_v: bool,
) -> Routes {
    let mesh = Mesh::new(positions, normals)
        .with_texcoords(texcoords)
        .with_indices(indices);
    let options = Options::mikktspace().with_flip_v(flip_v);
    let mut bytes = vec![0u8; scratch_bytes(positions.len(), indices.len()).expect("a scratch size")];
    let (_, routes, _) = compute(&mesh, &options, &mut bytes, None, &mut Report::default()).expect("a result");
    routes
}

#[test]
fn the_benchmark_torus_welds_by_value_and_groups_fan_by_fan() {
    let torus = scenes::build(&scenes::SceneSpec::torus(20_000));
    let routes = routes_of(
        &torus.positions,
        &torus.normals,
        &torus.texcoords,
        &torus.indices,
        false,
    );
    assert_eq!(routes.weld, WeldPath::ByValue);
    let GroupRoute::Fans(settled) = routes.groups else {
        panic!("the torus's groups by {:?}", routes.groups);
    };
    assert!(
        settled.components > 0 && settled.compared == 0 && settled.searched == 0,
        "{settled:?}"
    );
}

/// The fans project their corners' directions in SIMD lanes ([`super::fans`]): every path this
/// CPU supports gives the baseline's bits on the torus, which takes the fan route, on one thread
/// and two; and written in place into a per-corner output (two threads spill corners to each
/// other's parts of it), the same frames as in the scratch's arrays, which stay untouched.
#[test]
fn the_fans_give_the_same_bits_on_every_simd_path() {
    let torus = scenes::build(&scenes::SceneSpec::torus(20_000));
    let mesh = Mesh::new(&torus.positions[..], &torus.normals[..])
        .with_texcoords(&torus.texcoords[..])
        .with_indices(&torus.indices[..]);
    let paths = supported_paths();
    for threads in [1, 2] {
        let options = Options::mikktspace().with_threads(threads);
        let mut bytes = vec![0u8; scratch_bytes(mesh.vertex_count(), mesh.corner_count()).expect("a size")];
        let mut fill = 0u8;
        let mut on_path = |path: Path| {
            // Each run starts from other bytes: a corner some run leaves unwritten differs.
            fill = fill.wrapping_add(0x55);
            bytes.fill(fill);
            let (buffers, routes, _) = along(path, || {
                compute(&mesh, &options, &mut bytes, None, &mut Report::default())
            })
            .expect("a result");
            assert!(matches!(routes.groups, GroupRoute::Fans(_)), "{:?}", routes.groups);
            let bits: Vec<u32> = buffers.tangents.iter().flatten().map(|x| x.to_bits()).collect();
            (bits, buffers.orientation.to_vec())
        };
        let baseline = on_path(Path::Baseline);
        for &path in &paths[1..] {
            assert!(
                on_path(path) == baseline,
                "{path:?} differs from the baseline on {threads} threads"
            );
        }
        let (tangents, orientation) = &baseline;
        let frames: Vec<[u32; 4]> = tangents
            .chunks(3)
            .zip(orientation)
            .map(|(t, &o)| [t[0], t[1], t[2], if o != 0 { 1.0f32 } else { -1.0 }.to_bits()])
            .collect();
        let mut written = vec![[0.0f32; 4]; mesh.corner_count()];
        for &path in &paths {
            fill = fill.wrapping_add(0x55);
            bytes.fill(fill);
            written.fill([f32::from_bits(u32::from_ne_bytes([fill; 4])); 4]);
            let mut output = StridedMut::from_slice(&mut written);
            let (buffers, _, in_place) = along(path, || {
                compute(&mesh, &options, &mut bytes, Some(&mut output), &mut Report::default())
            })
            .expect("a result");
            assert!(in_place, "the fan route wrote the scratch");
            // The scratch's per-corner results stay as the caller left them (README, "Memory").
            let untouched = u32::from_ne_bytes([fill; 4]);
            let results_untouched = buffers.tangents.iter().flatten().all(|x| x.to_bits() == untouched)
                && buffers.orientation.iter().all(|&o| o == fill);
            assert!(
                results_untouched,
                "{path:?} on {threads} threads wrote the scratch's results"
            );
            let bits: Vec<[u32; 4]> = written.iter().map(|f| f.map(f32::to_bits)).collect();
            assert!(bits == frames, "{path:?} in place differs on {threads} threads");
        }
    }
}

/// Where the weld by value holds but the last run can matter, two threads run the last-run check
/// beside the derivatives and the replay after it: random meshes whose positions repeat, so that
/// triangles share vertices, give mikktspace.c's bits on one thread and two, and on one thread
/// with every fan's edges sorted as large fans' are ([`fans::SORT_ALWAYS`]): both ways pair the
/// last run's edges as mikktspace.c's walk did. Most have 16 to 80 triangles (under `cfg(test)`
/// two workers split 16); every fourth has up to 2016, past the check's own replay of a few
/// cells, so that only the full replay gives every index.
#[test]
fn a_replayed_last_run_gives_mikktspace_cs_bits_on_two_threads() {
    let mut rng = TestRng(0x5EED_1A57);
    let mut replayed = 0;
    for round in 0..400 {
        let large = round % 4 == 0;
        let vertex_count = 8 + rng.below(if large { 600 } else { 24 });
        let at = |rng: &mut TestRng| rng.below(6) as f32 * 0.5;
        let positions: Vec<[f32; 3]> = (0..vertex_count)
            .map(|_| [at(&mut rng), at(&mut rng), at(&mut rng)])
            .collect();
        let normals = vec![[0.0, 0.0, 1.0]; vertex_count];
        let texcoords: Vec<[f32; 2]> = (0..vertex_count).map(|_| [at(&mut rng), at(&mut rng)]).collect();
        let triangles = 16 + rng.below(if large { 2000 } else { 64 });
        let indices: Vec<u32> = (0..3 * triangles).map(|_| rng.below(vertex_count) as u32).collect();
        let routes = routes_of(&positions, &normals, &texcoords, &indices, false);
        if routes.weld != WeldPath::ReplayedForLastRun {
            continue;
        }
        replayed += 1;
        let expected =
            reference_corners(&positions, &normals, &texcoords, Some(&indices), false).expect("mikktspace.c");
        let mesh = Mesh::new(&positions[..], &normals[..])
            .with_texcoords(&texcoords[..])
            .with_indices(&indices[..]);
        for (threads, sorted) in [(1, false), (2, false), (1, true)] {
            let mut corners = vec![[0.0f32; 4]; indices.len()];
            let options = Options::mikktspace().with_threads(threads);
            fans::SORT_ALWAYS.with(|always| always.set(sorted));
            let generated = crate::generate_corners(&mesh, &options, &mut StridedMut::from_slice(&mut corners));
            fans::SORT_ALWAYS.with(|always| always.set(false));
            generated.expect("a result");
            let bits = |frames: &[[f32; 4]]| frames.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
            let way = if sorted { ", fans sorted" } else { "" };
            assert!(
                bits(&corners) == bits(&expected),
                "round {round}, {threads} threads{way}"
            );
        }
    }
    // Not vacuous: many meshes replay.
    assert!(replayed > 50, "{replayed} of 400 replayed the last run");
}

#[test]
fn every_corpus_mesh_reports_the_routes_it_takes() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    let dir = load::corpus_dir().expect("the corpus");
    // Corners per way: by value, replayed for the attributes, replayed for the last run. Corners
    // per group route: fan by fan, over the mesh. Groups: as components (either route), of which
    // compared pairwise, and by the search.
    let mut corners = [0usize; 3];
    let mut routed = [0usize; 2];
    let mut groups = [components::Settled::default(); 2];
    let mut lines = Vec::new();
    for row in load::read_manifest(&dir).expect("MANIFEST.tsv") {
        // Debug builds leave out the largest meshes, as the corpus tests do.
        if cfg!(debug_assertions) && row.vertices > 200_000 {
            continue;
        }
        let file = load::load(&dir, &row).expect("a corpus file");
        for (p, primitive) in file.primitives.iter().enumerate() {
            let Some(texcoords) = &primitive.texcoords else {
                continue;
            };
            let (positions, normals, indices) = (&primitive.positions, &primitive.normals, &primitive.indices);
            let routes = routes_of(positions, normals, texcoords, indices, primitive.v_down);
            let way = match routes.weld {
                WeldPath::ByValue => 0,
                WeldPath::ReplayedForAttributes => 1,
                WeldPath::ReplayedForLastRun => 2,
            };
            corners[way] += indices.len();
            let (route, settled) = match routes.groups {
                GroupRoute::Fans(settled) => (0, settled),
                GroupRoute::Components(settled) => (1, settled),
                GroupRoute::Search => panic!("{} #{p}: triangles grouped by the search alone", row.path),
            };
            routed[route] += indices.len();
            groups[route] += settled;
            lines.push(format!(
                "{} #{p}: {} corners, {:?}, {}: {} groups as components ({} compared), {} by search",
                row.path,
                indices.len(),
                routes.weld,
                ["fan by fan", "over the mesh"][route],
                settled.components,
                settled.compared,
                settled.searched
            ));
        }
    }
    eprintln!("{}", lines.join("\n"));
    let [by_value, for_attributes, for_last_run] = corners;
    eprintln!(
        "corners welded by value: {by_value}; replayed for their attributes: {for_attributes}; \
         replayed for the last run: {for_last_run}"
    );
    let [by_fans, over_the_mesh] = routed;
    for (route, (corners, settled)) in ["fan by fan", "over the mesh"].iter().zip(routed.iter().zip(&groups)) {
        eprintln!(
            "{route}: {corners} corners, {} groups as components, of which compared pairwise: {}; by \
             search: {}; fans of more than {} corners: {}",
            settled.components,
            settled.compared,
            settled.searched,
            super::fans::SCAN_LIMIT,
            settled.large_fans
        );
    }
    // Each way is taken somewhere: none goes untested by the corpus.
    assert!(by_value > 0, "no corpus mesh welds by value");
    assert!(
        for_attributes > 0,
        "no corpus mesh has attributes the weld by value declines"
    );
    assert!(for_last_run > 0, "no corpus mesh needs the last run replayed");
    let [fans, mesh] = groups;
    assert!(
        by_fans > 0 && fans.components > 0,
        "no corpus mesh is grouped fan by fan"
    );
    assert!(fans.compared > 0, "no fan's group needs the pairwise comparison");
    assert!(fans.large_fans > 0, "no corpus fan is too large for the stack");
    assert!(
        over_the_mesh > 0 && mesh.components > 0,
        "no corpus mesh is grouped over the mesh"
    );
    assert!(
        mesh.compared > 0,
        "no component over the mesh needs the pairwise comparison"
    );
    assert!(mesh.searched > 0, "no corpus mesh needs the search for its groups");
}
