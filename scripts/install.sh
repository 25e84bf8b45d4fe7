#!/usr/bin/env bash
# Builds tbasis's two C libraries and installs them (Linux): libtbasis, and the drop-in for
# mikktspace.c, libtbasis_mikktspace.
#
#   scripts/install.sh PREFIX [--profile release|debug]
#
# PREFIX/lib/libtbasis.so.X.Y.Z     the shared library (soname libtbasis.so.MAJOR, or
#                                   libtbasis.so.0.MINOR while MAJOR is 0, set by build.rs through
#                                   packaging/soname.rs)
# PREFIX/lib/<soname>, libtbasis.so symlinks to it
# PREFIX/lib/libtbasis.a            the static archive
# PREFIX/include/tbasis.h           the committed header
# PREFIX/lib/pkgconfig/tbasis.pc    pkg-config: `pkg-config --cflags --libs [--static] tbasis`
# PREFIX/lib/libtbasis_mikktspace.so.X.Y.Z, its <soname> and libtbasis_mikktspace.so links,
# PREFIX/lib/libtbasis_mikktspace.a, PREFIX/include/tbasis_mikktspace.h and
# PREFIX/lib/pkgconfig/tbasis_mikktspace.pc
#                                   the same for the drop-in (crates/mikktspace-c)
# PREFIX/lib/cmake/tbasis/          CMake: find_package(tbasis) gives tbasis::tbasis (shared) and
#                                   tbasis::tbasis_static, tbasis::mikktspace (shared) and
#                                   tbasis::mikktspace_static
#
# The profile defaults to release. Cargo runs as `cargo build --lib` ($CARGO if set, else cargo)
# in the usual target directory (CARGO_TARGET_DIR is honoured). DESTDIR, when set, is prepended
# to every installed path for staged installs; the files still describe PREFIX.
set -euo pipefail

usage() {
  echo "usage: $0 PREFIX [--profile release|debug]" >&2
  exit 2
}

prefix=""
profile=release
while [ "$#" -gt 0 ]; do
  case "$1" in
    --profile)
      [ "$#" -ge 2 ] || usage
      profile=$2
      shift 2
      ;;
    --profile=*)
      profile=${1#--profile=}
      shift
      ;;
    -h | --help)
      echo "usage: $0 PREFIX [--profile release|debug]"
      exit 0
      ;;
    -*) usage ;;
    *)
      [ -z "$prefix" ] || usage
      prefix=$1
      shift
      ;;
  esac
done
[ -n "$prefix" ] || usage
case "$profile" in
  release) cargo_profile=(--release) ;;
  debug) cargo_profile=() ;;
  *) usage ;;
esac
if [ "$(uname -s)" != Linux ]; then
  echo "$0: only Linux layouts (.so with a soname) are supported" >&2
  exit 1
