"""Parameters the excitation does not determine, set to the value that adds no force beyond what
the log shows (docs/effects.md#undetermined-parameters).

A one-way ramp cannot tell a viscous slope from a constant level, and a log that never moves in
−x says nothing of the −x levels: left at whatever the fit found, such a parameter extrapolates
(σ2 = 999 gives 100 N at 0.1 m/s). A parameter whose standard error exceeds :data:`RELATIVE`
times its value is undetermined; the ones below have a value that adds no force (:data:`NEUTRAL`)
and are fixed there, the model refitted without them, and a warning names each with the value
the file keeps.

The standard errors come from the Jacobian of the weighted simulation error at the fit,
cov = s²·(JᵀJ)⁺ with s² the noise variance inflated by the residual's correlation in time (the
number of independent samples of coloured noise is smaller than the number of samples).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .._typing import FloatArray
from .evaluate import evaluate
from .solve import Fitted, Target
from .structure import Scales, Structure

#: The −x parameters of ``asymmetry``: when the −x level is undetermined (a log that never moves
#: in −x), the model is made symmetric (the −x levels the +x ones) instead of fixing a number.
MINUS_X = ("Fc_neg", "Fs_neg_rise", "sigma2_neg")

#: A parameter is undetermined when its standard error exceeds this share of its absolute value.
RELATIVE = 0.5
#: Most lags of the residual's autocorrelation summed into the inflation of the variance.
MAX_LAG = 200


def neutral(name: str, theta: dict[str, float]) -> float | None:
    """The value at which parameter ``name`` adds no force, or None if it has none."""
    if name in ("sigma1", "sigma2", "sigma2_neg", "Fs_rise", "Fs_neg_rise", "offset", "inertia"):
        return 0.0
    if name == "Fc_neg":
        return theta.get("Fc")
    if name.startswith(("level_", "force_")):
        return 0.0
    return None


@dataclass(frozen=True)
class Undetermined:
    """A parameter fixed at its neutral value: its name, the value the fit found and its
    standard error, and the value kept."""

    name: str
    value: float
    error: float
    kept: float

    def warning(self) -> str:
        return (
            f"`{self.name}` = {self.value:.4g} is not determined by this excitation (standard error "
            f"{self.error:.3g}): the file holds {self.kept:.4g}, "
            "which adds no force beyond what the log shows"
        )


def inflation(residual: FloatArray) -> float:
    """1 + 2·Σρ(k): how many samples of ``residual`` count as one independent one."""
    centred = residual - residual.mean()
    variance = float(np.dot(centred, centred))
    if not variance > 0:
        return 1.0
    total = 0.0
    for lag in range(1, min(MAX_LAG, centred.size // 4)):
        rho = float(np.dot(centred[lag:], centred[:-lag])) / variance
        if rho <= 0:
            break
        total += rho
    return 1.0 + 2.0 * total


def standard_errors(fitted: Fitted, scales: Scales, target: Target, noise: float) -> dict[str, float]:
    """The standard error of each parameter of ``fitted`` at its θ."""
    rows = target.rows
    result = evaluate(fitted.structure, scales, fitted.theta, target.motion, target.tau, rows)
    assert result.jacobian is not None
    names = fitted.structure.names() + fitted.structure.share_names(scales.deltas.size)
    jac = result.jacobian * np.sqrt(target.weight[rows])[:, None]
    residual = (target.force - fitted.force)[rows]
    variance = noise**2 * inflation(residual)
    scale = np.linalg.norm(jac, axis=0)
    scale[scale == 0] = 1.0
    normal = (jac / scale).T @ (jac / scale)
    covariance = np.linalg.pinv(normal, rcond=1e-12) * variance / np.outer(scale, scale)
    errors = np.sqrt(np.maximum(np.diag(covariance), 0.0))
    # A column the data never excites (all zero) has no information at all.
    errors[np.linalg.norm(jac, axis=0) == 0] = math.inf
    return dict(zip(names, errors.tolist(), strict=True))


def settle(
    fitted: Fitted,
    scales: Scales,
    target: Target,
    noise: float,
    refit: Callable[[Structure, dict[str, float]], Fitted],
    threshold: float = math.inf,
) -> tuple[Fitted, list[Undetermined]]:
    """``fitted`` with its undetermined parameters fixed at their neutral values and the rest
    refitted (``refit(structure, fixed)``), and what was fixed.

    A standard error is read from the fit's linearisation. Where parameters trade off nonlinearly
    (a Stribeck rise against a small Vs and δ), each one's error is large although together they
    are determined: fixing the rise at 0 takes out an effect the log shows. So the fixed set may
    cost at most ``threshold`` in the target's mean squared error; when it costs more, a parameter
    whose neutral value alone (the others as fitted) costs more than ``threshold`` is left free."""
    errors = standard_errors(fitted, scales, target, noise)
    found: list[Undetermined] = []
    for name, value in fitted.theta.items():
        kept = neutral(name, fitted.theta)
        if kept is None or value == kept:
            continue
        error = errors.get(name, 0.0)
        if not error <= RELATIVE * abs(value - kept):
            found.append(Undetermined(name, value, error, kept))
    if not found:
        return fitted, []
    settled = _fixed(fitted, found, refit)
    if settled.mse - fitted.mse <= threshold:
        return settled, found
    found = [item for item in found if _cost(fitted, item, scales, target) <= threshold]
    if not found:
        return fitted, []
    settled = _fixed(fitted, found, refit)
    if settled.mse - fitted.mse <= threshold:
        return settled, found
    return fitted, []


def _neutral_model(structure: Structure, fixed: dict[str, float]) -> tuple[Structure, dict[str, float]]:
    """The structure and the fixed values that hold the parameters of ``fixed`` at their neutral
    values: an undetermined −x level makes the model symmetric (without ``asymmetry``, so
    without any of :data:`MINUS_X`) instead of fixing a number."""
    if "Fc_neg" not in fixed:
        return structure, fixed
    return structure.without("asymmetry"), {name: fixed[name] for name in fixed if name not in MINUS_X}


def _fixed(
    fitted: Fitted, found: list[Undetermined], refit: Callable[[Structure, dict[str, float]], Fitted]
) -> Fitted:
    return refit(*_neutral_model(fitted.structure, {item.name: item.kept for item in found}))


def _cost(fitted: Fitted, item: Undetermined, scales: Scales, target: Target) -> float:
    """What fixing ``item`` alone at its neutral value, the rest as fitted, adds to the mean
    squared error."""
    structure, fixed = _neutral_model(fitted.structure, {item.name: item.kept})
    theta = {**fitted.theta, **fixed}
    force = evaluate(structure, scales, theta, target.motion, target.tau, None).force
    return target.mse(force) - fitted.mse


__all__ = ["MINUS_X", "RELATIVE", "Undetermined", "inflation", "neutral", "settle", "standard_errors"]
