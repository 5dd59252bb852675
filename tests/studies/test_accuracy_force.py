"""The force-driven accuracy case (leuven_rt.studies.accuracy.force_accuracy): a mass on the LuGre-like
friction of docs/model.md#accuracy-of-the-schemes, pushed by a 2 N, 5 Hz sine, against the implicit
step 100× finer.

Measured (1 s, refine 100): implicit 21.3 %, 4.73 %, 0.481 % of Fs at 100 Hz, 1 kHz, 10 kHz;
explicit diverges at 100 Hz and 1 kHz (its friction step's stability number dt·|v|·σ0/Fc reaches
44.7 and 4.47) and is 0.791 % at 10 kHz.
"""

from __future__ import annotations

import math

import pytest

from leuven_rt.studies.accuracy import (
    MassAccuracyRow,
    force_accuracy,
    force_report,
    format_force_table,
    full_report,
)

RATES = (100.0, 1000.0, 10000.0)


@pytest.fixture(scope="module")
def rows() -> dict[tuple[float, str], MassAccuracyRow]:
    return {(row.rate_hz, row.scheme): row for row in force_accuracy(RATES, refine=100)}


def test_implicit_is_within_10_percent_of_fs_at_1_khz(rows: dict[tuple[float, str], MassAccuracyRow]) -> None:
    assert rows[(1000.0, "implicit")].rms_error_relative_to_Fs < 0.10


def test_implicit_converges_with_the_rate(rows: dict[tuple[float, str], MassAccuracyRow]) -> None:
    errors = [rows[(rate, "implicit")].rms_error for rate in RATES]
    positions = [rows[(rate, "implicit")].rms_position_error for rate in RATES]
    assert errors[1] < errors[0] / 3 and errors[2] < errors[1] / 5
    assert positions[1] < positions[0] / 5 and positions[2] < positions[1] / 5


def test_explicit_diverges_where_its_stability_numbers_exceed_2(
    rows: dict[tuple[float, str], MassAccuracyRow],
) -> None:
    assert rows[(100.0, "explicit")].diverged and rows[(1000.0, "explicit")].diverged
    explicit = rows[(10000.0, "explicit")]
    assert not explicit.diverged and explicit.rms_error_relative_to_Fs < 0.02
    assert math.isinf(rows[(100.0, "explicit")].rms_position_error)


def test_table_and_reports() -> None:
    rows = force_accuracy((1000.0,), refine=10, duration=0.2)
    table = format_force_table(rows).splitlines()
    assert table[0].startswith("| rate [Hz] | scheme | RMS force error [N]") and len(table) == 4
    assert "| 1000 | explicit | diverged | diverged | diverged | diverged |" in table
    text = force_report((1000.0,), refine=10)
    assert "Force-driven scenario" in text and "dt*max|v|*sigma0/Fc = 4.47" in text
    assert full_report().count("| rate [Hz] | scheme |") == 3  # two velocity-driven tables, one force-driven


def test_bad_refine_and_duration_are_value_errors() -> None:
    with pytest.raises(ValueError, match="refine"):
        force_accuracy((1000.0,), refine=1)
    with pytest.raises(ValueError, match="duration"):
        force_accuracy((1000.0,), duration=0.0005)
