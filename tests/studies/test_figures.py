"""`leuven-rt figures --out DIR` writes the paper's figures and prints the numbers behind them."""

from __future__ import annotations

import contextlib
import io
import re
from pathlib import Path

import pytest

from leuven_rt.cli import main

NAMES = ("fig1_loop_closure.png", "fig4_5_nonlocal_memory.png", "free_response_memory.png")


@pytest.fixture(scope="module")
def printed(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, str]:
    """Runs the command once (quick: two step sizes for Fig. 1) into a folder it must create."""
    out = tmp_path_factory.mktemp("figures") / "new"
    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        assert main(["figures", "--out", str(out), "--quick"]) == 0
    return out, buffer.getvalue()


def test_the_three_pngs_are_written(printed: tuple[Path, str]) -> None:
    out, text = printed
    for name in NAMES:
        path = out / name
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", name
        assert path.stat().st_size > 20_000, name
        assert str(path) in text


def test_fig1_numbers_show_the_jump_of_the_original_model(printed: tuple[Path, str]) -> None:
    rows = re.findall(r"^\| ([0-9.e-]+) \| ([0-9.e-]+) \| ([0-9.e-]+) \|$", printed[1], flags=re.MULTILINE)
    assert [float(row[0]) for row in rows] == [4e-4, 1e-4]
    original = [float(row[1]) for row in rows]
    modified = [float(row[2]) for row in rows]
    assert original[1] > 0.8 * original[0]  # a jump: does not shrink with dt
    assert modified[1] < 0.3 * modified[0]  # continuous: ÷4 with dt


def test_fig4_5_numbers_show_the_same_hysteresis(printed: tuple[Path, str]) -> None:
    text = printed[1]
    fitted = float(re.search(r"over both paths: ([0-9.e-]+) N", text).group(1))  # type: ignore[union-attr]
    exact = float(re.search(r"the same hysteresis\): ([0-9.e-]+) N", text).group(1))  # type: ignore[union-attr]
    assert fitted < 0.05 and exact < 1e-12
    at_a = re.search(r"stack ([0-9.]+) / ([0-9.]+) N, Maxwell slip ([0-9.]+) / ([0-9.]+) N", text)
    assert at_a is not None
    stack_1, stack_2, maxwell_1, maxwell_2 = map(float, at_a.groups())
    assert stack_1 == stack_2 and maxwell_1 == maxwell_2  # point a, two paths, one value


def test_free_response_numbers_show_the_overflow(printed: tuple[Path, str]) -> None:
    text = printed[1]
    match = re.search(r"overflowed at sample (\d+): it holds depth = 10 .* after (\d+) reversals", text)
    assert match is not None, text
    assert int(match.group(2)) >= 2 * 10
    assert "Maxwell slip memory: 4 numbers throughout" in text
