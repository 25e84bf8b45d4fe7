#!/usr/bin/env bash
# Runs the libFuzzer targets `generate` (fuzz/fuzz_targets/generate.rs, the C ABI) and `gltf_tool`
# (fuzz/fuzz_targets/gltf_tool.rs, the glTF tool's reader and converter) for a bounded time: two
# thirds of it for the first, a third for the second.
#
#   bash .ci/fuzz.sh [SECONDS]    # default 60, in all
#
# Exits non-zero on any crash, sanitizer report, timeout or build failure, and prints libFuzzer's
# final stats line per target. First, each past finding of `generate` (fuzz/regressions/NAME) runs
# alone through the sanitized target, which must pass it and must decode it to its case,
# fuzz/regression_cases/NAME.txt (FUZZ_DESCRIBE=1 prints what it decoded; the inputs are written
# from their cases by `cargo run --manifest-path fuzz/Cargo.toml --example regressions`). The
# corpora grow in fuzz/corpus/TARGET (not tracked); the regressions and the glTF tool's seeds
# (written into fuzz/corpus/gltf_tool_seeds by tools/gltf/examples/fuzz_seeds.rs, when absent) are
# replayed first and then seed the run. The seed is fixed (FUZZ_SEED to change it); a run repeats
# exactly only from the same corpus.
# To read a failure: FUZZ_DEBUG=1 fuzz/target/x86_64-unknown-linux-gnu/release/TARGET INPUT
set -euo pipefail

seconds="${1:-60}"
seed="${FUZZ_SEED:-20240601}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root/fuzz"

# shellcheck source=fuzz-toolchain.sh
source "$root/.ci/fuzz-toolchain.sh"
echo "fuzz: toolchain ${toolchain:-default} ($(fuzz_cargo --version)), ${seconds}s, seed $seed"

log="$(mktemp)"
trap 'rm -f "$log" "$log.diff"' EXIT

# fuzz TARGET SECONDS KNOWN [LIBFUZZER OPTIONS...]: replays the inputs in the folder KNOWN (each
# must pass), then fuzzes from corpus/TARGET and KNOWN for SECONDS.
fuzz() {
    local target="$1" seconds="$2" known="$3"
    shift 3
    mkdir -p "corpus/$target"
    shopt -s nullglob
    local inputs=("$known"/*)
    if ((${#inputs[@]} > 0)); then
        fuzz_cargo fuzz run "$target" "${inputs[@]}" -- -runs=1 "$@" >"$log" 2>&1 || {
            cat "$log"
            echo "fuzz: $target: an input of $known fails" >&2
            exit 1
        }
    fi
    local status=0
    fuzz_cargo fuzz run "$target" "corpus/$target" "$known" -- \
        -max_total_time="$seconds" -seed="$seed" -rss_limit_mb=2048 -timeout=10 \
        -print_final_stats=1 "$@" >"$log" 2>&1 || status=$?
    if ((status != 0)); then
        # The crash report, the input's path and how to reproduce it.
        tail -n 80 "$log"
        echo "fuzz: $target FAILED (exit $status)" >&2
        exit "$status"
    fi
    grep -E '^#[0-9]+[[:space:]]+DONE' "$log" | tail -n 1 || true
    grep -E '^Done [0-9]+ runs' "$log" | tail -n 1 || true
    echo "fuzz: $target: no crash in ${seconds}s"
}

# The past findings of the C ABI: each input alone, through the sanitized target, which must pass it
# and decode it to its case.
replay_regressions() {
    fuzz_cargo fuzz build generate >"$log" 2>&1 || {
        cat "$log"
        echo "fuzz: generate does not build" >&2
        exit 1
    }
    # The writer of the inputs shares the target's modules: it must keep building with them.
    fuzz_cargo check --quiet --example regressions >"$log" 2>&1 || {
        cat "$log"
        echo "fuzz: the regressions writer (examples/regressions.rs) does not build" >&2
        exit 1
    }
    local binary="target/x86_64-unknown-linux-gnu/release/generate" failed=0 count=0 input name
    shopt -s nullglob
    for input in regressions/*; do
        name="$(basename "$input")"
        [[ -f "regression_cases/$name.txt" ]] || {
            echo "fuzz: regressions/$name has no case in regression_cases/" >&2
            failed=1
        }
    done
    for case in regression_cases/*.txt; do
        name="$(basename "$case" .txt)"
        input="regressions/$name"
        count=$((count + 1))
        if [[ ! -f "$input" ]]; then
            echo "fuzz: $case has no input $input" >&2
            failed=1
            continue
        fi
        if ! FUZZ_DESCRIBE=1 "$binary" "$input" >"$log" 2>&1; then
            tail -n 60 "$log"
            echo "fuzz: generate fails on $input" >&2
            failed=1
            continue
        fi
        # libFuzzer may run an input twice (the second time to look for a leak): the first run's.
        if ! diff <(awk '/^generate counts/ { n++ } n == 1 && /^(generate|listing|corners) /' "$log") \
            <(grep -vE '^(#|hint )' "$case") >"$log.diff"; then
            head -n 20 "$log.diff"
            echo "fuzz: $input no longer decodes to $case (rewrite it: cargo run --manifest-path fuzz/Cargo.toml --example regressions)" >&2
            failed=1
        fi
    done
    rm -f "$log.diff"
    ((failed == 0)) || exit 1
    echo "fuzz: generate: $count regressions pass and decode to their cases"
}
replay_regressions

# Past findings of the C ABI (fuzz/regressions), and the glTF tool's seeds.
fuzz generate "$((seconds - seconds / 3))" regressions
if [ ! -e corpus/gltf_tool_seeds/quad.glb ]; then
    (cd "$root" && cargo run --quiet -p tbasis-gltf --example fuzz_seeds -- fuzz/corpus/gltf_tool_seeds)
fi
fuzz gltf_tool "$((seconds / 3))" corpus/gltf_tool_seeds -dict=gltf_tool.dict
