"""A friction model as a set of catalogue effects, fitted by linear least squares on chosen rows.

The coefficients come from the identification's :func:`fit_linear` (nonnegative where the
effect asks). With ``stribeck`` in the model, its shape (Vs, δ) is fitted by variable
projection: for each trial shape the linear coefficients are solved exactly (plain least
squares), and Nelder–Mead moves (log Vs, δ), started from the best of a grid over the speeds.
With ``presliding_hysteresis``, the bank's drive (:mod:`.drive`) is fitted by fixed-point
iteration for each exponent n tried: the weights fitted on the bank driven by z give the z of
the next pass, starting from the bank driven by x; the fit with the smallest residual is kept.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import minimize

from .._typing import FloatArray
from ..data.regression import fit_linear
from .drive import EXPONENTS, Drive
from .effects import TERMS, Shape
from .features import Features

Rows = NDArray[np.bool_]

#: Bounds of the Stribeck exponent δ searched.
DELTA_RANGE = (0.5, 4.0)
#: Fixed-point passes of the presliding drive for each exponent n.
DRIVE_PASSES = 2
PRESLIDING = "presliding_hysteresis"


@dataclass(frozen=True, eq=False)
class ModelFit:
    effects: tuple[str, ...]
    coefficients: dict[str, float]
    groups: dict[str, tuple[str, ...]]
    """The coefficient names of every effect."""
    shape: Shape | None
    drive: Drive | None = None
    periods: tuple[float, ...] = ()
    """The ripple periods the position columns were built with."""
    standard_errors: dict[str, float] = field(default_factory=dict)
    """Of each coefficient, from the linear fit (the Stribeck shape and the drive held fixed)."""

    def predict(self, features: Features) -> FloatArray:
        return self.predict_columns(self.drive.apply(features) if self.drive is not None else features)

    def predict_columns(self, features: Features) -> FloatArray:
        """The prediction on ``features`` as they are (already driven)."""
        columns = design(self.effects, features, self.shape)
        prediction = np.zeros_like(features.force)
        for name, column in columns.items():
            prediction += self.coefficients[name] * column
        return prediction

    def params(self, effect: str) -> dict[str, float]:
        """The fitted values that belong to ``effect``."""
        out = {name: self.coefficients[name] for name in self.groups[effect]}
        if effect == "stribeck" and self.shape is not None:
            out.update(Vs=self.shape.Vs, delta=self.shape.delta)
        if effect == PRESLIDING and self.drive is not None:
            out.update(n=self.drive.n)
        if effect == "position_dependence":
            out.update({f"period{number}": period for number, period in enumerate(self.periods, 1)})
        return out

    def to_dict(self) -> dict[str, object]:
        out: dict[str, object] = {
            "effects": list(self.effects),
            "params": {name: self.params(name) for name in self.effects},
        }
        if self.drive is not None:  # the weights that shaped z, to reproduce the prediction
            out["presliding_drive"] = {"n": self.drive.n, "W": list(self.drive.weights)}
        return out


def design(effects: Sequence[str], features: Features, shape: Shape | None) -> dict[str, FloatArray]:
    columns: dict[str, FloatArray] = {}
    for name in effects:
        columns.update(TERMS[name].columns(features, effects, shape))
    return columns


def fit_model(effects: Sequence[str], features: Features, rows: Rows, drive: Drive | None = None) -> ModelFit:
    """Coefficients (and the Stribeck shape, and the presliding drive unless ``drive`` is given)
    of ``effects`` fitted on ``rows``."""
    effects = tuple(effects)
    if PRESLIDING not in effects:
        return _fit_linear_part(effects, features, rows, None)
    if drive is not None:
        return _fit_linear_part(effects, drive.apply(features), rows, drive)
    return _fit_driven(effects, features, rows)


def _fit_linear_part(
    effects: tuple[str, ...], features: Features, rows: Rows, drive: Drive | None, shape: Shape | None = None
) -> ModelFit:
    if shape is None and "stribeck" in effects:
        shape = _fit_shape(effects, features, rows)
    groups = {
        name: tuple(TERMS[name].columns(features, effects, shape or Shape(1.0, 1.0))) for name in effects
    }
    if not effects:
        return ModelFit(effects, {}, groups, shape, drive, features.scales.periods)
    columns = design(effects, features, shape)
    nonnegative = [column for name in effects for column in TERMS[name].nonnegative]
    fit = fit_linear({key: value[rows] for key, value in columns.items()}, features.force[rows],
                     nonnegative or False)  # fmt: skip
    return ModelFit(effects, fit.coefficients, groups, shape, drive, features.scales.periods,
                    fit.standard_errors)  # fmt: skip


def _weights(fit: ModelFit) -> tuple[float, ...]:
    return tuple(max(fit.coefficients[name], 0.0) for name in fit.groups[PRESLIDING])


def _fit_driven(effects: tuple[str, ...], features: Features, rows: Rows) -> ModelFit:
    """The best fit over the exponents tried, each after DRIVE_PASSES fixed-point passes; the
    bank stays driven by x when the fit gives no element a positive weight."""
    undriven = _fit_linear_part(effects, features, rows, None)
    start = _weights(undriven)
    if max(start) <= 0.0:
        return undriven
    # The Stribeck shape is held at the undriven fit's while the drive is searched (the shape
    # search costs more than a drive pass), then fitted again with the drive chosen.
    tried: list[tuple[float, ModelFit, Features]] = []
    for n in EXPONENTS:
        drive = Drive(n, start)
        for _ in range(DRIVE_PASSES):
            driven = drive.apply(features)
            fit = _fit_linear_part(effects, driven, rows, drive, undriven.shape)
            residual = features.force[rows] - fit.predict_columns(driven)[rows]
            tried.append((float(residual @ residual), fit, driven))
            weights = _weights(fit)
            if max(weights) <= 0.0:
                break
            drive = Drive(n, weights)
    _, best, driven = min(tried, key=lambda item: item[0])
    if best.shape is None:
        return best
    return _fit_linear_part(effects, driven, rows, best.drive)


def _fit_shape(effects: tuple[str, ...], features: Features, rows: Rows) -> Shape:
    # Vs is searched within the speeds the data visits (moving samples only).
    speeds = np.abs(features.v[rows & (features.travel > features.scales.deflections[-1])])
    high = float(np.percentile(speeds, 95))
    low = max(float(np.percentile(speeds, 2)), 1e-3 * high)

    bounds = np.log([low, high])
    # Only the Stribeck column moves with the shape: the normal equations of the other columns
    # are formed once, and each trial adds one row and column (plain least squares, no bounds).
    others = [name for name in effects if name != "stribeck"]
    matrix = np.column_stack(
        [c[rows] for c in design(others, features, None).values()] or [np.zeros(int(rows.sum()))]
    )
    target, sign, speed = features.force[rows], features.sign[rows], np.abs(features.v[rows])
    gram, moment = matrix.T @ matrix, matrix.T @ target

    def cost(p: FloatArray) -> float:
        column = sign * np.exp(-((speed / np.exp(np.clip(p[0], *bounds))) ** np.clip(p[1], *DELTA_RANGE)))
        cross = matrix.T @ column
        system = np.block([[gram, cross[:, None]], [cross[None, :], np.array([[column @ column]])]])
        right = np.append(moment, column @ target)
        theta = np.linalg.lstsq(system, right, rcond=None)[0]
        return float(target @ target - theta @ right)  # the residual sum of squares

    grid = [np.array([np.log(vs), delta]) for vs in np.geomspace(low, high, 8) for delta in (1.0, 2.0)]
    start = min(grid, key=cost)
    result = minimize(cost, start, method="Nelder-Mead", options={"xatol": 1e-3, "fatol": 1e-9, "maxfev": 80})
    return Shape(float(np.exp(np.clip(result.x[0], *bounds))), float(np.clip(result.x[1], *DELTA_RANGE)))
