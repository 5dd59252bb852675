"""`leuven_rt.fitting.sensitivities` and `simulate_sets` against `leuven_rt.simulate`.

The derivatives must equal central finite differences of `leuven_rt.simulate` (or
`simulate_position`) to 1e-6 of the largest derivative of each column, on seeded random
parameter sets, wherever no element changes between sticking and slipping between the two runs
of a difference (seen by stepping a `LeuvenModel` and reading its state); within what the
differences resolve, a few ε·(max|F| + K·max|z|)/h, since the core rounds z⁺ to an ulp of z.
The forces must equal `simulate`'s bit for bit.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest

import leuven_rt
from conftest import LUGRE, MAXWELL
from leuven_rt import DivergenceError, InputError, LeuvenModel, ParameterError, Params
from leuven_rt.fitting import Sensitivities, sensitivities, simulate_sets

SHARED = ("Fc", "Fs", "Vs", "delta", "n", "sigma1", "sigma2", "Fc_neg", "Fs_neg", "sigma2_neg")
TOLERANCE = 1e-6
STEP = 1e-6
ROUNDING = 8.0


@dataclass(frozen=True)
class Case:
    """A model in column order (the asymmetric parameterisation) and a signal for it."""

    values: np.ndarray
    delta: np.ndarray  # empty for a linear spring
    signal: np.ndarray
    dt: float
    input: str
    scheme: str

    @property
    def linear(self) -> bool:
        return self.delta.size == 0

    def params(self, values: np.ndarray | None = None) -> Params:
        v = self.values if values is None else values
        keys = dict(zip(SHARED, v[:10].tolist(), strict=True))
        if self.linear:
            return Params(**keys, sigma0=float(v[10]))
        return Params(**keys, W=v[10:].tolist(), Delta=self.delta.tolist())

    def stiffness(self) -> float:
        own = self.values[10:]
        return float(own[0]) if self.linear else float(np.sum(own / self.delta))

    def simulate(self, params: Params) -> np.ndarray:
        run = leuven_rt.simulate if self.input == "velocity" else leuven_rt.simulate_position
        return run(params, self.signal, self.dt, self.scheme)


def make_case(seed: int, elements: int, n: float, scheme: str, input: str, symmetric: bool) -> Case:
    rng = np.random.default_rng(seed)
    fc, ratio = rng.uniform(0.5, 2.0), rng.uniform(1.1, 2.0)
    fc_neg, ratio_neg = (fc, ratio) if symmetric else (rng.uniform(0.5, 2.0), rng.uniform(1.1, 2.0))
    vs = 10 ** rng.uniform(-2.7, -1.7)
    sigma2 = 10 ** rng.uniform(-1.3, 0.7)
    values = [fc, fc * ratio, vs, rng.uniform(0.6, 2.5), n, 10 ** rng.uniform(0, 2), sigma2,
              fc_neg, fc_neg * ratio_neg, sigma2]  # fmt: skip
    peak = max(fc * ratio, fc_neg * ratio_neg)
    if elements == 0:
        delta = np.zeros(0)
        own = [peak / 1e-5]
    else:
        delta = 10 ** rng.uniform(-6, -4, elements)
        weights = rng.uniform(0.2, 1.0, elements)
        own = (weights / weights.sum() * peak * rng.uniform(1.3, 3.0)).tolist()
    dt = 10 ** rng.uniform(-4, -3)
    width = max(float(delta.max()) if delta.size else 1e-5, 1e-5)
    pieces = []
    for _ in range(4):
        kind = rng.integers(3)
        if kind == 0:  # sliding, with reversals
            half, halves = int(rng.integers(40, 120)), int(rng.integers(1, 3))
            pieces.append(
                rng.choice([-1, 1])
                * rng.uniform(0.3, 5)
                * vs
                * np.sin(np.pi * np.arange(half * halves) / half)
            )
        elif kind == 1:  # a dwell at exactly v = 0
            pieces.append(np.zeros(int(rng.integers(5, 30))))
        else:  # presliding loops within the widest windows
            period, loops = int(rng.integers(20, 60)), int(rng.integers(1, 4))
            omega = 2 * np.pi / period
            amplitude = 0.5 * rng.uniform(0.1, 1.0) * width * omega / dt
            pieces.append(amplitude * np.cos(omega * np.arange(period * loops)))
    velocity = np.concatenate(pieces)
    values_array = np.array(values + own)
    if not symmetric:  # drawn last, so that the other draws of a seed stay as they were
        values_array[9] = 10 ** rng.uniform(-1.3, 0.7)
    if scheme == "explicit":  # a step fine enough for forward Euler: dt·|v|·K/g ≤ 0.5
        stiffness = own[0] if elements == 0 else float(np.sum(np.array(own) / delta))
        number = dt * np.max(np.abs(velocity)) * stiffness / min(fc, fc_neg)
        repeats = int(np.ceil(number / 0.5)) if number > 0.5 else 1
        velocity, dt = np.repeat(velocity, repeats), dt / repeats
    signal = velocity if input == "velocity" else 0.25 + np.cumsum(velocity) * dt
    return Case(values_array, delta, signal, dt, input, scheme)


def ways(case: Case, params: Params) -> np.ndarray:
    """For every step and element: -1 sticking, +1 slipping, 0 within a few ulps of the edge
    (either side, by rounding), at z⁺ and, for the explicit step, at z; by stepping the model."""
    model = LeuvenModel(params, scheme=case.scheme)
    step = model.step if case.input == "velocity" else model.step_position
    out = []
    state = model.state
    for sample in case.signal:
        z, zeta = float(state.z[0]), state.zeta[0].copy()
        step(float(sample), case.dt)
        state = model.state
        z_next = float(state.z[0])
        for y in (z_next, z) if case.scheme == "explicit" else (z_next,):
            deviation = np.abs(y - zeta)
            margin = 16 * np.finfo(float).eps * np.maximum(abs(y), case.delta)
            out.append(
                np.where(deviation < case.delta - margin, -1, np.where(deviation > case.delta + margin, 1, 0))
            )
    return np.array(out)


def differ(a: np.ndarray, b: np.ndarray) -> bool:
    return bool(np.any(a * b < 0))  # one sticks where the other slips


def velocities(case: Case) -> np.ndarray:
    if case.input == "velocity":
        return case.signal
    return np.concatenate([[0.0], np.diff(case.signal) / case.dt])


def check(case: Case) -> int:
    """Compares every column with central differences; returns how many were compared."""
    params = case.params()
    result = sensitivities(params, case.signal, case.dt, input=case.input, scheme=case.scheme)
    assert isinstance(result, Sensitivities)
    force, jacobian, columns = result
    expected = case.simulate(params)
    np.testing.assert_array_equal(force, expected, strict=True)
    assert jacobian.shape == (case.signal.size, case.values.size)
    assert columns[:10] == SHARED
    assert len(columns) == case.values.size
    v = velocities(case)
    np.testing.assert_array_equal(jacobian[:, 6], np.where(v < 0, 0.0, v))
    np.testing.assert_array_equal(jacobian[:, 9], np.where(v < 0, v, 0.0))
    base_ways = ways(case, params) if not case.linear else None
    model = LeuvenModel(params, scheme=case.scheme)
    largest_z = 0.0
    step = model.step if case.input == "velocity" else model.step_position
    for sample in case.signal:
        step(float(sample), case.dt)
        largest_z = max(largest_z, abs(float(model.state.z[0])))
    scale = float(np.max(np.abs(expected))) + case.stiffness() * largest_z
    compared = 0
    for j in range(case.values.size):
        h = STEP * abs(case.values[j])
        moved = []
        for sign in (1.0, -1.0):
            values = case.values.copy()
            values[j] += sign * h
            moved.append(case.params(values))
        if base_ways is not None:
            plus_ways, minus_ways = ways(case, moved[0]), ways(case, moved[1])
            if differ(plus_ways, minus_ways) or differ(plus_ways, base_ways):
                continue
        difference = (case.simulate(moved[0]) - case.simulate(moved[1])) / (2 * h)
        derivative = jacobian[:, j]
        largest = float(np.max(np.abs(derivative)))
        allowed = TOLERANCE * largest + ROUNDING * np.finfo(float).eps * scale / h
        worst = float(np.max(np.abs(derivative - difference)))
        assert worst <= allowed, f"column {columns[j]}: {worst:.3g} off, {allowed:.3g} allowed"
        compared += 1
    return compared


CASES = [
    # seed, N (0: linear spring), n, scheme, input, symmetric
    (1, 1, 1.0, "implicit", "velocity", False),
    (2, 3, 2.0, "implicit", "position", True),
    (3, 10, 1.5, "implicit", "velocity", True),
    (4, 20, 3.0, "implicit", "position", False),
    (5, 10, 2.0, "implicit", "position", False),
    (6, 0, 1.0, "implicit", "velocity", False),
    (7, 3, 1.0, "explicit", "velocity", False),
    (8, 3, 3.0, "explicit", "position", True),
    (9, 10, 1.5, "explicit", "velocity", False),
    (10, 0, 1.0, "explicit", "position", True),
]


@pytest.mark.parametrize(("seed", "elements", "n", "scheme", "input", "symmetric"), CASES)
def test_derivatives_equal_central_differences(
    seed: int, elements: int, n: float, scheme: str, input: str, symmetric: bool
) -> None:
    case = make_case(seed, elements, n, scheme, input, symmetric)
    compared = check(case)
    assert 2 * compared >= case.values.size, f"only {compared} columns kept their ways under ±h"


@pytest.mark.parametrize("params", [MAXWELL, LUGRE], ids=["maxwell", "lugre"])
@pytest.mark.parametrize("scheme", ["implicit", "explicit"])
def test_rows_pick_out_the_rows_of_the_whole_jacobian(params: dict[str, Any], scheme: str) -> None:
    v = 0.01 * np.sin(2 * np.pi * 5 * np.arange(500) * 1e-3)
    whole = sensitivities(params, v, 1e-3, scheme=scheme)
    rows = [0, 3, 4, 250, 499]
    for given in (rows, np.array(rows, dtype=np.int32), np.array(rows, dtype=np.uint64)):
        some = sensitivities(params, v, 1e-3, scheme=scheme, rows=given)
        np.testing.assert_array_equal(some.force, whole.force, strict=True)
        np.testing.assert_array_equal(some.jacobian, whole.jacobian[rows], strict=True)
        assert some.columns == whole.columns
    none = sensitivities(params, v, 1e-3, scheme=scheme, rows=[])
    assert none.jacobian.shape == (0, len(whole.columns))
    np.testing.assert_array_equal(whole.force, leuven_rt.simulate(params, v, 1e-3, scheme), strict=True)
    own = [f"W[{i}]" for i in range(len(params["W"]))] if "W" in params else ["sigma0"]
    assert whole.columns == (*SHARED, *own)


def test_many_sets_are_each_sets_run() -> None:
    v = 0.01 * np.sin(2 * np.pi * 5 * np.arange(400) * 1e-3)
    x = 0.1 + np.cumsum(v) * 1e-3
    sets: list[Any] = [
        Params(**MAXWELL),
        LUGRE,
        {**MAXWELL, "W": [0.6, 0.6, 0.6], "Delta": [1e-6, 3e-6, 9e-6]},
    ]
    for scheme in ("implicit", "explicit"):
        forces = simulate_sets(sets, v, 1e-3, scheme=scheme)
        assert forces.shape == (3, 400)
        for row, params in zip(forces, sets, strict=True):
            np.testing.assert_array_equal(row, leuven_rt.simulate(params, v, 1e-3, scheme), strict=True)
        positions = simulate_sets(sets, x, 1e-3, input="position", scheme=scheme)
        for row, params in zip(positions, sets, strict=True):
            expected = leuven_rt.simulate_position(params, x, 1e-3, scheme)
            np.testing.assert_array_equal(row, expected, strict=True)
    assert simulate_sets([], v, 1e-3).shape == (0, 400)


def refused(error_class: type[Exception], call: Any) -> Any:
    """The error ``call()`` raises, which must be of ``error_class``."""
    with pytest.raises(error_class) as caught:
        call()
    return caught.value


def test_refusals_name_the_argument_and_carry_their_data() -> None:
    v = 0.01 * np.sin(np.arange(50) * 0.1)
    cases: list[tuple[type[Exception], Any, str, dict[str, Any]]] = [
        (InputError, lambda: sensitivities(MAXWELL, v, 1e-3, rows=[1, 3, 3]),
         "`rows` must be strictly increasing, got rows[2] = 3 after rows[1] = 3",
         dict(kind="not_increasing", field="rows[2]", index=2, value=3, bound=3)),
        (InputError, lambda: sensitivities(MAXWELL, v, 1e-3, rows=[0, 50]),
         "`rows` must be samples of the signal, below its length 50, got rows[1] = 50",
         dict(kind="out_of_range", field="rows[1]", index=1, value=50, bound=50)),
        (InputError, lambda: sensitivities(MAXWELL, v, 1e-3, rows=np.array([4, 2**63], dtype=np.uint64)),
         "`rows` must be samples of the signal, below its length 50, got rows[1] = 9223372036854775808",
         dict(kind="out_of_range", field="rows[1]", index=1, value=2**63, bound=50)),
        (InputError, lambda: sensitivities(MAXWELL, v, 1e-3, rows=[-1, 2]),
         "`rows` must be sample indices >= 0, got rows[0] = -1",
         dict(kind="out_of_range", field="rows[0]", index=0, value=-1, bound=0)),
        (InputError, lambda: sensitivities(MAXWELL, v, 1e-3, rows=[1.0, 2.0]),
         "`rows` must be integer sample indices, got dtype float64",
         dict(kind="not_integer", field="rows", value="float64")),
        (InputError, lambda: sensitivities(MAXWELL, v, 1e-3, rows=[True]),
         "`rows` must be integer sample indices, got dtype bool",
         dict(kind="not_integer", field="rows", value="bool")),
        (InputError, lambda: sensitivities(MAXWELL, v, 1e-3, rows="1"),
         "`rows` must be integer sample indices, got str",
         dict(kind="not_integer", field="rows", value="1")),
        (InputError, lambda: sensitivities(MAXWELL, v, 1e-3, rows=[[1, 2]]),
         "`rows` must have shape (R,), got shape (1, 2)",
         dict(kind="shape", field="rows", expected="(R,)", got=(1, 2))),
        (InputError, lambda: sensitivities(MAXWELL, v, 1e-3, input="force"),
         "`input` must be 'velocity' or 'position', got 'force'",
         dict(kind="invalid_choice", field="input", value="force", expected=("velocity", "position"))),
        (InputError, lambda: sensitivities(MAXWELL, v, 1e-3, scheme="rk4"),
         "`scheme` must be 'implicit' or 'explicit', got 'rk4'",
         dict(kind="invalid_choice", field="scheme", value="rk4")),
        (InputError, lambda: sensitivities(MAXWELL, np.stack([v, v]), 1e-3),
         "`signal` must have shape (T,), got shape (2, 50)",
         dict(kind="shape", field="signal", expected="(T,)", got=(2, 50))),
        (InputError, lambda: sensitivities(MAXWELL, np.where(np.arange(50) == 7, np.nan, v), 1e-3),
         "`v` must be finite, got nan at sample 7",
         dict(kind="not_finite", field="v", sample=7)),
        (InputError, lambda: sensitivities(MAXWELL, v, 0.0),
         "`dt` must be finite and > 0, got 0.0",
         dict(kind="not_positive", field="dt", value=0.0)),
        (ParameterError, lambda: sensitivities({**MAXWELL, "Fc": -1.0}, v, 1e-3),
         "`Fc` must be finite and > 0",
         dict(kind="not_positive", field="Fc", value=-1.0)),
    ]  # fmt: skip
    for error_class, call, message, data in cases:
        error = refused(error_class, call)
        assert str(error).startswith(message), str(error)
        for name, value in data.items():
            assert getattr(error, name) == value, (message, name, getattr(error, name))
    # LuGre by forward Euler at 100 Hz: ten times past its stability limit.
    sine = 0.01 * np.sin(2 * np.pi * 5 * np.arange(1000) * 1e-2)
    diverged = refused(DivergenceError, lambda: sensitivities(LUGRE, sine, 1e-2, scheme="explicit"))
    assert diverged.kind == "diverged" and isinstance(diverged.sample, int)
    assert f"diverged at sample {diverged.sample}" in str(diverged)


def test_refusals_of_many_sets_name_the_set() -> None:
    v = 0.01 * np.sin(np.arange(50) * 0.1)
    bad_set = refused(ParameterError, lambda: simulate_sets([MAXWELL, {**MAXWELL, "Fs": 0.5}], v, 1e-3))
    assert str(bad_set).startswith("params[1]: `Fs` must be >= `Fc`")
    assert (bad_set.kind, bad_set.field, bad_set.value, bad_set.channel) == (
        "static_below_coulomb",
        "Fs",
        0.5,
        1,
    )
    not_sets = refused(ParameterError, lambda: simulate_sets(Params(**MAXWELL), v, 1e-3))  # type: ignore[arg-type]
    assert str(not_sets) == "`params` must be a sequence of parameter sets, got Params"
    assert (not_sets.kind, not_sets.field) == ("wrong_type", "params")
    bad = v.copy()
    bad[4] = np.inf
    run = refused(InputError, lambda: simulate_sets([MAXWELL, LUGRE], bad, 1e-3))
    assert str(run) == "parameter set 0: `v` must be finite, got inf at sample 4"
    assert (run.kind, run.field, run.sample, run.channel) == ("not_finite", "v", 4, 0)
