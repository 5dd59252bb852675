#!/usr/bin/env bash
# Every check: formatting, lints, Rust tests and docs, the no_std proof, the Python build, Python
# lint, types and stubs, pytest, and the packages as users get them: the wheel and sdist, the
# wheel in fresh virtualenvs without Rust, the installed C library, the gms-core crate.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
step() { printf '\n==> %s\n' "$*"; }

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
bash scripts/c_package.sh
step "cargo package -p gms-core (the crate as crates.io would get it)"
cargo package --quiet -p gms-core --allow-dirty
step "libFuzzer on the C ABI under AddressSanitizer and UndefinedBehaviorSanitizer, 60 s (scripts/fuzz_c.sh)"
bash scripts/fuzz_c.sh 60
