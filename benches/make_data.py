"""Log to loop on the package's own generated logs: ``make_data`` (the paper's model, with
presliding, a Stribeck curve, σ1 and σ2) for seeds 0–9, identified from the baseline
``coulomb,viscous``; prints, per seed, the effects named, the rms of the written model file
through ``predict`` against the noise, and the wall time.

Target (the "one model" issue): named exactly {stribeck, presliding_hysteresis} on every seed,
and the written file's rms within 1.2× the noise.

    python benches/make_data.py [--seeds 0-9]
"""

from __future__ import annotations

import argparse
import time

import leuven_rt as lr
from leuven_rt.data.synthetic import make_data

EXPECTED = {"stribeck", "presliding_hysteresis"}
BOUND = 1.2


def seeds(text: str) -> list[int]:
    first, _, last = text.partition("-")
    return list(range(int(first), int(last or first) + 1))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="0-9", help="a seed or a range, e.g. 0-9 (default)")
    arguments = parser.parse_args()
    passed = 0
    chosen = seeds(arguments.seeds)
    for seed in chosen:
        log = make_data(seed=seed)
        start = time.perf_counter()
        result = lr.identify(log.data)
        seconds = time.perf_counter() - start
        rms = lr.predict(result.model, log.data).rms
        named = set(result.diagnosis.named_effects)
        ok = named == EXPECTED and rms <= BOUND * log.noise_std
        passed += ok
        ratio = rms / log.noise_std
        print(f"seed {seed}: {log.data.samples} samples, named {sorted(named)}, file rms {ratio:.3f}x "
              f"the noise, {seconds:.1f} s  {'PASS' if ok else 'FAIL'}", flush=True)  # fmt: skip
    print(f"make_data: {passed}/{len(chosen)} named exactly with the file within {BOUND}x the noise")
    return 0 if passed == len(chosen) else 1


if __name__ == "__main__":
    raise SystemExit(main())
