#!/usr/bin/env bash
# Every check: formatting, lints, Rust tests and docs, the no_std proof, the Python build, Python
# lint, types and stubs, and pytest.
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
