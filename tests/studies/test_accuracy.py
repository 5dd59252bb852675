"""The explicit-vs-implicit accuracy claim of docs/model.md#accuracy-of-the-schemes, measured by
leuven_rt.studies.accuracy.

What is asserted is what holds for the scenario of docs/model.md#accuracy-of-the-schemes
(σ0 = 1e5 N/m, 10 mm/s at 5 Hz): the implicit step is accurate at 1 kHz and converges as the rate
grows, and the explicit step blows up where its stability number dt·|v|·σ0/g(v) exceeds 2. At
1 kHz that number peaks at exactly 1, so forward Euler is stable there and about as accurate as
backward Euler; a "10× better at 1 kHz" assertion would fail on a correct implementation and is not made.
"""

from __future__ import annotations

import dataclasses
import math

import pytest

from leuven_rt.studies.accuracy import LUGRE, AccuracyRow, format_table, step_accuracy

RATES = (100.0, 1000.0, 10000.0)


@pytest.fixture(scope="module")
def rows() -> dict[tuple[float, str], AccuracyRow]:
    # The whole 1 s table takes well under a second (the finest run is 1e6 Rust steps).
    return {(row.rate_hz, row.scheme): row for row in step_accuracy(RATES, refine=100)}


def test_implicit_is_within_5_percent_of_fs_at_1_khz(rows: dict[tuple[float, str], AccuracyRow]) -> None:
    implicit = rows[(1000.0, "implicit")]
    assert implicit.rms_error_relative_to_Fs < 0.05
    assert math.isclose(implicit.rms_error_relative_to_Fs, implicit.rms_error / 1.5)


def test_implicit_error_shrinks_as_the_rate_grows(rows: dict[tuple[float, str], AccuracyRow]) -> None:
    errors = [rows[(rate, "implicit")].rms_error for rate in RATES]
    assert errors[0] > errors[1] > errors[2]
    # Backward Euler is first order: 10× the rate should give close to 10× less error.
    assert errors[1] < errors[0] / 5 and errors[2] < errors[1] / 5


def test_explicit_blows_up_where_it_is_unstable(rows: dict[tuple[float, str], AccuracyRow]) -> None:
    # At 100 Hz the stability number reaches 10: forward Euler grows without bound (or raises
    # DivergenceError, reported as inf) while backward Euler stays within a couple of Fs.
    explicit, implicit = rows[(100.0, "explicit")], rows[(100.0, "implicit")]
    assert implicit.rms_error < 1.5
    assert explicit.diverged or explicit.rms_error > 10 * implicit.rms_error


def test_diverged_runs_are_rows_not_errors() -> None:
    # σ0 = 1e20 N/m at 30 Hz: the explicit state overflows and the core raises DivergenceError.
    # The table must still come, with that row marked diverged and the implicit row finite.
    stiff = dataclasses.replace(LUGRE, sigma0=1e20)
    rows = step_accuracy((30.0,), refine=10, params=stiff)
    explicit, implicit = rows
    assert explicit.diverged and math.isinf(explicit.max_error)
    assert not implicit.diverged and math.isfinite(implicit.rms_error)
    assert "| 30 | explicit | diverged | diverged | diverged |" in format_table(rows)


def test_unstable_finite_runs_do_not_overflow() -> None:
    # Explicit at 100 Hz grows to ~1e65 N without reaching inf: its RMS must be finite and
    # consistent with its max (squaring unscaled errors would overflow, a warning = error here).
    explicit = step_accuracy((100.0,))[0]
    assert math.isfinite(explicit.rms_error) and explicit.rms_error > 1e6
    assert explicit.rms_error <= explicit.max_error


def test_rows_come_rate_by_rate_explicit_first() -> None:
    rows = step_accuracy((1000.0,), refine=10, duration=0.1)
    assert [(row.rate_hz, row.scheme) for row in rows] == [(1000.0, "explicit"), (1000.0, "implicit")]
    table = format_table(rows).splitlines()
    assert table[0].startswith("| rate [Hz] | scheme |") and len(table) == 4


def test_bad_refine_and_duration_are_value_errors() -> None:
    with pytest.raises(ValueError, match="refine"):
        step_accuracy((1000.0,), refine=1)
    with pytest.raises(ValueError, match="duration"):
        step_accuracy((1000.0,), duration=0.0005)
