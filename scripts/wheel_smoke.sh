#!/usr/bin/env bash
# The wheel as a user gets it: for every CPython >= 3.10 on this machine, a NEW virtualenv, the
# wheel installed from dist/ (built by scripts/dist.sh if missing), run with no Rust on PATH
# (PATH=<venv>/bin:/usr/bin:/bin) from a folder outside the source tree:
#   1. the lean core (numpy only): simulate, a compensator loop, the parameter file; a room that
#      needs [analysis] says so; `import leuven_rt` loads no scipy, matplotlib or tqdm;
#   2. with [analysis]: identify a small log that the package generates.
#
#   bash scripts/wheel_smoke.sh             # test
#   bash scripts/wheel_smoke.sh --measure   # also: install time (median of 3 fresh venvs),
#                                           # import time (median of 7), size of the install
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root="$PWD"
measure=0
[ "${1:-}" = "--measure" ] && measure=1

shopt -s nullglob
wheels=(dist/leuven_rt-*.whl)
if [ ${#wheels[@]} -eq 0 ]; then
    bash scripts/dist.sh >/dev/null
    wheels=(dist/leuven_rt-*.whl)
fi
[ ${#wheels[@]} -eq 1 ] || { echo "wheel_smoke.sh: expected one wheel in dist/, found ${#wheels[@]}" >&2; exit 1; }
wheel="$root/${wheels[0]}"
case "$wheel" in
    *-cp310-abi3-*manylinux_2_17_x86_64*) ;;
    *) echo "wheel_smoke.sh: not an abi3 manylinux_2_17 wheel: $wheel" >&2; exit 1 ;;
esac

# Every CPython >= 3.10 that this machine has (distinct interpreters, by real path).
pythons=()
declare -A seen=()
for candidate in python3 python3.10 python3.11 python3.12 python3.13 python3.14 \
    /usr/bin/python3.10 /usr/bin/python3.11 /usr/bin/python3.12 /usr/bin/python3.13 /usr/bin/python3.14; do
    path="$(command -v "$candidate" 2>/dev/null)" || continue
    # The interpreter itself (pyenv's shims are scripts), if it is CPython >= 3.10 with venv.
    real="$("$path" -c 'import os, sys, venv
if sys.implementation.name == "cpython" and sys.version_info >= (3, 10):
    print(os.path.realpath(sys.executable))' 2>/dev/null)" || continue
    [ -n "$real" ] && [ -z "${seen[$real]:-}" ] || continue
    seen[$real]=1
    pythons+=("$real")
done
[ ${#pythons[@]} -gt 0 ] || { echo "wheel_smoke.sh: no CPython >= 3.10 with venv on this machine" >&2; exit 1; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"

lean='
import sys
import numpy as np
import leuven_rt as lr
heavy = sorted(m for m in sys.modules if m.split(".")[0] in {"scipy", "matplotlib", "tqdm"})
assert not heavy, heavy
p = lr.Params(Fc=1.0, Fs=1.5, Vs=1e-3, delta=2.0, n=2.0, sigma1=30.0, sigma2=0.4,
              W=[0.6, 0.5, 0.4, 0.3], Delta=[1e-6, 2e-6, 4e-6, 8e-6])
p.save("params.json")
p = lr.Params.load("params.json")
t = np.arange(4000) * 1e-3
f = lr.simulate(p, 1e-2 * np.sin(2 * np.pi * t), 1e-3)
c = lr.Compensator(p, 1e-3, mode="observer")
forces = [c.step(x) for x in 1e-4 * (1 - np.cos(2 * np.pi * t[:1000]))]
assert np.all(np.isfinite(f)) and max(abs(x) for x in forces) > 1.0
try:
    import leuven_rt.discrepancy
except ImportError as error:
    assert "leuven-rt[analysis]" in str(error), error
else:
    raise AssertionError("leuven_rt.discrepancy imported without scipy")
print(f"lean core ok (leuven-rt {lr.__version__}, numpy {np.__version__})")
'
analysis='
import leuven_rt as lr
from leuven_rt.data.synthetic import make_data
log = make_data(dt=1e-3, seed=1).data  # 6k samples: a small log
result = lr.identify(log)
fitted = result.model.friction
assert abs(fitted.Fc - 1.0) < 0.5, fitted
result.model.save("identified.json", force=True)  # one file per interpreter run, replaced
assert lr.ModelFile.load("identified.json").friction == fitted
print(f"identify ok: Fc = {fitted.Fc:.3f} N, Fs = {fitted.Fs:.3f} N, {len(fitted.W)} elements")
'

run() { env -i HOME="$HOME" PATH="$1/bin:/usr/bin:/bin" "${@:2}"; }
pip_install() { run "$1" python -m pip install --quiet --disable-pip-version-check "${@:2}"; }

for python in "${pythons[@]}"; do
    version="$("$python" -c 'import sys; print("%d.%d" % sys.version_info[:2])')"
    venv="$work/venv-$version-$(echo "$python" | md5sum | cut -c1-6)"
    "$python" -m venv "$venv"
    if run "$venv" sh -c 'command -v cargo rustc' >/dev/null; then
        echo "wheel_smoke.sh: Rust on the smoke PATH" >&2
        exit 1
    fi
    pip_install "$venv" "$wheel"
    echo "CPython $version ($python):"
    run "$venv" python -c "$lean" | sed 's/^/  /'
    pip_install "$venv" "$wheel[analysis]"
    run "$venv" python -c "$analysis" | sed 's/^/  /'
    run "$venv" leuven-rt --version | sed 's/^/  /'
done

if [ "$measure" = 1 ]; then
    python="${pythons[0]}"
    median() { sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
    times=()
    for i in 1 2 3; do
        venv="$work/measure-$i"
        "$python" -m venv "$venv"
        start=$(date +%s.%N)
        pip_install "$venv" "$wheel"
        times+=("$(echo "$(date +%s.%N) - $start" | bc)")
    done
    echo "install of $(basename "$wheel") into a fresh venv (numpy from pip's cache), 3 runs: ${times[*]} s; median $(printf '%s\n' "${times[@]}" | median) s"
    imports=() numpys=()
    for i in 1 2 3 4 5 6 7; do
        profile="$(run "$venv" python -X importtime -c 'import leuven_rt' 2>&1)"
        imports+=("$(echo "$profile" | awk -F'|' '$3 ~ /^ leuven_rt$/ {gsub(/ /, "", $2); print int($2 / 1000)}')")
        numpys+=("$(echo "$profile" | awk -F'|' '$3 ~ /^ +numpy$/ {gsub(/ /, "", $2); print int($2 / 1000)}' | head -n 1)")
    done
    echo "import leuven_rt (python -X importtime, cumulative), 7 runs: ${imports[*]} ms; median $(printf '%s\n' "${imports[@]}" | median) ms, of which numpy $(printf '%s\n' "${numpys[@]}" | median) ms (median)"
    bare="$work/bare"
    "$python" -m venv "$bare"
    site() { run "$1" python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])'; }
    kib() { du -sk "$(site "$1")" | cut -f1; }
    echo "compensator-only install: site-packages $(( $(kib "$venv") - $(kib "$bare") )) KiB above a bare venv ($(du -sh "$(site "$venv")" | cut -f1) in all)"
fi
