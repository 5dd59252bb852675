"""The progress reporter of long runs (leuven_rt.progress): timestamped lines when the stream is
not a terminal (a stage's beginning and end always, in between at most every ``interval``), a
tqdm bar on a terminal, nothing when off; ``reporting`` turns a library's ``progress`` argument
into a reporter."""

from __future__ import annotations

import io
import re

import pytest

from leuven_rt.errors import InputError
from leuven_rt.progress import Progress, reporting

LINE = re.compile(r"^run: \d\d:\d\d:\d\d (?P<text>.*)$")


class _Clock:
    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def _texts(stream: io.StringIO) -> list[str]:
    texts = []
    for line in stream.getvalue().splitlines():
        match = LINE.match(line)
        assert match is not None, line
        texts.append(match["text"])
    return texts


def test_lines_at_each_stage_its_end_and_every_interval() -> None:
    stream, clock = io.StringIO(), _Clock()
    with Progress("run", stream=stream, interval=5.0, clock=clock) as progress:
        assert progress.mode == "lines"  # a StringIO is no terminal
        progress.stage("signals")
        for done in range(10):
            clock.now += 1.0
            progress.stage("fits", done, 10, f"candidate {done}")
        progress.stage("fits", 10, 10)
        progress.stage("fits", 10, 10)  # the same end again: not repeated
        clock.now += 1.0
        progress.stage("refinement", 3, None, "simulations")
    assert _texts(stream) == [
        "signals",
        "fits 0/10 (candidate 0)",  # a new stage
        "fits 5/10 (candidate 5)",  # 5 s later
        "fits 10/10",  # its end
        "refinement 3 (simulations)",
    ]


def test_off_writes_nothing_and_auto_draws_a_bar_on_a_terminal() -> None:
    quiet = io.StringIO()
    with Progress("run", "off", stream=quiet) as progress:
        progress.stage("fits", 1, 2)
    assert quiet.getvalue() == ""
    terminal = _Terminal()
    with Progress("run", stream=terminal) as progress:
        assert progress.mode == "bar"
        progress.stage("fits", 1, 4, "stribeck")
        progress.stage("fits", 2, 6)
        progress.stage("refinement", 7, None)
    drawn = terminal.getvalue()
    assert "fits" in drawn and "1/4" in drawn and "stribeck" in drawn and "2/6" in drawn
    assert "refinement" in drawn and "run:" not in drawn  # a bar, not lines


def test_reporting_takes_a_bool_or_a_reporter() -> None:
    with reporting(False, "diagnose") as progress:
        assert progress.mode == "off"
    with reporting(True, "diagnose") as progress:
        assert progress.mode == "lines" and progress.label == "diagnose"  # stderr is captured
    own = Progress("mine", "off")
    with reporting(own, "diagnose") as progress:
        assert progress is own
    for bad in ("yes", 1, None):
        with pytest.raises(InputError, match=r"`progress` must be a bool or a leuven_rt\.progress\.Progress"):
            with reporting(bad, "diagnose"):  # type: ignore[arg-type]
                pass
    with pytest.raises(InputError, match=r"`mode` must be one of auto, bar, lines, off, got 'loud'"):
        Progress("run", "loud")  # type: ignore[arg-type]
