"""The main job: simulate the standard presliding-to-sliding scenario and draw it."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .params import Params  # noqa: E402
from .scenarios import presliding_to_sliding, standard_params  # noqa: E402
from .simulation import simulate_position  # noqa: E402


@dataclass(frozen=True)
class DemoResult:
    """What the demo computed and where it wrote the figure."""

    figure: Path
    samples: int
    peak_force: float
    sliding_force: float
    presliding_peak: float
    params: Params


def run_demo(out: Path) -> DemoResult:
    """Simulates the scenario with the standard parameters and writes ``presliding_to_sliding.png``."""
    params = standard_params()
    excitation = presliding_to_sliding()
    force = simulate_position(params, excitation.x, excitation.dt)

    out.mkdir(parents=True, exist_ok=True)
    figure_path = out / "presliding_to_sliding.png"
    figure, (by_position, by_time) = plt.subplots(1, 2, figsize=(12, 4.5))
    by_position.plot(excitation.x * 1e6, force, linewidth=0.7)
    by_position.set_xlabel("displacement x [µm]")
    by_position.set_ylabel("friction force F [N]")
    by_position.set_title("Force vs displacement: presliding loops, then sliding")
    by_position.set_xscale("symlog", linthresh=1.0)
    by_time.plot(excitation.t, force, linewidth=0.7)
    by_time.set_xlabel("time t [s]")
    by_time.set_ylabel("friction force F [N]")
    by_time.set_title("Force vs time")
    for axis in (by_position, by_time):
        axis.axhline(params.Fs, color="grey", linestyle=":", linewidth=0.8)
        axis.axhline(-params.Fs, color="grey", linestyle=":", linewidth=0.8)
        axis.grid(alpha=0.3)
    figure.tight_layout()
    figure.savefig(figure_path, dpi=120)
    plt.close(figure)

    presliding = excitation.amplitude < 0.5 * params.Delta[-1]
    sliding = excitation.t > excitation.t[-1] - 1.0
    return DemoResult(
        figure=figure_path,
        samples=len(force),
        peak_force=float(np.max(np.abs(force))),
        sliding_force=float(np.median(np.abs(force[sliding]))),
        presliding_peak=float(np.max(np.abs(force[presliding]))),
        params=params,
    )
