# Sourced by main.sh and test.sh: a project virtualenv with the Python package built in release
# mode and its runtime and test dependencies installed. Safe to run again; it only adds.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check --upgrade "pip>=23" "maturin>=1.9,<2" \
    "ziglang>=0.13"
# An extension built before the abi3 wheel (_core.cpython-*.so) would shadow the abi3 one.
rm -f python/leuven_rt/_core.cpython-*.so
# maturin finds zig through the ziglang package of the Python it runs with.
export PATH="$root/.venv/bin:$PATH"
# Installs leuven-rt in editable mode (the extension built in release mode into python/), with its
# runtime dependencies, the test and lint tools and the benchmarks' peers. The extension is built
# exactly as scripts/dist.sh builds the wheel's (zig, manylinux2014; same target, linker and
# profile), so that the wheel's build finds it all compiled: one release build, not two.
MATURIN_PEP517_ARGS="--zig --compatibility manylinux2014" .venv/bin/python -m pip install --quiet \
    --disable-pip-version-check --no-build-isolation --editable ".[test,lint,bench]"
