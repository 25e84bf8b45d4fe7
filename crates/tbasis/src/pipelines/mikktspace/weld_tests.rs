//! The weld by value ([`super::value_weld`]) and the last-run test ([`super::last_run`]) against
//! the replayed weld ([`super::weld`]), on random meshes built to meet each way they can differ:
//! duplicate vertices, +0 against -0, `NaN`, coordinates near the float range's end, triangles
//! with equal positions, and vertices shared far apart in the triangle order.
#![forbid(unsafe_code)]

use super::attributes::Attributes;
use super::weld::{self, Wanted, WeldScratch};
use super::{last_run, value_weld, NONE};
use crate::kernel::memory::{bytes_of, Arena};
use crate::kernel::mesh::Mesh;
use crate::kernel::test_rng::TestRng;
use crate::kernel::vector::equal;

/// A random mesh whose attributes come from a small palette, so that vertices repeat.
struct Case {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    texcoords: Vec<[f32; 2]>,
    indices: Vec<u32>,
}

impl Case {
    fn mesh(&self) -> Mesh<'_> {
        Mesh::new(&self.positions[..], &self.normals[..])
            .with_texcoords(&self.texcoords[..])
            .with_indices(&self.indices[..])
    }

    /// `check` on the case's attributes as mikktspace.c reads them (V as given).
    fn read<R>(&self, check: impl FnOnce(&Attributes) -> R) -> R {
        let mesh = self.mesh();
        check(&Attributes {
            mesh: &mesh,
            flip_v: false,
            corner_values: None,
            index_zero: None,
        })
    }
}

/// Runs `check` on 3000 random cases drawn from `seed`, each with its attributes as mikktspace.c
/// reads them (V as given).
fn for_each_case(seed: u64, mut check: impl FnMut(usize, &Case, &Attributes)) {
    let mut rng = TestRng(seed);
    for round in 0..3000 {
        let case = case(&mut rng);
        case.read(|attributes| check(round, &case, attributes));
    }
}

fn case(rng: &mut TestRng) -> Case {
    let (vertex_count, triangles) = (3 + rng.below(40), 1 + rng.below(60));
    sized_case(rng, vertex_count, triangles)
}

fn sized_case(rng: &mut TestRng, vertex_count: usize, triangles: usize) -> Case {
    let palette: &[f32] = match rng.below(4) {
        0 => &[0.0, 1.0, 2.0, 0.5],
        1 => &[0.0, -0.0, 1.0, 2.0],
        2 => &[0.0, 1.0, f32::NAN, 3.0],
        _ => &[0.0, 1.0, 2e38, -3e38],
    };
    let pick = |rng: &mut TestRng| palette[rng.below(palette.len())];
    let mut case = Case {
        positions: (0..vertex_count).map(|_| [pick(rng), pick(rng), pick(rng)]).collect(),
        normals: (0..vertex_count)
            .map(|_| [0.0, 0.0, if rng.chance(50) { 1.0 } else { pick(rng) }])
            .collect(),
        texcoords: (0..vertex_count).map(|_| [pick(rng), 0.5]).collect(),
        indices: (0..3 * triangles).map(|_| rng.below(vertex_count) as u32).collect(),
    };
    // Exact copies of other vertices, as exporters write them.
    for v in 0..vertex_count {
        if rng.chance(30) {
            let from = rng.below(vertex_count);
            case.positions[v] = case.positions[from];
            case.normals[v] = case.normals[from];
            case.texcoords[v] = case.texcoords[from];
        }
    }
    case
}

/// The replayed weld: each corner's welded vertex, a vertex of each, and each one's index.
fn replayed(attributes: &Attributes, indices: &[u32]) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let (v, c) = (attributes.mesh.vertex_count(), indices.len());
    let mut memory = vec![0u8; bytes_of(|a| WeldScratch::take(a, v, c).map(|_| ())).unwrap()];
    let scratch = WeldScratch::take(&mut Arena::Carve(&mut memory), v, c).unwrap();
    let (mut welded, mut source, mut values) = (indices.to_vec(), vec![0; c], vec![0; c]);
    let count = weld::weld(attributes, 1, &mut welded, &mut source, &mut values, scratch);
    source.truncate(count);
    values.truncate(count);
    (welded, source, values)
}

/// The weld by value: each corner's welded vertex, each vertex's, and a vertex of each welded
/// vertex; `None` where it declines, after checking it left the corners as they were. Every
/// worker count must give the same: with many, the workers' regions of the table are small and
/// fill up, and the weld starts again on one.
fn by_value_weld(attributes: &Attributes, indices: &[u32]) -> Option<(Vec<u32>, Vec<u32>, Vec<u32>)> {
    let weld_on = |workers: usize| {
        let v = attributes.mesh.vertex_count();
        let (mut welded, mut class, mut source) = (indices.to_vec(), vec![0; v], vec![0; v]);
        let mut table = vec![0; 2 * v + 2];
        let Some(count) = value_weld::weld(attributes, workers, &mut welded, &mut class, &mut source, &mut table)
        else {
            assert_eq!(welded, indices, "a declined weld changed the corners");
            return None;
        };
        source.truncate(count);
        Some((welded, class, source))
    };
    let one = weld_on(1);
    for workers in [2, 7] {
        assert_eq!(weld_on(workers), one, "{workers} workers");
    }
    one
}

