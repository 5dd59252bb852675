#!/usr/bin/env bash
# The C package, built and used the way a C project would: cargo-c (`cargo cinstall`) builds
# crates/gms-ffi with the release-c profile and installs libleuven_rt.so (SONAME
# libleuven_rt.so.0), libleuven_rt.a, leuven_rt.h and leuven_rt.pc; this script strips the
# static library's debug information, adds the CMake package (lib/cmake/leuven_rt), then builds
# crates/gms-ffi/examples/c against the INSTALLED tree with pkg-config and with CMake and runs it.
#
#   bash scripts/c_package.sh                 # into a temporary prefix, removed afterwards
#   bash scripts/c_package.sh --prefix DIR    # install into DIR and keep it
#
# Needs cargo-c (pinned), a C compiler, pkg-config and cmake: scripts/system.sh installs those
# that are missing.
set -euo pipefail
prefix="" keep=0
case "$#:${1:-}" in
    0:) ;;
    # A relative DIR is the caller's, so it is resolved before the script moves to the root.
    2:--prefix) prefix="$(mkdir -p "$2" && cd "$2" && pwd)" keep=1 ;;
    *) echo "usage: bash scripts/c_package.sh [--prefix DIR]" >&2; exit 2 ;;
esac
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root="$PWD"
work="$(mktemp -d)"
cleanup() { rm -rf "$work"; }
trap cleanup EXIT
[ -n "$prefix" ] || prefix="$work/prefix"

source scripts/system.sh
system_install gcc pkg-config libssl-dev cmake
cargo_c_install

start=$SECONDS
cargo cinstall -p gms-ffi --profile release-c --prefix "$prefix" --libdir lib >"$work/cinstall.log" 2>&1 \
    || { cat "$work/cinstall.log" >&2; exit 1; }
built=$((SECONDS - start))
lib="$prefix/lib"
size() { stat -L -c %s "$1"; }
before="$(size "$lib/libleuven_rt.a")"
strip --strip-debug "$lib/libleuven_rt.a"
after="$(size "$lib/libleuven_rt.a")"

# The CMake package: a relocatable config and the version of the workspace.
version="$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -n 1)"
mkdir -p "$lib/cmake/leuven_rt"
cp crates/gms-ffi/cmake/leuven_rtConfig.cmake "$lib/cmake/leuven_rt/"
sed "s/@VERSION@/$version/" crates/gms-ffi/cmake/leuven_rtConfigVersion.cmake.in \
    >"$lib/cmake/leuven_rt/leuven_rtConfigVersion.cmake"

soname="$(readelf -d "$lib/libleuven_rt.so" | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p')"
[ "$soname" = "libleuven_rt.so.0" ] || { echo "unexpected SONAME '$soname'" >&2; exit 1; }

# A parameter file: the `friction` object of the model file that `leuven-rt identify` writes.
cat >"$work/params.json" <<'JSON'
{
  "Fc": 1.0,
  "Fs": 1.5,
  "Vs": 0.001,
  "delta": 2.0,
  "n": 2.0,
  "sigma1": 30.0,
  "sigma2": 0.4,
  "W": [0.6, 0.5, 0.4, 0.3],
  "Delta": [1e-06, 2e-06, 4e-06, 8e-06]
}
JSON

# pkg-config, the shared library.
export PKG_CONFIG_PATH="$lib/pkgconfig"
example="$root/crates/gms-ffi/examples/c/example.c"
# shellcheck disable=SC2046 # the flags are words
cc -std=c11 -Wall -Wextra -Werror -O2 "$example" $(pkg-config --cflags --libs leuven_rt) \
    -Wl,-rpath,"$lib" -o "$work/example_pkgconfig"
"$work/example_pkgconfig" >/dev/null
"$work/example_pkgconfig" "$work/params.json" >/dev/null

# CMake: find_package(leuven_rt), shared and static targets.
cmake -S crates/gms-ffi/examples/c -B "$work/cmake" -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_BUILD_TYPE=Release >"$work/cmake.log" 2>&1 || { cat "$work/cmake.log" >&2; exit 1; }
cmake --build "$work/cmake" >>"$work/cmake.log" 2>&1 || { cat "$work/cmake.log" >&2; exit 1; }
"$work/cmake/example" "$work/params.json" >/dev/null
out="$("$work/cmake/example_static")"

echo "installed into $prefix$([ "$keep" = 1 ] || echo ' (temporary)'): $(cd "$prefix" && find . -type f -o -type l | sort | tr '\n' ' ')"
echo "cargo cinstall (build and install): $built s"
echo "libleuven_rt.a: $before bytes built, $after after strip --strip-debug; libleuven_rt.so: $(size "$lib/libleuven_rt.so") bytes, SONAME $soname"
echo "example (pkg-config, shared): $(size "$work/example_pkgconfig") bytes; example_static (CMake): $(size "$work/cmake/example_static") bytes"
echo "$out"
