"""The ``--plot`` figure: residual over time with the regions where it was largest marked, and
residual against velocity, position and displacement since the last reversal, for the baseline
and after each step."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .._plot import figure, save
from ..units import unit_names
from .report import Diagnosis


def plot_diagnosis(diagnosis: Diagnosis, path: str | Path) -> Path:
    usable = diagnosis.layout.usable
    t, v, x, travel = diagnosis.t, diagnosis.v, diagnosis.x, diagnosis.travel
    names = unit_names(diagnosis.units)
    force, position, velocity = names.force, names.position, names.velocity
    labels = ["baseline"] + [f"+ {step.effect}" for step in diagnosis.steps]
    drawing, axes = figure(2, 2, size=(13, 8))
    by_time, by_velocity, by_position, by_travel = axes.ravel()
    worst = max(diagnosis.regions_before, key=lambda region: region.rms).name
    marked = diagnosis.layout.masks[worst]
    by_time.fill_between(t, 0, 1, where=marked, transform=by_time.get_xaxis_transform(), color="orange",
                         alpha=0.15, label=f"largest baseline residual: {worst}")  # fmt: skip
    for label, residual in zip(labels, diagnosis.residuals, strict=True):
        by_time.plot(t[usable], residual[usable], linewidth=0.5, label=label)
        by_velocity.plot(v[usable], residual[usable], ".", markersize=1, label=label)
        by_position.plot(x[usable], residual[usable], ".", markersize=1, label=label)
        by_travel.plot(np.maximum(travel[usable], 1e-12), residual[usable], ".", markersize=1, label=label)
    by_time.set(xlabel="time t [s]", ylabel=f"residual f − model [{force}]", title="Residual over time")
    by_velocity.set(
        xlabel=f"velocity v [{velocity}]", ylabel=f"residual [{force}]", title="Residual vs velocity"
    )
    linear_below = max(float(np.percentile(np.abs(v[usable]), 10)), 1e-12)
    by_velocity.set_xscale("symlog", linthresh=linear_below)
    # Decades from ten times the linear range outwards, and 0: labels at ±linthresh would collide.
    top = max(float(np.max(np.abs(v[usable]))), 10.0 * linear_below)
    decades = 10.0 ** np.arange(np.ceil(np.log10(10.0 * linear_below)), np.floor(np.log10(top)) + 1)
    by_velocity.set_xticks(np.concatenate((-decades[::-1], [0.0], decades)))
    by_position.set(
        xlabel=f"position x [{position}]", ylabel=f"residual [{force}]", title="Residual vs position"
    )
    by_travel.set(xlabel=f"displacement since reversal [{position}]", ylabel=f"residual [{force}]",
                  xscale="log", title="Residual vs displacement since reversal")  # fmt: skip
    for axis in axes.ravel():
        axis.grid(alpha=0.3)
        axis.legend(fontsize=7, markerscale=8, loc="upper right")
    drawing.suptitle(f"diagnose: rms {diagnosis.rms_before:.3g} {force} -> {diagnosis.rms_after:.3g} {force} "
                    f"(noise floor {diagnosis.noise_std:.3g} {force})")  # fmt: skip
    drawing.tight_layout()
    return save(drawing, path, dpi=110)
