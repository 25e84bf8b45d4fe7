//! One proptest configuration for every property test file.

use proptest::test_runner::{Config, RngSeed};

/// `cases` cases from the fixed `seed`, so that every run checks the same inputs;
/// `PROPTEST_CASES` and `PROPTEST_RNG_SEED` explore further. No regression files are written.
pub fn fixed(cases: u32, seed: u64) -> Config {
    let default = Config::default();
    let from_env = |name: &str| std::env::var_os(name).is_some();
    Config {
        cases: if from_env("PROPTEST_CASES") {
            default.cases
        } else {
            cases
        },
        rng_seed: if from_env("PROPTEST_RNG_SEED") {
            default.rng_seed
        } else {
            RngSeed::Fixed(seed)
        },
        failure_persistence: None,
        ..default
    }
}