fi
# The .pc file records the prefix, so it must not depend on the current directory.
case "$prefix" in
  /*) ;;
  *) prefix="$PWD/$prefix" ;;
esac

root=$(cd "$(dirname "$0")/.." && pwd)
cargo=${CARGO:-cargo}
manifest="$root/Cargo.toml"
dropin_manifest="$root/crates/mikktspace-c/Cargo.toml"

# What a Rust static library needs from the system on Linux; printed by
# `cargo rustc --lib --crate-type staticlib -- --print native-static-libs`.
native_static_libs="-lgcc_s -lutil -lrt -lpthread -lm -ldl -lc"

# Version from a manifest: `cargo pkgid` ends in `#VERSION` or `#NAME@VERSION`.
version_of() {
  local pkgid version
  pkgid=$("$cargo" pkgid --quiet --manifest-path "$1")
  version=${pkgid##*#}
  echo "${version##*@}"
}
version=$(version_of "$manifest")
if [ "$(version_of "$dropin_manifest")" != "$version" ]; then
  echo "$0: crates/mikktspace-c has another version than $version; the libraries carry one" >&2
  exit 1
fi
core=${version%%[-+]*}
IFS=. read -r major minor patch <<<"$core"
if ! [[ "$major" =~ ^[0-9]+$ && "$minor" =~ ^[0-9]+$ && "$patch" =~ ^[0-9]+$ ]]; then
  echo "$0: cannot read the version from cargo pkgid: $version" >&2
  exit 1
fi
# The soname packaging/soname.rs gives lib$1.so.
soname_of() {
  if [ "$major" = 0 ]; then
    echo "lib$1.so.0.$minor"
  else
    echo "lib$1.so.$major"
  fi
}
soname=$(soname_of tbasis)
real_name="libtbasis.so.$core"
dropin_soname=$(soname_of tbasis_mikktspace)
dropin_real_name="libtbasis_mikktspace.so.$core"
# The package description of a manifest.
description_of() {
  awk -F'"' '/^\[/ { in_package = ($0 == "[package]") }
    in_package && /^description *=/ { print $2; exit }' "$1"
}

"$cargo" build --lib --manifest-path "$manifest" -p tbasis-ffi -p tbasis-mikktspace "${cargo_profile[@]}"
target_dir=$("$cargo" metadata --no-deps --format-version 1 --manifest-path "$manifest" |
  sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
built="$target_dir/$profile"
dest="${DESTDIR:-}$prefix"
install -d "$dest/lib/pkgconfig" "$dest/lib/cmake/tbasis" "$dest/include"

# Installs lib$1: the shared library under its full version with the soname and development
# links, the archive and the header $2.
install_library() {
  local name=$1 header=$2 lib_soname lib_real_name embedded file
  lib_soname=$(soname_of "$name")
  lib_real_name="lib$name.so.$core"
  for file in "lib$name.so" "lib$name.a"; do
    if [ ! -f "$built/$file" ]; then
      echo "$0: cargo did not produce $built/$file" >&2
      exit 1
    fi
  done
  # The symlinks below must carry the name executables will look for.
  if command -v readelf >/dev/null 2>&1; then
    embedded=$(readelf -d "$built/lib$name.so" | sed -n 's/.*(SONAME).*\[\(.*\)\].*/\1/p')
    if [ "$embedded" != "$lib_soname" ]; then
      echo "$0: $built/lib$name.so has soname '$embedded', expected '$lib_soname'" >&2
      exit 1
    fi
  fi
  install -m 755 "$built/lib$name.so" "$dest/lib/$lib_real_name"
  ln -sfn "$lib_real_name" "$dest/lib/$lib_soname"
  ln -sfn "$lib_soname" "$dest/lib/lib$name.so"
  install -m 644 "$built/lib$name.a" "$dest/lib/lib$name.a"
  install -m 644 "$root/include/$header" "$dest/include/$header"
}
install_library tbasis tbasis.h
install_library tbasis_mikktspace tbasis_mikktspace.h

# Byte 4 of an ELF header: 1 for a 32-bit object, 2 for a 64-bit one.
sizeof_void_p=$(($(od -An -tu1 -j4 -N1 "$built/libtbasis.so") * 4))
native_static_libs_cmake=$(echo "$native_static_libs" | sed 's/^-l//; s/ -l/;/g')

# Replaces every @KEY@ of template $1 with its value (KEY=VALUE arguments) into file $2.
render() {
  local text key value
  text=$(<"$1")
  shift
  local out=$1
  shift
  for pair in "$@"; do
    key=${pair%%=*}
    value=${pair#*=}
    text=${text//"@$key@"/"$value"}
  done
  if [[ "$text" =~ @[A-Z_]+@ ]]; then
    echo "$0: $out: no value for ${BASH_REMATCH[0]}" >&2
    exit 1
  fi
  printf '%s\n' "$text" >"$out"
  chmod 644 "$out"
}

# One .pc file per library: its name, and the manifest its description comes from.
for pair in "tbasis:$manifest" "tbasis_mikktspace:$dropin_manifest"; do
  render "$root/packaging/${pair%%:*}.pc.in" "$dest/lib/pkgconfig/${pair%%:*}.pc" \
    "PREFIX=$prefix" "VERSION=$version" "DESCRIPTION=$(description_of "${pair#*:}")" \
    "NATIVE_STATIC_LIBS=$native_static_libs"
done
render "$root/packaging/tbasisConfig.cmake.in" "$dest/lib/cmake/tbasis/tbasisConfig.cmake" \
  "VERSION=$core" "REAL_NAME=$real_name" "SONAME=$soname" \
  "MIKKTSPACE_REAL_NAME=$dropin_real_name" "MIKKTSPACE_SONAME=$dropin_soname" \
  "NATIVE_STATIC_LIBS_CMAKE=$native_static_libs_cmake"
render "$root/packaging/tbasisConfigVersion.cmake.in" \
  "$dest/lib/cmake/tbasis/tbasisConfigVersion.cmake" \
  "VERSION=$core" "VERSION_MAJOR=$major" "VERSION_MINOR=$minor" \
  "SIZEOF_VOID_P=$sizeof_void_p"

echo "installed tbasis $version ($profile, soname $soname) into $dest"
echo "installed tbasis_mikktspace $version ($profile, soname $dropin_soname) into $dest"
# The loader finds a new library in a system prefix only once its cache is rebuilt.
if [ -z "${DESTDIR:-}" ]; then
  echo "programs load $soname and $dropin_soname by soname: in a prefix the loader searches" \
    "(/usr/local/lib on Debian), run ldconfig as root; elsewhere link with -Wl,-rpath,$prefix/lib" \
    "or set LD_LIBRARY_PATH"
fi
