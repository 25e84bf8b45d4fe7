//! Measurements of tbasis against its peers: see the examples `bench`, `chart` and
//! `corpus_table` (`cargo run --release -p tbasis-compare --example bench`).
