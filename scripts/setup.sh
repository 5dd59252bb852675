# Sourced by main.sh and test.sh: a project virtualenv with the Python package built in release
# mode and its runtime and test dependencies installed. Safe to run again; it only adds.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check --upgrade "pip>=23" "maturin>=1.9,<2"
# An extension built before the abi3 wheel (_core.cpython-*.so) would shadow the abi3 one.
rm -f python/leuven_rt/_core.cpython-*.so
# Installs leuven-rt in editable mode, with its runtime dependencies, the test and lint tools and
# the benchmarks' peers.
# PIP_QUIET: maturin runs pip for the dependencies; its progress is not what the reader needs.
PIP_QUIET=1 PIP_DISABLE_PIP_VERSION_CHECK=1 .venv/bin/maturin develop --release --quiet --extras test,lint,bench
export PATH="$root/.venv/bin:$PATH"
