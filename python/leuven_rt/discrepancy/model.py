"""A friction model as a set of catalogue effects, fitted by linear least squares on chosen rows.

The columns of a design are put on the fitted rows once, with their normal equations per
cross-validation block (:mod:`.normal`): every fit on a union of blocks solves the summed Gram
matrix (bounded at 0 where the effect asks, as the identification's :func:`fit_linear` does).
With ``stribeck`` in the model, its shape (Vs, δ) is fitted by variable projection: for each
trial shape the linear coefficients are solved exactly (plain least squares, the other columns'
normal equations formed once), and ``scipy.optimize.least_squares`` (trust region, bounded)
moves (log Vs, δ) with the analytic Jacobian of the projected residual, started from the best of
a grid over the speeds. With ``presliding_hysteresis``, the bank's drive (:mod:`.drive`) is
fitted by fixed-point iteration for each exponent n tried: the weights fitted on the bank driven
by z give the z of the next pass, starting from the bank driven by x; the fit with the smallest
residual is kept.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import least_squares

from .._typing import FloatArray
from ..data.slip import element_deflections
from .drive import EXPONENTS, Drive
from .effects import TERMS, Shape, shape_columns
from .features import Features
from .normal import Normal, spans

Rows = NDArray[np.bool_]

#: Bounds of the Stribeck exponent δ searched.
DELTA_RANGE = (0.5, 4.0)
#: Fixed-point passes of the presliding drive for each exponent n.
DRIVE_PASSES = 2
#: Most residual evaluations of the Stribeck shape's least squares (after the grid).
SHAPE_EVALUATIONS = 40
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
    driven: tuple[Features, Features] | None = field(default=None, repr=False)
    """The features the fit was made on and the same driven by ``drive``: predicting on them
    again needs no simulation."""

    def predict(self, features: Features) -> FloatArray:
        if self.drive is None:
            return self.predict_columns(features)
        if self.driven is not None and self.driven[0] is features:
            return self.predict_columns(self.driven[1])
        return self.predict_columns(self.drive.apply(features))

    def predict_by_element(self, features: Features) -> FloatArray:
        """:meth:`predict`, the bank driven by the model's z made one element at a time and added
        into the prediction: no bank of every sample (for the residuals of a long record, where
        that bank was the memory peak)."""
        if self.drive is None:
            return self.predict(features)
        z = self.drive.deflection(features)
        deflections = features.scales.deflections
        unbanked = dataclasses.replace(features, bank=np.empty((features.force.size, 0)))
        prediction = np.zeros_like(features.force)
        for name in self.effects:
            if name == PRESLIDING:
                for j in range(deflections.size):
                    column = element_deflections(z, deflections[j : j + 1])[:, 0]
                    prediction += self.coefficients.get(f"W{j + 1}", 0.0) * column
                continue
            for column_name, column in TERMS[name].columns(unbanked, self.effects, self.shape).items():
                prediction += self.coefficients.get(column_name, 0.0) * column
        return prediction

    def predict_columns(self, features: Features) -> FloatArray:
        """The prediction on ``features`` as they are (already driven)."""
        prediction = np.zeros_like(features.force)
        for name in self.effects:  # effect by effect: only one effect's columns at a time
            for column_name, column in TERMS[name].columns(features, self.effects, self.shape).items():
                # a column the fitted samples did not have (Fc_rest, rest too short there) is 0
                prediction += self.coefficients.get(column_name, 0.0) * column
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


class Design:
    """``effects`` on ``features``: the columns that do not depend on the Stribeck shape put on
    ``rows`` once, with their normal equations per block of ``blocks`` (subsets of ``rows``)."""

    def __init__(self, effects: tuple[str, ...], features: Features, rows: Rows, blocks: Sequence[Rows]):
        if not effects:
            raise ValueError("a design needs at least one effect")
        self.effects, self.features, self.rows, self.blocks = effects, features, rows, blocks
        self.spans = spans(rows, blocks)
        fixed = tuple(name for name in effects if name != "stribeck")
        columns: dict[str, FloatArray] = {}
        self.groups: dict[str, tuple[str, ...]] = {}
        for name in fixed:  # the columns, and the names of each effect's, made once
            made = TERMS[name].columns(features, fixed, None)
            self.groups[name] = tuple(made)
            columns.update(made)
        if "stribeck" in effects:
            self.groups["stribeck"] = ("Fs_minus_Fc",)
            if "asymmetry" in effects:
                self.groups["asymmetry"] = (*self.groups["asymmetry"], "Fs_neg_shift")
        self.groups = {name: self.groups[name] for name in effects}
        self.normal = Normal.build(columns, features.force, rows, blocks) if columns else None
        self.nonnegative = {column for name in effects for column in TERMS[name].nonnegative}

    def fit(
        self, use: Sequence[int], drive: Drive | None = None, shape: Shape | None = None
    ) -> tuple[ModelFit, Normal]:
        """The fit on the blocks ``use`` (the Stribeck shape fitted there unless given), and the
        normal equations it was solved from (for its predictions on any block)."""
        normal = self.normal
        if "stribeck" in self.effects:
            if shape is None:
                shape = _fit_shape(self, use)
            added = shape_columns(self.features, self.effects, shape)
            if normal is None:
                normal = Normal.build(added, self.features.force, self.rows, self.blocks)
            else:
                normal = normal.extend(added, self.rows)
        assert normal is not None
        periods = self.features.scales.periods
        coefficients, errors = normal.solve(use, self.nonnegative)
        fit = ModelFit(self.effects, coefficients, self.groups, shape, drive, periods, errors)
        return fit, normal


def fit_model(effects: Sequence[str], features: Features, rows: Rows, drive: Drive | None = None) -> ModelFit:
    """Coefficients (and the Stribeck shape, and the presliding drive unless ``drive`` is given)
    of ``effects`` fitted on ``rows``."""
    effects = tuple(effects)
    if PRESLIDING in effects and drive is None:
        return fit_driven(effects, features, rows)
    if not effects:
        return ModelFit(effects, {}, {}, None, drive, features.scales.periods)
    driven = drive.apply(features) if drive is not None else features
    fit = Design(effects, driven, rows, [rows]).fit([0], drive)[0]
    if drive is not None:
        return _with_driven(fit, features, driven)
    return fit


def _with_driven(fit: ModelFit, features: Features, driven: Features) -> ModelFit:
    return ModelFit(fit.effects, fit.coefficients, fit.groups, fit.shape, fit.drive, fit.periods,
                    fit.standard_errors, (features, driven))  # fmt: skip


def _weights(fit: ModelFit) -> tuple[float, ...]:
    return tuple(max(fit.coefficients[name], 0.0) for name in fit.groups[PRESLIDING])


def fit_driven(effects: tuple[str, ...], features: Features, rows: Rows) -> ModelFit:
    """The best fit over the exponents tried, each after DRIVE_PASSES fixed-point passes; the
    bank stays driven by x when the fit gives no element a positive weight. The fit keeps the
    driven features (:attr:`ModelFit.driven`)."""
    undriven = Design(effects, features, rows, [rows]).fit([0])[0]
    start = _weights(undriven)
    if max(start) <= 0.0:
        return undriven
    # The Stribeck shape is held at the undriven fit's while the drive is searched (the shape
    # search costs more than a drive pass), then fitted again with the drive chosen. Only the
    # best pass is kept (each holds a bank of the record's length).
    best: tuple[float, ModelFit, Features] | None = None
    for n in EXPONENTS:
        drive = Drive(n, start)
        for _ in range(DRIVE_PASSES):
            driven = drive.apply(features)
            fit, normal = Design(effects, driven, rows, [rows]).fit([0], drive, undriven.shape)
            theta = np.array([fit.coefficients[name] for name in normal.names])
            residual = normal.residual(theta, 0)
            error = float(residual @ residual)
            if best is None or error < best[0]:
                best = (error, fit, driven)
            weights = _weights(fit)
            if max(weights) <= 0.0:
                break
            drive = Drive(n, weights)
    assert best is not None
    _, chosen, driven = best
    if chosen.shape is not None:
        chosen = Design(effects, driven, rows, [rows]).fit([0], chosen.drive)[0]
    return _with_driven(chosen, features, driven)


def _fit_shape(design_: Design, use: Sequence[int]) -> Shape:
    """The Stribeck shape fitted on the blocks ``use`` of ``design_`` (variable projection)."""
    features, rows = design_.features, design_.rows
    normal = design_.normal
    weight = np.zeros(int(np.count_nonzero(rows)))
    for block in use:
        weight[design_.spans[block]] = 1.0
    fitted = np.zeros(features.force.size, dtype=bool)
    fitted[np.flatnonzero(rows)[weight > 0.0]] = True
    # Vs is searched within the speeds the data visits (moving samples only).
    speeds = np.abs(features.v[fitted & (features.travel > features.scales.deflections[-1])])
    high = float(np.percentile(speeds, 95))
    low = max(float(np.percentile(speeds, 2)), 1e-3 * high)
    bounds = np.log([low, high])

    # Only the Stribeck column moves with the shape: the other columns' normal equations are
    # formed once (summed over the blocks), and each trial adds one row and column.
    if normal is not None:
        matrix = np.column_stack(normal.parts) if len(normal.parts) > 1 else normal.parts[0]
        gram, moment = normal.gram[list(use)].sum(axis=0), normal.moment[list(use)].sum(axis=0)
        target = normal.target
    else:
        matrix = np.zeros((weight.size, 1))
        gram, moment = np.zeros((1, 1)), np.zeros(1)
        target = np.ascontiguousarray(features.force[rows])
    square = float((weight * target) @ target)
    sign, speed = features.sign[rows], np.abs(features.v[rows])
    moving = speed > 0.0
    log_speed = np.log(np.where(moving, speed, 1.0))

    def project(p: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """The Stribeck column, u = (|v|/Vs)^δ, the coefficients and the solved system's right side."""
        u = np.where(moving, np.exp(p[1] * (log_speed - p[0])), 0.0)
        column = sign * np.exp(-u)
        weighted = weight * column
        cross = matrix.T @ weighted
        system = np.block([[gram, cross[:, None]], [cross[None, :], np.array([[weighted @ column]])]])
        right = np.append(moment, weighted @ target)
        theta = np.linalg.lstsq(system, right, rcond=None)[0]
        return column, u, theta, right

    def cost(p: FloatArray) -> float:
        _, _, theta, right = project(p)
        return float(square - theta @ right)  # the residual sum of squares

    cache: dict[bytes, tuple[FloatArray, FloatArray, FloatArray, FloatArray]] = {}

    def solved(p: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        key = np.asarray(p, dtype=np.float64).tobytes()
        if key not in cache:
            cache.clear()
            cache[key] = project(p)
        return cache[key]

    def residual(p: FloatArray) -> FloatArray:
        column, _, theta, _ = solved(p)
        out: FloatArray = weight * (target - matrix @ theta[:-1] - theta[-1] * column)
        return out

    def jacobian(p: FloatArray) -> FloatArray:
        # Kaufman's variable projection Jacobian: −P⊥·(∂column/∂p)·θ_stribeck, P⊥ the projection
        # off the columns (the Stribeck column included) on the fitted rows.
        column, u, theta, _ = solved(p)
        derivatives = np.column_stack(
            [column * u * p[1], -column * u * np.where(moving, log_speed - p[0], 0.0)]
        )
        weighted = weight[:, None] * derivatives
        full_gram = np.block([[gram, (matrix.T @ (weight * column))[:, None]],
                              [(matrix.T @ (weight * column))[None, :],
                               np.array([[(weight * column) @ column]])]])  # fmt: skip
        moments = np.vstack([matrix.T @ weighted, column @ weighted])
        coefficients = np.linalg.lstsq(full_gram, moments, rcond=None)[0]
        projected = derivatives - matrix @ coefficients[:-1] - np.outer(column, coefficients[-1])
        out: FloatArray = -theta[-1] * weight[:, None] * projected
        return out

    grid = [np.array([np.log(vs), delta]) for vs in np.geomspace(low, high, 8) for delta in (1.0, 2.0)]
    start = np.clip(min(grid, key=cost), (bounds[0], DELTA_RANGE[0]), (bounds[1], DELTA_RANGE[1]))
    if not bounds[0] < bounds[1]:
        return Shape(float(np.exp(start[0])), float(start[1]))
    result = least_squares(residual, start, jac=jacobian,
                           bounds=((bounds[0], DELTA_RANGE[0]), (bounds[1], DELTA_RANGE[1])),
                           method="trf", max_nfev=SHAPE_EVALUATIONS)  # fmt: skip
    best = result.x if cost(result.x) <= cost(start) else start
    return Shape(float(np.exp(np.clip(best[0], *bounds))), float(np.clip(best[1], *DELTA_RANGE)))
