"""The discrepancy workflow on generated logs with hidden effects, over several seeds and two
encoder resolutions: is every case named exactly, and how close does the final rms come to the
noise floor (target: within 1.2x for in-catalogue cases)?

    python benches/hidden.py [--seeds 4]

Single effects at dt = 0.8 ms, pairs at 0.4 ms, as in tests/discrepancy/test_discrepancy_hidden.py; a few
minutes on a 2-core machine.
"""

from __future__ import annotations

import argparse

from tqdm import tqdm

import leuven_rt as lr
from leuven_rt.discrepancy import CATALOGUE
from leuven_rt.discrepancy.hidden import make_hidden

BASE = ("coulomb", "viscous")
CASES = [
    (),
    *[(name,) for name in CATALOGUE if name not in BASE],
    ("inertia", "offset"),
    ("presliding_hysteresis", "position_dependence"),
    ("stribeck", "inertia"),
    ("stribeck", "asymmetry"),
]
RESOLUTIONS = (1e-9, 1e-10)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=4)
    seeds = range(parser.parse_args().seeds)
    print("| hidden | encoder | named exactly | final rms / noise floor (min-max over seeds) |")
    print("|---|---|---:|---:|")
    for hidden in CASES:
        for resolution in RESOLUTIONS:
            exact, ratios = 0, []
            for seed in tqdm(seeds, desc="+".join(hidden) or "null", leave=False):
                dt = 4e-4 if len(hidden) > 1 else 8e-4
                data = make_hidden(BASE + hidden, dt=dt, quantization=resolution, seed=seed,
                                   with_velocity="offset" in hidden).data  # fmt: skip
                diagnosis = lr.diagnose(data, BASE)
                exact += sorted(diagnosis.named_effects) == sorted(hidden)
                ratios.append(diagnosis.rms_after / diagnosis.noise_std)
            print(f"| {' + '.join(hidden) or 'none (null case)'} | {resolution * 1e9:g} nm | "
                  f"{exact}/{len(seeds)} | {min(ratios):.2f}-{max(ratios):.2f} |", flush=True)  # fmt: skip


if __name__ == "__main__":
    main()
