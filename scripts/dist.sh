#!/usr/bin/env bash
# The Python distributions into dist/: one abi3 wheel (CPython >= 3.10) for manylinux2014
# (glibc 2.17, x86_64), linked with zig from the ziglang package so that it runs on old
# systems, checked by maturin's own manylinux audit and by auditwheel; and the sdist. Prints the file names and
# sizes, nothing else. Uses the project virtualenv .venv (created if missing).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
[ -x .venv/bin/python ] || python3 -m venv .venv
.venv/bin/python -m pip install --quiet --disable-pip-version-check "maturin>=1.9,<2" "ziglang>=0.13" \
    "auditwheel>=6"
# maturin finds zig through the ziglang package of the Python it runs with.
export PATH="$PWD/.venv/bin:$PATH"
# Only this package's earlier builds are replaced; anything else in dist/ is left alone.
mkdir -p dist
rm -f dist/leuven_rt-*.whl dist/leuven_rt-*.tar.gz
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
build() { "$@" >"$log" 2>&1 || { cat "$log" >&2; exit 1; }; }
# The flags of scripts/setup.sh's editable build: after it, this build has nothing to compile.
build .venv/bin/maturin build --release --quiet --zig --compatibility manylinux2014 --out dist
build .venv/bin/maturin sdist --out dist
# auditwheel's verdict: the wheel is consistent with manylinux_2_17 (glibc 2.17) and no newer.
build .venv/bin/auditwheel show dist/leuven_rt-*.whl
grep -q '"manylinux_2_17_x86_64"' "$log" || { cat "$log" >&2; exit 1; }
for file in dist/leuven_rt-*; do
    printf '%s  %s bytes\n' "$file" "$(stat -c %s "$file")"
done
