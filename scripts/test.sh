#!/usr/bin/env bash
# Every check: formatting, lints, Rust tests, the no_std proof, the Python build and pytest.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
step() { printf '\n==> %s\n' "$*"; }

step "cargo fmt --check"
cargo fmt --all --check
step "cargo clippy --all-targets -- -D warnings"
cargo clippy --all-targets -- -D warnings
cargo clippy -p nostd-check --profile nostd -- -D warnings
step "cargo test"
cargo test
step "no_std proof: a #![no_std] static library without allocator links gms-core"
cargo build -p nostd-check --profile nostd
step "Python build"
source scripts/setup.sh
step "pytest"
python -m pytest
