#!/usr/bin/env bash
# Fuzzes the C ABI for SECONDS (default 60): the libFuzzer target crates/gms-ffi/fuzz/fuzz_c_abi.c,
# built with clang -fsanitize=fuzzer,address,undefined against a static library of the C ABI:
# LIBRARY if given (scripts/test.sh passes the libleuven_rt.a that scripts/c_package.sh
# installed, so that the library users get is fuzzed and not built twice), otherwise
# libgms_ffi.a of `cargo build --release -p gms-ffi`.
#
#   bash scripts/fuzz_c.sh [SECONDS [LIBRARY]]
#
# Installs clang and libFuzzer (libclang-rt-dev) if missing, with scripts/system.sh. New inputs go to a
# temporary directory; the seeds in crates/gms-ffi/fuzz/corpus are only read. Prints the number
# of inputs run and the time taken; exits non-zero on a crash or a broken invariant, leaving the
# reproducer in the temporary directory (whose path is printed).
set -euo pipefail
seconds="${1:-60}" library="${2:-}"
if [ -n "$library" ]; then
    # A relative LIBRARY is the caller's, so it is resolved before the script moves to the root.
    [ -f "$library" ] || { echo "fuzz_c.sh: no static library at $library" >&2; exit 2; }
    library="$(cd "$(dirname "$library")" && pwd)/$(basename "$library")"
fi
cd "$(dirname "${BASH_SOURCE[0]}")/.."

source scripts/system.sh
system_install clang libclang-rt-dev

if [ -z "$library" ]; then
    echo "==> cargo build --release -p gms-ffi"
    cargo build --release -p gms-ffi --quiet
    target_dir="$(cargo metadata --format-version 1 --no-deps | sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')"
    library="$target_dir/release/libgms_ffi.a"
fi

work="$(mktemp -d "${TMPDIR:-/tmp}/leuven-rt-fuzz.XXXXXX")"
echo "==> building the harness in $work"
clang -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -Icrates/gms-ffi/include crates/gms-ffi/fuzz/fuzz_c_abi.c \
    "$library" -lm -lpthread -ldl -o "$work/fuzz_c_abi"

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
