#!/usr/bin/env bash
# Cold-build time of a new binary crate that depends on the tbasis crate, against one that
# depends on glam alone (docs/build-time.md). Each builds from an empty target directory, with the
# crates already downloaded, so that the time is compiling only.
#
#   bash scripts/build-time.sh [PROFILE_FLAG]    (e.g. --release; default: the dev profile)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
glam_requirement="$(sed -n 's/^glam = "\(.*\)"$/\1/p' "$root/crates/tbasis/Cargo.toml")"

make_crate() { # name, dependency line, main body
  mkdir -p "$work/$1/src"
  printf '[package]\nname = "%s"\nversion = "0.0.0"\nedition = "2021"\n\n[dependencies]\n%s\n' "$1" "$2" > "$work/$1/Cargo.toml"
  printf 'fn main() {\n    %s\n}\n' "$3" > "$work/$1/src/main.rs"
}
make_crate glam-only "glam = \"$glam_requirement\"" 'println!("{}", glam::Vec3::X.cross(glam::Vec3::Y));'
make_crate with-tbasis "tbasis = { path = \"$root/crates/tbasis\" }" \
  'let o = tbasis::Options::default(); println!("{:?}", tbasis::scratch_size_for_counts(&o, 3, 3));'

for crate in glam-only with-tbasis; do
  (cd "$work/$crate" && cargo fetch -q)
done
for crate in glam-only with-tbasis; do
  start=$(date +%s.%N)
  (cd "$work/$crate" && cargo build -q --offline "$@")
  end=$(date +%s.%N)
  awk -v c="$crate" -v s="$start" -v e="$end" 'BEGIN { printf "%s: %.1f s\n", c, e - s }'
done
