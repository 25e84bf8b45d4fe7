//! `threads = N` changes nothing but speed: results and reports are bit-identical for every N.

use tbasis::{DegeneratePolicy, Method, Options};
use tbasis_test_support::cases::{quantized_uv_sphere, Case};
use tbasis_test_support::scenes::{build, Pcg32, SceneSpec};

/// A jittered, warped torus large enough for four workers.
fn torus() -> Case {
    let scene = build(&SceneSpec::torus(140_000));
    Case {
        name: scene.name,
        positions: scene.positions,
        normals: scene.normals,
        texcoords: Some(scene.texcoords),
        indices: Some(scene.indices),
    }
}

/// [`torus`] with its vertices renumbered at random (a seeded shuffle), as FlightHelmet's are out
/// of its triangles' order: each half of the vertices has a corner in about 7 triangles of 8, so
/// two workers solve ranges of triangles apart instead of splitting the vertices.
fn scattered_torus() -> Case {
    let torus = torus();
    let count = torus.vertex_count();
    let mut renumbered: Vec<usize> = (0..count).collect();
    let mut rng = Pcg32::new(0x5CA7, 1);
    for i in (1..count).rev() {
        renumbered.swap(i, ((u64::from(rng.next_u32()) * (i as u64 + 1)) >> 32) as usize);
    }
    fn moved<T: Copy>(values: &[T], renumbered: &[usize]) -> Vec<T> {
        let mut moved = values.to_vec();
        for (v, &value) in values.iter().enumerate() {
            moved[renumbered[v]] = value;
        }
        moved
    }
    Case {
        name: "scattered torus".into(),
        positions: moved(&torus.positions, &renumbered),
        normals: moved(&torus.normals, &renumbered),
        texcoords: torus.texcoords.as_deref().map(|uv| moved(uv, &renumbered)),
        indices: torus
            .indices
            .as_ref()
            .map(|indices| indices.iter().map(|&v| renumbered[v as usize] as u32).collect()),
    }
}

fn bits<const N: usize>(values: &[[f32; N]]) -> Vec<u32> {
    values.iter().flatten().map(|x| x.to_bits()).collect()
}

fn assert_same_for_every_thread_count(case: &Case, options: Options, thread_counts: &[u32]) {
    let one = case.run(&options.with_threads(1));
    for &threads in thread_counts {
        let run = case.run(&options.with_threads(threads));
        let what = format!(
            "{} {:?} {:?} threads={threads}",
            case.name, options.method, options.degenerate_policy
        );
        assert_eq!(run.outcome(), one.outcome(), "{what}: result");
        assert!(bits(&run.tangents) == bits(&one.tangents), "{what}: tangents differ");
        assert!(
            bits(&run.bitangents) == bits(&one.bitangents),
            "{what}: bitangents differ"
        );
    }
}

#[test]
fn every_method_and_policy_is_bit_identical_across_thread_counts() {
    let cases = [torus(), quantized_uv_sphere()];
    let methods = [Method::Lengyel, Method::Angle, Method::Area, Method::Uniform];
    let policies = [
        DegeneratePolicy::Legacy,
        DegeneratePolicy::Skip,
        DegeneratePolicy::Inherit,
        DegeneratePolicy::Reject,
    ];
    for case in &cases {
        assert!(
            case.vertex_count() >= 2 * 32 * 1024,
            "{} is too small to split",
            case.name
        );
        for method in methods {
            for policy in policies {
                if policy == DegeneratePolicy::Legacy && !method.has_legacy_form() {
                    continue;
                }
                let options = Options::default().with_method(method).with_policy(policy);
                assert_same_for_every_thread_count(case, options, &[4]);
            }
        }
        assert_same_for_every_thread_count(case, Options::default(), &[2, 3, 8]);
    }
}

#[test]
fn scattered_vertices_give_the_same_bits_on_every_thread_count() {
    let case = scattered_torus();
    let legacy = Options::default()
        .with_method(Method::Lengyel)
        .with_policy(DegeneratePolicy::Legacy);
    for options in [legacy, Options::default()] {
        assert_same_for_every_thread_count(&case, options, &[2, 3, 8]);
    }
}

#[test]
fn the_quantized_sphere_exercises_degenerate_triangles_on_several_workers() {
    // Without degenerate triangles split across workers, the test above would prove less.
    let case = quantized_uv_sphere();
    let run = case.run(&Options::default().with_threads(4));
    let report = run.outcome().expect("INHERIT accepts the mesh");
    assert!(report.degenerate_triangles > 1000 && report.inherited_vertices + report.fallback_vertices > 0);
}
