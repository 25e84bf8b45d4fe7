# Sourced by .ci/fuzz.sh and scripts/fuzz-long: cargo-fuzz, installed when missing, and in
# `toolchain` the toolchain that builds the fuzz targets.
#
# cargo-fuzz passes nightly-only flags (-Zsanitizer=address): a nightly toolchain, installed with
# rustup when missing. Without rustup, the stable compiler accepts those flags with
# RUSTC_BOOTSTRAP=1. FUZZ_TOOLCHAIN names another.

if ! cargo fuzz --version >/dev/null 2>&1; then
    cargo install cargo-fuzz --locked
fi

toolchain="${FUZZ_TOOLCHAIN:-}"
if [[ -z "$toolchain" ]]; then
    if ! rustup toolchain list 2>/dev/null | grep -q '^nightly' && command -v rustup >/dev/null 2>&1; then
        # A failed install leaves the stable fallback below.
        rustup toolchain install nightly --profile minimal || true
    fi
    if rustup toolchain list 2>/dev/null | grep -q '^nightly'; then
        toolchain=nightly
    else
        toolchain=stable
    fi
fi
if [[ "$toolchain" != nightly* ]]; then
    export RUSTC_BOOTSTRAP=1
fi
