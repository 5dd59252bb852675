"""The model file's numbers, refined on the quantity a compensator delivers: the force of the
model file simulated along the log (what :func:`leuven_rt.predict` computes), against the measured
force.

The workflow's regression holds the friction in a linear form; the model file holds it in the
modified Leuven model's, where the hysteresis force saturates at the Stribeck level and the level
scales the whole contact force. The mapping (:mod:`.deploy`) is close but not exact, so the file's
levels, Stribeck shape, viscous term, level coefficients and measurement terms are refined by
bounded nonlinear least squares on the simulation error, starting from the mapping. The elements
keep their widths and relative weights (scaled with the static level), and n stays. The refined
file is kept only when it lowers the simulation error.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np
from scipy.optimize import least_squares

from .._typing import BoolArray, FloatArray
from ..errors import ParameterError
from ..level import PositionLevel, Ripple
from ..modelfile import ModelFile
from ..params import Params
from ..prediction import model_forces
from ..progress import Progress
from .deploy import MARGIN

#: Budget of the refinement, in simulations of the record.
EVALUATIONS = 200


def simulation_residual(
    model: ModelFile, x: FloatArray, a: FloatArray, dt: float, force: FloatArray
) -> FloatArray:
    """The model file's force along the filtered position ``x`` (acceleration ``a``) minus ``force``."""
    out: FloatArray = model_forces(model, x, a, dt)[1] - force
    return out


def refine(
    model: ModelFile,
    x: FloatArray,
    a: FloatArray,
    dt: float,
    force: FloatArray,
    rows: BoolArray,
    report: Progress | None = None,
) -> tuple[ModelFile, float, float]:
    """The refined model file (module documentation), and the simulation rms before and after,
    on ``rows`` (a boolean mask); ``report`` counts the simulations (stage ``refinement``)."""
    simulations = 0
    pack, unpack = _coordinates(model)
    start = pack()
    lower = np.array([bound for bound, _ in _bounds(model)])
    upper = np.array([bound for _, bound in _bounds(model)])
    start = np.clip(start, lower, upper)
    mask = np.asarray(rows, dtype=bool)
    worst = 10.0 * float(np.sqrt(np.mean(force[mask] ** 2))) + 1.0

    def residual(theta: FloatArray) -> FloatArray:
        nonlocal simulations
        if report is not None:  # the budget counts evaluations, not the Jacobians' simulations
            report.stage("refinement", simulations, None, "simulations")
        simulations += 1
        try:
            candidate = unpack(theta)
        except ParameterError:  # outside the model's rules (a level factor reaching 0)
            return np.full(int(mask.sum()), worst)
        inside: FloatArray = simulation_residual(candidate, x, a, dt, force)[mask]
        return inside

    before = residual(start)
    rms_before = float(np.sqrt(np.mean(before**2)))
    scale = np.maximum(np.abs(start), 1e-3 * np.maximum(np.abs(upper - lower), 1e-12))
    scale = np.where(np.isfinite(scale), scale, 1.0)
    result = least_squares(residual, start, bounds=(lower, upper), x_scale=scale, max_nfev=EVALUATIONS,
                           diff_step=np.full(start.size, 1e-4))  # fmt: skip
    rms_after = float(np.sqrt(np.mean(result.fun**2)))
    if not rms_after < rms_before:
        return model, rms_before, rms_before
    return unpack(result.x), rms_before, rms_after


def _bounds(model: ModelFile) -> list[tuple[float, float]]:
    p = model.friction
    tiny = 1e-9 * max(p.Fc, 1e-300)
    out = [(tiny, np.inf), (0.0, np.inf), (np.log(p.Vs) - 5.0, np.log(p.Vs) + 5.0), (0.0, np.inf)]
    out.append((tiny, np.inf) if p.Fc_neg is not None else (0.0, 0.0))
    out.append((0.0, np.inf) if p.Fs_neg is not None else (0.0, 0.0))
    out += [(-np.inf, np.inf), (0.0, np.inf)]  # offset, inertia
    if model.level is not None:
        out += [(-1.0, 1.0)] * len(_level_values(model.level))
    return [(low, high if high > low else low + 1e-300) for low, high in out]


def _level_values(level: PositionLevel) -> list[float]:
    values = [*level.trend]
    for ripple in level.ripples:
        values += [*ripple.cos, *ripple.sin]
    return values


def _coordinates(model: ModelFile) -> tuple[Callable[[], FloatArray], Callable[[FloatArray], ModelFile]]:
    p = model.friction
    weights = np.asarray(p.W, dtype=float)
    shares = weights / weights.sum()

    def pack() -> FloatArray:
        values = [p.Fc, p.Fs - p.Fc, np.log(p.Vs), p.sigma2,
                  p.Fc_neg if p.Fc_neg is not None else 0.0,
                  (p.Fs_neg - p.Fc_neg) if p.Fs_neg is not None and p.Fc_neg is not None else 0.0,
                  model.offset, model.inertia]  # fmt: skip
        if model.level is not None:
            values += _level_values(model.level)
        return np.array(values, dtype=float)

    def unpack(theta: FloatArray) -> ModelFile:
        fc, bump, log_vs, sigma2, fc_neg, bump_neg, offset, inertia = (float(v) for v in theta[:8])
        fs = fc + bump
        sides = {"Fc_neg": fc_neg, "Fs_neg": fc_neg + bump_neg} if p.Fc_neg is not None else {}
        top = max(fs, sides.get("Fs_neg", 0.0))
        friction = Params(
            Fc=fc, Fs=fs, Vs=float(np.exp(log_vs)), delta=p.delta, n=p.n, sigma1=p.sigma1, sigma2=sigma2,
            W=tuple(float(w) for w in shares * MARGIN * top), Delta=p.Delta, **sides,
        )  # fmt: skip
        level = model.level
        if level is not None:
            values = [float(v) for v in theta[8:]]
            trend, values = (values[0], values[1]), values[2:]
            ripples = []
            for ripple in level.ripples:
                count = len(ripple.cos)
                ripples.append(Ripple(ripple.period, tuple(values[:count]), tuple(values[count : 2 * count])))
                values = values[2 * count :]
            level = dataclasses.replace(level, trend=trend, ripples=tuple(ripples))
        return dataclasses.replace(model, friction=friction, level=level, offset=offset, inertia=inertia)

    return pack, unpack
