# Sourced by .ci/fuzz.sh and scripts/fuzz-long: cargo-fuzz, installed when missing, the toolchain
# that builds the fuzz targets in `toolchain`, and `fuzz_cargo ARGS`, cargo with that toolchain.
#
# cargo-fuzz passes nightly-only flags (-Zsanitizer=address): a nightly toolchain, installed with
# rustup when missing. Without one, the stable compiler accepts those flags with RUSTC_BOOTSTRAP=1
# (without rustup, whichever cargo is on PATH). FUZZ_TOOLCHAIN names another.

if ! cargo fuzz --version >/dev/null 2>&1; then
    cargo install cargo-fuzz --locked
fi

toolchain="${FUZZ_TOOLCHAIN:-}"
if [[ -z "$toolchain" ]] && command -v rustup >/dev/null 2>&1; then
    # The list is read whole before it is searched: a pipe into `grep -q` can fail under pipefail.
    installed_toolchains="$(rustup toolchain list 2>/dev/null || true)"
    if ! grep -q '^nightly' <<<"$installed_toolchains"; then
        # A failed install leaves the stable fallback below.
        rustup toolchain install nightly --profile minimal || true
        installed_toolchains="$(rustup toolchain list 2>/dev/null || true)"
    fi
    if grep -q '^nightly' <<<"$installed_toolchains"; then
        toolchain=nightly
    else
        toolchain=stable
    fi
fi
if [[ "$toolchain" != nightly* ]]; then
    export RUSTC_BOOTSTRAP=1
fi

fuzz_cargo() {
    if [[ -n "$toolchain" ]]; then
        cargo "+$toolchain" "$@"
    else
        cargo "$@"
    fi
}
