#!/usr/bin/env bash
# The size of libtbasis.so under release-profile options, and what each costs in speed
# (docs/library-size.md, which this script writes). Each variant builds the C library and the demo
# (`tbasis-demo`) into target/library-size/<variant>/ with the options as CARGO_PROFILE_RELEASE_*
# overrides of Cargo.toml's release profile; speed is the best of 10 runs of the demo's two timed
# calls (the default method on two threads, and MikkTSpace per corner with the seam split, on a
# 32k-vertex torus), which link the same code the library holds.
#
#   bash scripts/library-size.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
doc=docs/library-size.md
runs=10

# name | overrides (space-separated VAR=value)
variants=(
  "Cargo.toml's release profile (strip = \"symbols\")|"
  "strip = \"debuginfo\" (cargo's default without debug info; the profile before)|CARGO_PROFILE_RELEASE_STRIP=debuginfo"
  "strip = \"debuginfo\", lto = true|CARGO_PROFILE_RELEASE_STRIP=debuginfo CARGO_PROFILE_RELEASE_LTO=true"
  "strip = \"debuginfo\", codegen-units = 1|CARGO_PROFILE_RELEASE_STRIP=debuginfo CARGO_PROFILE_RELEASE_CODEGEN_UNITS=1"
  "strip = \"symbols\", codegen-units = 1|CARGO_PROFILE_RELEASE_CODEGEN_UNITS=1"
  "strip = \"symbols\", codegen-units = 1, lto = true|CARGO_PROFILE_RELEASE_CODEGEN_UNITS=1 CARGO_PROFILE_RELEASE_LTO=true"
  "strip = \"symbols\", opt-level = \"s\"|CARGO_PROFILE_RELEASE_OPT_LEVEL=s"
)

rows=()
for variant in "${variants[@]}"; do
  name="${variant%%|*}"
  overrides="${variant#*|}"
  label=$(echo "${overrides:-profile}" | sed 's/CARGO_PROFILE_RELEASE_//g' | tr -c 'A-Za-z0-9=\n' '_')
  dir="target/library-size/$label"
  # A cold build: the time goes into the table.
  rm -rf "$dir"
  start=$(date +%s)
  # shellcheck disable=SC2086
  env $overrides CARGO_TARGET_DIR="$dir" cargo build --release -q -p tbasis-ffi -p tbasis-demo
  built=$(($(date +%s) - start))
  bytes=$(stat -c %s "$dir/release/libtbasis.so")
  best_default="" best_mikk=""
  for _ in $(seq $runs); do
    out=$("$dir/release/tbasis-demo" "$dir/torus.ply")
    d=$(echo "$out" | sed -n 's/^default method, 2 threads: \([0-9.]*\) ms$/\1/p')
    m=$(echo "$out" | sed -n 's/^MikkTSpace per corner + seam split: \([0-9.]*\) ms.*/\1/p')
    best_default=$(awk -v a="$best_default" -v b="$d" 'BEGIN { print (a == "" || b < a) ? b : a }')
    best_mikk=$(awk -v a="$best_mikk" -v b="$m" 'BEGIN { print (a == "" || b < a) ? b : a }')
  done
  if [ -z "$best_default" ] || [ -z "$best_mikk" ]; then
    echo "library-size.sh: the demo printed no timing this script knows:" >&2
    echo "$out" >&2
    exit 1
  fi
  grouped=$(echo "$bytes" | sed ':a;s/\B[0-9]\{3\}\>/,&/;ta')
  row=$(printf '| %s | %s | %s | %s | %s s |' "$name" "$grouped" "$best_default" "$best_mikk" "$built")
  echo "$row"
  rows+=("$row")
done

{
  cat <<HEADER
# Size of the shared library

\`libtbasis.so\` as \`cargo build --release\` builds it (x86-64 Linux, $(rustc --version | cut -d' ' -f1-2)),
under the release-profile options that make it smaller, and what each costs in speed. Speed: the
best of $runs runs of the demo's two timed calls (\`cargo run --release -p tbasis-demo\`: the default
method on two threads, and MikkTSpace per corner plus the seam split, on a 32k-vertex torus), built
with the same options. Build: a cold build of the library and the demo, crates downloaded.
\`tests/install.rs\` (\`release_shared_library_is_under_one_megabyte\`) keeps the first row under
1,000,000 bytes.

Reproduce (builds each variant into \`target/library-size/\`; writes this file):

\`\`\`text
bash scripts/library-size.sh
\`\`\`

Measured $(date -u +%Y-%m-%d) on $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores, load average
$(cut -d' ' -f1-3 /proc/loadavg) at the end (other work on the machine scatters the times).

| release profile | libtbasis.so bytes | default, 2 threads (ms) | MikkTSpace + split (ms) | build |
|---|---:|---:|---:|---:|
HEADER
  printf '%s\n' "${rows[@]}"
  cat <<'FOOTER'

Stripping the symbol table (`strip = "symbols"`) removes what only debuggers and profilers read
(the `.symtab` and `.strtab` sections; the first two rows differ by them alone): the dynamic
symbols C programs link against stay, and the code is the same, so it costs no speed, whatever the
timings above show of the load. It brings the library under 1 MB
alone; `cargo build --profile profiling` keeps the symbols (and adds line tables) for profilers.
One codegen unit and LTO save more but lengthen every release build of the crate and its users'
builds of the C library, for differences in speed the noise of these timings hides;
`opt-level = "s"` would trade speed of the kernels for size. The static archive `libtbasis.a` is
not stripped: a program linked to it keeps only what it uses.
FOOTER
} > "$doc"
echo "wrote $doc"
