"""Bad data for the data toolkit: each gets a DataError (an InputError, a ValueError) whose message
names the column or argument and says what was expected; non-uniform time stamps are resampled
with a ResamplingWarning, and a gap in the log is refused."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
import scipy.io

from conftest import SMALL_LOG_SAMPLES as SAMPLES
from conftest import small_log as columns
from leuven_rt import identify
from leuven_rt.data import MotionData, as_motion_data, fit_linear
from leuven_rt.errors import DataError, InputError, ResamplingWarning


def test_a_valid_log_is_accepted() -> None:
    data = as_motion_data(columns())
    assert data.samples == SAMPLES and data.dt == pytest.approx(1e-3)
    assert issubclass(DataError, InputError) and issubclass(DataError, ValueError)


@pytest.mark.parametrize(
    ("changes", "data"),
    [
        (
            {"t": np.arange(50) * 1e-3, "x": np.zeros(50), "f": np.zeros(50)},
            {"kind": "too_few", "value": 50, "bound": 200},
        ),
        (
            {"f": np.r_[np.ones(10), np.nan, np.ones(SAMPLES - 11)]},
            {"kind": "not_finite", "field": "f", "value": np.nan, "sample": 10},
        ),
        (
            {"x": np.r_[np.zeros(5), np.inf, np.zeros(SAMPLES - 6)]},
            {"kind": "not_finite", "field": "x", "value": np.inf, "sample": 5},
        ),
        (
            {"t": np.r_[np.arange(100), 50, np.arange(101, SAMPLES)] * 1e-3},
            {"kind": "not_increasing", "field": "t", "sample": 100, "value": 0.05, "bound": 0.099},
        ),
        ({"t": np.r_[0.0, np.zeros(SAMPLES - 1)]}, {"kind": "not_increasing", "field": "t", "sample": 1}),
        ({"f": None}, {"kind": "missing_column", "field": "f", "got": ["t", "x"]}),
        (
            {"f": np.ones(SAMPLES - 1)},
            {"kind": "input_length_mismatch", "field": "f", "expected": SAMPLES, "got": SAMPLES - 1},
        ),
        (
            {"f": 1e12 * np.ones(SAMPLES)},
            {"kind": "implausible_units", "field": "f", "value": 1e12, "bound": 1e7},
        ),
        ({"x": 1e4 * np.linspace(0, 1, SAMPLES)}, {"kind": "implausible_units", "field": "x", "value": 1e4}),
        ({"t": np.arange(SAMPLES) * 1e-9}, {"kind": "implausible_units", "field": "t"}),
        ({"x": np.linspace(0.0, 900.0, SAMPLES)}, {"kind": "implausible_units", "field": "x"}),
        ({"x": np.zeros(SAMPLES)}, {"kind": "no_motion", "field": "x"}),
        ({"f": np.ones((SAMPLES, 2))}, {"kind": "shape", "field": "f", "got": (SAMPLES, 2)}),
        ({"f": ["a"] * SAMPLES}, {"kind": "not_real", "field": "f"}),
        ({"f": np.ones(SAMPLES) * 1j}, {"kind": "not_real", "field": "f"}),
    ],
)
def test_bad_columns_are_refused(changes: dict[str, Any], data: dict[str, Any]) -> None:
    """Each refusal names the column (``field``), the rule (``kind``) and what came."""
    for load, cls in ((as_motion_data, DataError), (identify, DataError)):  # the same through identify
        with pytest.raises(cls) as refused:
            load(columns(**changes))
        got = {name: getattr(refused.value, name) for name in data}
        assert all(
            value == expected or (isinstance(value, float) and np.isnan(value) and np.isnan(expected))
            for value, expected in zip(got.values(), data.values(), strict=True)
        ), (got, data)


@pytest.mark.parametrize(
    ("changes", "match"),
    [
        (
            {"t": np.arange(50) * 1e-3, "x": np.zeros(50), "f": np.zeros(50)},
            r"too few samples: need at least 200, got 50",
        ),
        (
            {"f": np.r_[np.ones(10), np.nan, np.ones(SAMPLES - 11)]},
            r"column `f` must be finite, got nan at sample 10",
        ),
        (
            {"t": np.r_[np.arange(100), 50, np.arange(101, SAMPLES)] * 1e-3},
            r"`t` must strictly increase, got t\[99\] = 0\.099 followed by t\[100\] = 0\.05$",
        ),
        ({"f": None}, r"missing columns \['f'\]: expected `t` \[s\], `x` \[m\], `f` \[N\]"),
        (
            {"f": 1e12 * np.ones(SAMPLES)},
            r"column `f` reaches 1e\+12 N, beyond 1e\+07 N: expected SI units \(N\)",
        ),
        (
            {"t": np.arange(SAMPLES) * 1e-9},
            r"sampling step of `t` must be between .* got 1e-09: is `t` in seconds\?",
        ),
        ({"x": np.linspace(0.0, 900.0, SAMPLES)}, r"`x` moves at up to .* m/s .*expected `x` in m"),
    ],
)
def test_bad_column_messages_say_what_was_expected(changes: dict[str, Any], match: str) -> None:
    """Where the words are the point: units, the expected columns, the sample and its value."""
    with pytest.raises(DataError, match=match):
        as_motion_data(columns(**changes))


def test_non_uniform_sampling_is_resampled_with_a_warning() -> None:
    t = np.arange(SAMPLES) * 1e-3
    t[1::2] += 2e-4  # jitter of 20 % of the step
    with pytest.warns(
        ResamplingWarning, match=r"not uniformly sampled .* resampled linearly onto a uniform grid"
    ):
        data = as_motion_data(columns(t=t, x=np.sin(t), f=np.cos(t)))
    steps = np.diff(data.t)
    np.testing.assert_allclose(steps, steps[0], rtol=1e-9)
    np.testing.assert_allclose(data.x, np.sin(data.t), atol=1e-6)


def test_a_gap_in_the_log_is_refused() -> None:
    t = np.arange(SAMPLES) * 1e-3
    t[200:] += 0.5
    with pytest.raises(
        DataError, match=r"`t` has a gap of 0\.501 s after sample 199 .*split the log"
    ) as refused:
        as_motion_data(columns(t=t))
    assert (refused.value.kind, refused.value.field, refused.value.sample) == ("gap", "t", 199)
    assert refused.value.value == pytest.approx(0.501)


def test_motion_data_refuses_non_uniform_time_without_resampling() -> None:
    t = np.arange(SAMPLES) * 1e-3
    t[1::2] += 2e-4
    with pytest.raises(
        DataError, match=r"`t` must be uniformly sampled .*as_motion_data resamples"
    ) as refused:
        MotionData(t, np.sin(t), np.cos(t))
    assert (refused.value.kind, refused.value.field) == ("not_uniform", "t")


def test_files(tmp_path: Path) -> None:
    with pytest.raises(DataError, match=r"does not exist") as refused:
        as_motion_data(tmp_path / "missing.csv")
    assert (refused.value.kind, refused.value.value) == ("no_such_file", str(tmp_path / "missing.csv"))
    wrong = tmp_path / "log.txt"
    wrong.write_text("t,x,f\n", encoding="utf-8")
    with pytest.raises(DataError, match=r"must end in \.csv or \.mat, got 'log\.txt'") as refused:
        as_motion_data(wrong)
    assert (refused.value.kind, refused.value.got) == ("invalid_choice", ".txt")
    csv = tmp_path / "log.csv"
    np.savetxt(csv, np.column_stack((np.arange(SAMPLES) * 1e-3, np.ones(SAMPLES))), delimiter=",",
               header="t,x", comments="")  # fmt: skip
    with pytest.raises(DataError, match=r"missing columns \['f'\]") as refused:
        as_motion_data(csv)
    assert (refused.value.kind, refused.value.field) == ("missing_column", "f")
    assert str(refused.value).startswith(f"{csv}: ")  # the file is named, the data kept
    mat = tmp_path / "log.mat"
    scipy.io.savemat(mat, {"t": np.arange(SAMPLES) * 1e-3, "qm": np.ones(SAMPLES)})
    with pytest.raises(DataError, match=r"lacks the EMPS variables \['vir', 'gtau'\]") as refused:
        as_motion_data(mat)
    assert (refused.value.kind, refused.value.field) == ("missing_column", "vir")
    with pytest.raises(DataError, match=r"`data` must be a MotionData, a path .* got int") as refused:
        as_motion_data(3)  # type: ignore[arg-type]
    assert (refused.value.kind, refused.value.field, refused.value.value) == ("wrong_type", "data", 3)


def test_linear_fit_refuses_bad_regressors() -> None:
    with pytest.raises(DataError, match=r"regressor `a` must be finite") as refused:
        fit_linear({"a": np.array([1.0, np.nan, 2.0])}, np.ones(3))
    assert (refused.value.kind, refused.value.field) == ("not_finite", "a")
    with pytest.raises(
        DataError, match=r"`nonnegative` names columns that are not regressors: \['b'\]"
    ) as refused:
        fit_linear({"a": np.ones(3)}, np.ones(3), nonnegative=["b"])
    assert (refused.value.kind, refused.value.field, refused.value.value) == (
        "unknown_key",
        "nonnegative",
        "b",
    )
