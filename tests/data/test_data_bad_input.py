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
            {"x": np.r_[np.zeros(5), np.inf, np.zeros(SAMPLES - 6)]},
            r"column `x` must be finite, got inf at sample 5",
        ),
        (
            {"t": np.r_[np.arange(100), 50, np.arange(101, SAMPLES)] * 1e-3},
            r"`t` must strictly increase, got t\[99\]",
        ),
        ({"t": np.r_[0.0, np.zeros(SAMPLES - 1)]}, r"`t` must strictly increase"),
        ({"f": None}, r"missing columns \['f'\]: expected `t` \[s\], `x` \[m\], `f` \[N\]"),
        ({"f": np.ones(SAMPLES - 1)}, r"columns must have the same length"),
        (
            {"f": 1e12 * np.ones(SAMPLES)},
            r"column `f` reaches 1e\+12 N, beyond 1e\+07 N: expected SI units \(N\)",
        ),
        ({"x": 1e4 * np.linspace(0, 1, SAMPLES)}, r"column `x` reaches 10000 m"),
        (
            {"t": np.arange(SAMPLES) * 1e-9},
            r"sampling step of `t` must be between .* got 1e-09: is `t` in seconds\?",
        ),
        ({"x": np.linspace(0.0, 900.0, SAMPLES)}, r"`x` moves at up to .* m/s .*expected `x` in m"),
        ({"x": np.zeros(SAMPLES)}, r"`x` never changes"),
        ({"f": np.ones((SAMPLES, 2))}, r"column `f` must be one-dimensional, got shape \(400, 2\)"),
        ({"f": ["a"] * SAMPLES}, r"column `f` must hold real numbers"),
        ({"f": np.ones(SAMPLES) * 1j}, r"column `f` must be real"),
    ],
)
def test_bad_columns_are_refused(changes: dict[str, Any], match: str) -> None:
    with pytest.raises(DataError, match=match):
        as_motion_data(columns(**changes))
    with pytest.raises(InputError, match=match):  # the same through identify
        identify(columns(**changes))


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
    with pytest.raises(DataError, match=r"`t` has a gap of 0\.501 s after sample 199 .*split the log"):
        as_motion_data(columns(t=t))


def test_motion_data_refuses_non_uniform_time_without_resampling() -> None:
    t = np.arange(SAMPLES) * 1e-3
    t[1::2] += 2e-4
    with pytest.raises(DataError, match=r"`t` must be uniformly sampled .*as_motion_data resamples"):
        MotionData(t, np.sin(t), np.cos(t))


def test_files(tmp_path: Path) -> None:
    with pytest.raises(DataError, match=r"does not exist"):
        as_motion_data(tmp_path / "missing.csv")
    wrong = tmp_path / "log.txt"
    wrong.write_text("t,x,f\n", encoding="utf-8")
    with pytest.raises(DataError, match=r"must end in \.csv or \.mat, got 'log\.txt'"):
        as_motion_data(wrong)
    csv = tmp_path / "log.csv"
    np.savetxt(csv, np.column_stack((np.arange(SAMPLES) * 1e-3, np.ones(SAMPLES))), delimiter=",",
               header="t,x", comments="")  # fmt: skip
    with pytest.raises(DataError, match=r"missing columns \['f'\]"):
        as_motion_data(csv)
    mat = tmp_path / "log.mat"
    scipy.io.savemat(mat, {"t": np.arange(SAMPLES) * 1e-3, "qm": np.ones(SAMPLES)})
    with pytest.raises(DataError, match=r"lacks the EMPS variables \['vir', 'gtau'\]"):
        as_motion_data(mat)
    with pytest.raises(DataError, match=r"`data` must be a MotionData, a path .* got int"):
        as_motion_data(3)  # type: ignore[arg-type]


def test_linear_fit_refuses_bad_regressors() -> None:
    with pytest.raises(DataError, match=r"regressor `a` must be finite"):
        fit_linear({"a": np.array([1.0, np.nan, 2.0])}, np.ones(3))
    with pytest.raises(DataError, match=r"`nonnegative` names columns that are not regressors: \['b'\]"):
        fit_linear({"a": np.ones(3)}, np.ones(3), nonnegative=["b"])
