"""The identified compensator against the true friction law, in the closed-loop study's loop: how
much tracking the identification leaves on the table, per plant and compensation mode.

For each plant, the stage is logged on the study's identification trajectory under the PID
without compensation and identified from ``coulomb,viscous`` (``studies.closed_loop``); then
the evaluation trajectory is tracked with the compensator running the identified file and with
one running the plant's own law (the study's hand-set model made the truth), each fed the planned
velocity (feedforward) or the encoder (observer). Printed: the tracking RMS and the reversal
glitch of each, and identified ÷ true law. The numbers do not depend on the machine.

Plants: the study's stage (Maxwell-slip, σ1 = 50), and two LuGre stages (a linear bristle,
n = 1) that no part of the workflow was tuned on.

    python benches/true_law.py [--plant study|lugre_soft|lugre_stiff ...]
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence

from leuven_rt import Params
from leuven_rt.studies import closed_loop

PLANTS = {
    "study": closed_loop.TRUE,
    # Presliding over about 3·Fs/σ0 = 90 µm, damped by σ1.
    "lugre_soft": Params(Fc=2.0, Fs=3.0, Vs=2e-3, delta=2.0, n=1.0, sigma0=1e5, sigma1=300.0, sigma2=5.0),
    # Presliding over about 9 µm; Fs − Fc = 2 N over a wider Stribeck curve (δ = 1); little viscous
    # friction.
    "lugre_stiff": Params(Fc=4.0, Fs=6.0, Vs=4e-3, delta=1.0, n=1.0, sigma0=2e6, sigma1=1000.0, sigma2=2.0),
}
MODES = ("feedforward", "observer")


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--plant", choices=list(PLANTS), nargs="+", default=list(PLANTS), help="the plants (default: all)"
    )
    arguments = parser.parse_args(argv)
    compensations = [f"{kind}_{mode}" for kind in ("leuven", "identified") for mode in MODES]
    columns = ["plant", "named", "mode", "RMS identified / true law [µm]", "ratio",
               "glitch identified / true law [µm]", "ratio"]  # fmt: skip
    print("| " + " | ".join(columns) + " |\n|---|---|---|---:|---:|---:|---:|")
    for name in arguments.plant:
        scenario = closed_loop.Scenario(true=PLANTS[name], model=PLANTS[name])
        identified = closed_loop.identify_stage(scenario)
        metrics = closed_loop.compare(scenario, compensations, identified=identified).metrics
        named = ", ".join(identified.named)
        for mode in MODES:
            found, true_law = metrics[f"identified_{mode}"], metrics[f"leuven_{mode}"]
            print(
                f"| {name} | {named} | {mode} | {found.rms * 1e6:.3f} / {true_law.rms * 1e6:.3f} "
                f"| {found.rms / true_law.rms:.2f}× | {found.glitch * 1e6:.3f} / {true_law.glitch * 1e6:.3f} "
                f"| {found.glitch / true_law.glitch:.2f}× |",
                flush=True,
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
