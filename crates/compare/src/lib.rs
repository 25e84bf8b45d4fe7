//! Measurements of tbasis against its peers: see the examples `bench`, `chart` and
//! `corpus_table` (`cargo run --release -p tbasis-compare --example bench`).
//!
//! The library part holds what the examples compute from their measurements and what is worth a
//! test of its own: [`pareto`].

pub mod pareto;
