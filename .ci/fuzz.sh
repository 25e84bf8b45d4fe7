#!/usr/bin/env bash
# Runs the libFuzzer target `generate` (fuzz/fuzz_targets/generate.rs) for a bounded time.
#
#   bash .ci/fuzz.sh [SECONDS]    # default 60
#
# Exits non-zero on any crash, sanitizer report, timeout or build failure, and prints libFuzzer's
# final stats line. The corpus grows in fuzz/corpus/generate (not tracked); the inputs in
# fuzz/regressions are replayed first and then seed the run. The seed is fixed (FUZZ_SEED to
# change it); a run repeats exactly only from the same corpus.
# To read a failure: FUZZ_DEBUG=1 fuzz/target/x86_64-unknown-linux-gnu/release/generate INPUT
set -euo pipefail

seconds="${1:-60}"
seed="${FUZZ_SEED:-20240601}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root/fuzz"

if ! cargo fuzz --version >/dev/null 2>&1; then
    cargo install cargo-fuzz --locked
fi

# cargo-fuzz passes nightly-only flags (-Zsanitizer=address). Use a nightly toolchain when one is
# installed; otherwise let the stable compiler accept those flags with RUSTC_BOOTSTRAP=1.
toolchain="${FUZZ_TOOLCHAIN:-}"
if [[ -z "$toolchain" ]]; then
    if rustup toolchain list 2>/dev/null | grep -q '^nightly'; then
        toolchain=nightly
    else
        toolchain=stable
    fi
fi
if [[ "$toolchain" != nightly* ]]; then
    export RUSTC_BOOTSTRAP=1
fi
echo "fuzz: toolchain $toolchain ($(cargo "+$toolchain" --version)), ${seconds}s, seed $seed"

mkdir -p corpus/generate
log="$(mktemp)"
trap 'rm -f "$log"' EXIT

# Known crashers and past findings first: each must pass.
shopt -s nullglob
regressions=(regressions/*)
if ((${#regressions[@]} > 0)); then
    cargo "+$toolchain" fuzz run generate "${regressions[@]}" -- -runs=1 >"$log" 2>&1 || {
        cat "$log"
        echo "fuzz: a regression input fails" >&2
        exit 1
    }
fi

status=0
cargo "+$toolchain" fuzz run generate corpus/generate regressions -- \
    -max_total_time="$seconds" -seed="$seed" -rss_limit_mb=2048 -timeout=10 \
    -print_final_stats=1 >"$log" 2>&1 || status=$?

if ((status != 0)); then
    # The crash report, the input's path and how to reproduce it.
    tail -n 80 "$log"
    echo "fuzz: FAILED (exit $status)" >&2
    exit "$status"
fi
grep -E '^#[0-9]+[[:space:]]+DONE' "$log" | tail -n 1 || true
grep -E '^Done [0-9]+ runs' "$log" | tail -n 1 || true
echo "fuzz: no crash in ${seconds}s"
