"""Progress of ``identify`` and ``diagnose`` without a terminal: timestamped lines on stderr,
never on stdout (which carries ``--json``), none with ``--quiet``. On a small log, run for real."""

from __future__ import annotations

import contextlib
import io
import json
import re
from pathlib import Path

import numpy as np
import pytest

from leuven_rt.cli import main

PROGRESS = re.compile(r"^leuven-rt (identify|diagnose): \d\d:\d\d:\d\d (?P<text>.*)$")


@pytest.fixture(scope="module")
def log(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """3 s at 1 kHz of a Coulomb-and-viscous stage moved by a 1 Hz sine."""
    t = np.arange(3000) * 1e-3
    x = 1e-3 * np.sin(2.0 * np.pi * t)
    v = np.gradient(x, 1e-3)
    f = np.tanh(v / 1e-4) + 0.5 * v + 0.01 * np.random.default_rng(0).standard_normal(t.size)
    path = tmp_path_factory.mktemp("progress") / "log.csv"
    rows = (f"{a!r},{b!r},{c!r}" for a, b, c in zip(t.tolist(), x.tolist(), f.tolist(), strict=True))
    path.write_text("\n".join(["t,x,f", *rows]) + "\n", encoding="utf-8")
    return path


def _run(argv: list[str]) -> tuple[str, list[str]]:
    """stdout, and the progress texts on stderr (every stderr line must be progress)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        assert main(argv) == 0, err.getvalue()
    texts = []
    for line in err.getvalue().splitlines():
        match = PROGRESS.match(line)
        if match is None:
            assert "warning: " in line, line  # the fit's own warnings (identify)
            continue
        assert match[1] == argv[0]
        texts.append(match["text"])
    assert not any(PROGRESS.match(line) for line in out.getvalue().splitlines())
    return out.getvalue(), texts


def test_diagnose_reports_its_stages_as_lines_and_keeps_stdout_for_json(log: Path) -> None:
    out, texts = _run(["diagnose", str(log), "--json"])
    assert json.loads(out)["samples"] == 3000  # stdout is the report alone
    assert texts[0] == "selecting effects"
    rounds = [text for text in texts if text.startswith("round ")]
    assert rounds and re.fullmatch(r"round 1: trying [a-z_, ]+", rounds[0])
    assert texts[-1] == "the model file and its prediction"
    out, texts = _run(["diagnose", str(log), "--json", "--quiet"])
    assert texts == [] and json.loads(out)["samples"] == 3000


def test_identify_reports_the_rounds_and_the_file(log: Path, tmp_path: Path) -> None:
    out, texts = _run(["identify", str(log), "-o", str(tmp_path / "model.json")])
    assert "model file (linear)" in out
    assert texts[0] == "selecting effects"
    assert "choosing how the written file reconstructs the motion" in texts
    assert texts[-2:] == ["the parameters the excitation determines", "the model file and its prediction"]
    _, texts = _run(["identify", str(log), "-o", str(tmp_path / "quiet.json"), "--quiet"])
    assert texts == []