#[test]
fn welding_by_value_finds_the_replayed_weld_or_declines() {
    let mut by_value = 0;
    for_each_case(0xC0FFEE, |round, case, attributes| {
        let (welded, source, _) = replayed(attributes, &case.indices);
        let Some((ours_welded, class, ours)) = by_value_weld(attributes, &case.indices) else {
            return;
        };
        let count = ours.len();
        by_value += 1;
        assert_eq!(count, source.len(), "round {round}: welded vertex count");
        assert_eq!(ours_welded, welded, "round {round}: numbering");
        let through_class: Vec<u32> = case.indices.iter().map(|&v| class[v as usize]).collect();
        assert_eq!(through_class, welded, "round {round}: each vertex's welded vertex");
        for (id, (&a, &b)) in ours.iter().zip(&source).enumerate().take(count) {
            let bits = |v: u32| attributes.key(v).map(f32::to_bits);
            assert_eq!(bits(a), bits(b), "round {round}: welded vertex {id}'s attributes");
        }
        assert!(class
            .iter()
            .enumerate()
            .all(|(v, &c)| (c == NONE) != case.indices.contains(&(v as u32))));
    });
    // Not vacuous: most cases without NaN or mixed zeros weld by value.
    assert!(by_value > 1000, "{by_value} of 3000 welded by value");
}

/// What [`last_run::is_trivial`] says about `case` and the truth, from every welded vertex's
/// index, with the run when they differ; `None` when the weld by value declines or no triangle
/// is good.
fn last_run_outcome(case: &Case, attributes: &Attributes) -> Option<(bool, bool, Vec<u32>)> {
    let v = case.positions.len();
    let (welded, _, source) = by_value_weld(attributes, &case.indices)?;
    let count = source.len();
    let position = |id: u32| attributes.position(source[id as usize]);
    let ids: Vec<[u32; 3]> = welded
        .chunks(3)
        .map(|t| [t[0], t[1], t[2]])
        .filter(|&[a, b, c]| {
            !(equal(position(a), position(b)) || equal(position(a), position(c)) || equal(position(b), position(c)))
        })
        .collect();
    if ids.is_empty() {
        return None;
    }
    // The truth, from every welded vertex's index.
    let (_, _, values) = replayed(attributes, &case.indices);
    let edges = ids.iter().flat_map(|&[a, b, c]| [(a, b), (b, c), (c, a)]);
    let key = |(a, b): (u32, u32)| {
        let (x, y) = (values[a as usize], values[b as usize]);
        (x.min(y), x.max(y))
    };
    let last = edges.clone().map(|e| key(e).0).max().unwrap();
    let run: Vec<u32> = edges.filter(|&e| key(e).0 == last).map(|e| key(e).1).collect();
    let truly_trivial = run.len() == 1 || (run.len() == 2 && run[0] == run[1]);

    let (mut lo, mut hi) = (vec![0; count], vec![0; count]);
    let c = case.indices.len();
    let mut memory = vec![0u8; bytes_of(|a| WeldScratch::take(a, v, c).map(|_| ())).unwrap()];
    let weld = WeldScratch::take(&mut Arena::Carve(&mut memory), v, c).unwrap();
    let memory = last_run::Memory {
        lo: &mut lo,
        hi: &mut hi,
        weld,
    };
    let packed: Vec<_> = source.iter().map(|&v| attributes.key(v)).collect();
    let said = last_run::is_trivial(attributes, 1, &welded, (&source, &packed), &ids, memory);
    Some((said, truly_trivial, run))
}

#[test]
fn a_last_run_called_trivial_is_one_edge_or_its_two_sides() {
    let (mut trivial, mut truly) = (0, 0);
    for_each_case(0xBEEF, |round, case, attributes| {
        let Some((said, truly_trivial, run)) = last_run_outcome(case, attributes) else {
            return;
        };
        truly += usize::from(truly_trivial);
        trivial += usize::from(said);
        assert!(
            !said || truly_trivial,
            "round {round}: called trivial, but the last run is {run:?}"
        );
    });
    // Not vacuous: the cells are replayed and the run found whenever it is trivial.
    assert!(
        truly > 300 && trivial == truly,
        "{trivial} called trivial, {truly} truly trivial"
    );
}

/// `run` with the weld counting corners into cells whatever their number.
fn counting_into_cells<R>(run: impl FnOnce() -> R) -> R {
    weld::COUNT_ALWAYS.with(|always| always.set(true));
    let result = run();
    weld::COUNT_ALWAYS.with(|always| always.set(false));
    result
}

