"""Bad options and data for identification: each gets an InputError (a ValueError) whose message
names the argument and says what was expected, from the function and from the command line."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

import leuven_rt.cli
from conftest import small_log as columns
from leuven_rt import DataError, InputError
from leuven_rt.identification import identify_staged as identify


@pytest.mark.parametrize(
    ("options", "match"),
    [
        ({"elements": 0}, r"`elements` must be None or an integer in \[1, \d+\], got 0"),
        ({"elements": 2.5}, r"`elements` must be None or an integer"),
        ({"held_out": 0.9}, r"`held_out` must be a fraction in \[0, 0\.5\], got 0\.9"),
        ({"max_evaluations": 1}, r"`max_evaluations` must be an integer >= 3, got 1"),
        (
            {"cutoff": 600.0},
            r"`cutoff` must be below 500 Hz \(the Nyquist frequency of a 0\.001 s step\), got 600\.0 Hz",
        ),
    ],
)
def test_bad_options_are_refused(options: dict[str, Any], match: str) -> None:
    with pytest.raises(InputError, match=match):
        identify(columns(), **options)


def test_data_without_sliding_is_refused() -> None:
    # Presliding only: a 1 µm oscillation never slides, so the sliding curve is not identifiable.
    t = np.arange(2000) * 1e-3
    with pytest.raises(DataError, match=r"presliding range cannot be estimated|too few sliding samples"):
        identify(columns(t=t, x=1e-6 * np.sin(2 * np.pi * t), f=np.tanh(np.sin(2 * np.pi * t))))


def test_command_line_reports_bad_data(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    csv = tmp_path / "log.csv"
    np.savetxt(csv, np.column_stack((np.arange(50) * 1e-3, np.zeros(50), np.zeros(50))), delimiter=",",
               header="t,x,f", comments="")  # fmt: skip
    assert leuven_rt.cli.main(["identify", str(csv), "-o", str(tmp_path / "p.json"), "--quiet"]) == 2
    assert "too few samples: need at least 200, got 50" in capsys.readouterr().err
    assert not (tmp_path / "p.json").exists()
