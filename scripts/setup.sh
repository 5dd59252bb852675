# Sourced by main.sh and test.sh: a project virtualenv with the Python package built in release
# mode and its runtime and test dependencies installed. Safe to run again; it only adds.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check --upgrade "pip>=23" "maturin>=1.9,<2"
# Installs leuven-rt in editable mode, with its runtime dependencies and the test and lint tools.
.venv/bin/maturin develop --release --quiet --extras test,lint
export PATH="$root/.venv/bin:$PATH"
