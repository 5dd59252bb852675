#!/usr/bin/env bash
# Fuzzes the C ABI for SECONDS (default 60): the libFuzzer target crates/gms-ffi/fuzz/fuzz_c_abi.c,
# built with clang -fsanitize=fuzzer,address,undefined against the release static library.
# Installs clang (and libFuzzer, in libclang-rt-*-dev) with apt if missing. New inputs go to a
# temporary directory; the seeds in crates/gms-ffi/fuzz/corpus are only read. Prints the number
# of inputs run and the time taken; exits non-zero on a crash or a broken invariant, leaving the
# reproducer in the temporary directory (whose path is printed).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
seconds="${1:-60}"

if ! command -v clang >/dev/null; then
    echo "==> installing clang"
    apt-get update -qq
    apt-get install -y -qq clang >/dev/null
fi
resource_dir="$(clang -print-resource-dir)"
if ! ls "$resource_dir"/lib/linux/libclang_rt.fuzzer-*.a >/dev/null 2>&1; then
    # Debian ships libFuzzer in libclang-rt-<version>-dev (a "Recommends" of clang).
    version="$(clang -dumpversion | cut -d. -f1)"
    echo "==> installing libclang-rt-$version-dev (libFuzzer)"
    apt-get update -qq
    apt-get install -y -qq "libclang-rt-$version-dev" >/dev/null
fi

echo "==> cargo build --release -p gms-ffi"
cargo build --release -p gms-ffi --quiet
target_dir="$(cargo metadata --format-version 1 --no-deps | sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')"

work="$(mktemp -d "${TMPDIR:-/tmp}/leuven-rt-fuzz.XXXXXX")"
echo "==> building the harness in $work"
clang -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -Icrates/gms-ffi/include crates/gms-ffi/fuzz/fuzz_c_abi.c \
    "$target_dir/release/libgms_ffi.a" -lm -lpthread -ldl -o "$work/fuzz_c_abi"

mkdir -p "$work/corpus"
echo "==> fuzzing for $seconds s"
start=$(date +%s)
status=0
(cd "$work" && ASAN_OPTIONS=detect_leaks=1 ./fuzz_c_abi -max_total_time="$seconds" \
    -print_final_stats=1 -timeout=10 -rss_limit_mb=2048 \
    corpus "$OLDPWD/crates/gms-ffi/fuzz/corpus") >"$work/log" 2>&1 || status=$?
elapsed=$(( $(date +%s) - start ))
runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log" | tail -1)"
grep -E "^(==|SUMMARY|invariant broken|artifact_prefix|Test unit written|#[0-9]+ *DONE)" "$work/log" | tail -20 || true
echo "fuzz_c_abi: ${runs:-?} inputs in ${elapsed} s, exit status $status"
if [ "$status" -ne 0 ]; then
    echo "full log: $work/log"
    exit "$status"
fi
rm -rf "$work"