#[test]
fn sorting_and_counting_corners_into_cells_weld_alike() {
    let mut sorted = 0;
    for_each_case(0xCE11, |round, case, attributes| {
        sorted += usize::from(case.indices.len() < weld::FEW_CORNERS);
        let weld = replayed(attributes, &case.indices);
        assert_eq!(
            weld,
            counting_into_cells(|| replayed(attributes, &case.indices)),
            "round {round}: the weld"
        );
        assert_eq!(
            last_run_outcome(case, attributes),
            counting_into_cells(|| last_run_outcome(case, attributes)),
            "round {round}: the last run"
        );
    });
    // Not vacuous: most cases are small enough to be sorted.
    assert!(sorted > 1500, "{sorted} of 3000 sorted");
}

/// A grid of `width` by `strips` quads whose even strips are listed first, then the odd ones: with
/// an odd `strips`, the second half of the triangles uses only vertices the first half used, as
/// in FlightHelmet.cc1's primitives, so nearly every vertex has a corner late in the list.
fn interleaved_strips(width: usize, strips: usize, rng: &mut TestRng) -> Case {
    let vertex = |i: usize, j: usize| (j * (width + 1) + i) as u32;
    let mut case = Case {
        positions: Vec::new(),
        normals: Vec::new(),
        texcoords: Vec::new(),
        indices: Vec::new(),
    };
    for j in 0..=strips {
        for i in 0..=width {
            let lift = rng.below(1000) as f32 / 4096.0;
            case.positions.push([i as f32, j as f32, lift]);
            case.normals.push([0.0, 0.0, 1.0]);
            case.texcoords.push([i as f32 / width as f32, j as f32 / strips as f32]);
        }
    }
    for j in (0..strips).step_by(2).chain((1..strips).step_by(2)) {
        for i in 0..width {
            let [a, b, c, d] = [vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)];
            case.indices.extend([a, b, c, a, c, d]);
        }
    }
    case
}

#[test]
fn the_probe_settles_meshes_whose_late_triangles_reuse_early_vertices() {
    let mut rng = TestRng(0x5EED);
    let mut trivial = 0;
    for (width, strips) in [(100, 101), (60, 151), (211, 41), (80, 81)] {
        let case = interleaved_strips(width, strips, &mut rng);
        let (said, truly_trivial, run) = case.read(|attributes| last_run_outcome(&case, attributes)).unwrap();
        assert!(
            !said || truly_trivial,
            "{width}x{strips}: called trivial, but the last run is {run:?}"
        );
        trivial += usize::from(said);
    }
    // Every vertex used late has a `hi` above `L`: without the probe, past the replay's limit.
    assert!(trivial >= 3, "{trivial} of 4 meshes settled by the probe");
}

/// The replay of selected cells ([`weld::representatives`]) finds the same representatives on any
/// number of threads: the box, each welded vertex's cell, the cells selected and the hashes are
/// found on ranges of welded vertices.
#[test]
fn replayed_cells_give_the_same_representatives_on_any_thread_count() {
    let mut rng = TestRng(0xCE11);
    let mut compared = 0;
    for round in 0..300 {
        let (vertex_count, triangles) = (100 + rng.below(400), 200 + rng.below(400));
        let case = sized_case(&mut rng, vertex_count, triangles);
        case.read(|attributes| {
            let Some((welded, _, source)) = by_value_weld(attributes, &case.indices) else {
                return;
            };
            let packed: Vec<_> = source.iter().map(|&v| attributes.key(v)).collect();
            let (v, c) = (case.positions.len(), case.indices.len());
            let size = bytes_of(|a| WeldScratch::take(a, v, c).map(|_| ())).unwrap();
            let every_third = |w: usize| w % 3 == 0;
            let replay = |threads: u32, wanted: &(dyn Fn(usize) -> bool + Sync)| {
                let mut memory = vec![0u8; size];
                let mut scratch = WeldScratch::take(&mut Arena::Carve(&mut memory), v, c).unwrap();
                let wanted = Wanted {
                    welded: wanted,
                    corner_limit: usize::MAX,
                };
                let found =
                    weld::representatives(attributes, threads, (&welded, &source, &packed), wanted, &mut scratch);
                found.map(<[_]>::to_vec)
            };
            for wanted in [&|_| true, &every_third as &(dyn Fn(usize) -> bool + Sync)] {
                let one = replay(1, wanted);
                assert!(one.as_ref().is_some_and(|found| !found.is_empty()), "round {round}");
                for threads in [2, 3] {
                    assert_eq!(replay(threads, wanted), one, "round {round}, {threads} threads");
                }
            }
            compared += 1;
        });
    }
    // Not vacuous: the palette without NaN, huge coordinates or mixed zeros (a quarter of the
    // cases) welds by value.
    assert!(compared > 40, "{compared} of 300 compared");
}
