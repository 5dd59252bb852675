#!/usr/bin/env bash
# Every check: formatting, lints, Rust tests and docs, the no_std proof, the Python build, Python
# lint, types and stubs, pytest, and the packages as users get them: the wheel and sdist, the
# wheel in fresh virtualenvs without Rust, the installed C library, the gms-core crate, and the
# C ABI under libFuzzer. Installs what it needs first (scripts/system.sh): the system packages,
# and cargo-c, which compiles in the background while the checks run.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
work="$(mktemp -d)" cargo_c=""
# Each step's wall time, printed at the end (after a failure too): where a run's time goes.
times="" current="" since=$SECONDS
step() {
    [ -z "$current" ] || times+="$(printf '%6d s  %s' $((SECONDS - since)) "$current")"$'\n'
    current="$*" since=$SECONDS
    printf '\n==> %s\n' "$*"
}
finish() {
    # A run that stopped early ends the cargo-c build it started (its own process group).
    [ -z "$cargo_c" ] || kill -- -"$cargo_c" 2>/dev/null || true
    step "done"
    # The CPU time of every command the run waited for: on a shared machine the wall time
    # depends on the others' load, this much less.
    times >"$work/times"
    cpu="$(awk 'NR == 2 { split($0, t, /[ms ]+/); print int(t[1] * 60 + t[2] + t[3] * 60 + t[4]) }' "$work/times")"
    printf '%s%6d s  in all (CPU, user + sys: %d s; load average now: %s)\n' "$times" "$SECONDS" \
        "$cpu" "$(cut -d' ' -f1-3 /proc/loadavg)"
    rm -rf "$work"
}
trap finish EXIT

step "system packages and cargo-c (scripts/system.sh)"
source scripts/system.sh
system_install
if ! command -v cargo-cinstall >/dev/null; then
    # Minutes of compiling on a new machine: in the background, where it takes the core that the
    # single-threaded steps (pip, mypy, pytest, the fuzzer) leave idle. The C package waits for it.
    echo "cargo-c compiles in the background (log: $work/cargo-c.log)"
    setsid bash -c 'source scripts/system.sh && cargo_c_install' >"$work/cargo-c.log" 2>&1 &
    cargo_c=$!
fi
step "cargo fmt --check"
cargo fmt --all --check
step "cargo clippy --workspace --all-targets -- -D warnings"
cargo clippy --workspace --all-targets -- -D warnings
step "no_std proof: a #![no_std] static library without allocator links gms-core"
# A workspace of its own, so that no std crate switches features on in its dependencies.
cargo clippy --manifest-path crates/nostd-check/Cargo.toml --profile nostd -- -D warnings
cargo build --manifest-path crates/nostd-check/Cargo.toml --profile nostd
step "cargo test --workspace"
cargo test --workspace
step "cargo test -p gms-core (without the std feature, which the workspace's host crates switch on: libm's pow, as on a no_std target)"
cargo test -p gms-core
step "cargo test -p gms-dyn --no-default-features --features gms-core/std (as the C library builds it: no gms-batch, no rayon)"
cargo test -p gms-dyn --no-default-features --features gms-core/std
step "cargo doc --workspace --no-deps (warnings are errors)"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps
step "Python build"
source scripts/setup.sh
step "ruff check, ruff format --check"
ruff check python tests benches
ruff format --check python tests benches
step "mypy (strict) on the package"
mypy
step "stubtest: the extension against its stub"
python -m mypy.stubtest leuven_rt._core
step "pytest"
python -m pytest
step "wheel and sdist (scripts/dist.sh); the wheel in new venvs without Rust (scripts/wheel_smoke.sh)"
bash scripts/dist.sh
bash scripts/wheel_smoke.sh
step "C package: cargo cinstall, find_package and pkg-config against the install (scripts/c_package.sh)"
if [ -n "$cargo_c" ]; then
    status=0
    wait "$cargo_c" || status=$?
    cargo_c=""
    cat "$work/cargo-c.log"
    [ "$status" -eq 0 ] || exit "$status"
fi
bash scripts/c_package.sh --prefix "$work/c"
step "cargo package -p gms-core (the crate as crates.io would get it)"
cargo package --quiet -p gms-core --allow-dirty
step "libFuzzer on the installed libleuven_rt.a under AddressSanitizer and UndefinedBehaviorSanitizer, 60 s (scripts/fuzz_c.sh)"
bash scripts/fuzz_c.sh 60 "$work/c/lib/libleuven_rt.a"
