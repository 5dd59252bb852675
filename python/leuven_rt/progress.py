"""Progress of long runs (``identify``, ``diagnose``), reported on stderr, never on stdout (which
carries ``--json``): a tqdm bar when stderr is a terminal, plain timestamped lines otherwise (logs,
pipes, CI), nothing when quiet.

A run reports its stages through one call, :meth:`Progress.stage` (``name``, ``done`` of
``total``); the bar shows each stage as it goes, the lines mode writes a line when a stage begins,
when it completes and at most every :attr:`Progress.interval` seconds in between::

    leuven-rt identify: 14:02:07 diagnose: fits 12/30 (coulomb+viscous+stribeck)

The library's functions take ``progress=True`` (report, as a bar or lines), ``False`` (nothing),
or a :class:`Progress` of the caller's; :func:`reporting` turns either into the reporter a run uses.
"""

from __future__ import annotations

import contextlib
import sys
import time
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, Literal, NoReturn, TextIO

from .errors import InputError, shown

if TYPE_CHECKING:
    from types import TracebackType

    from tqdm import tqdm

#: How progress is shown: ``"auto"`` (a bar on a terminal, lines otherwise), ``"bar"``, ``"lines"``
#: or ``"off"``.
Mode = Literal["auto", "bar", "lines", "off"]
MODES: tuple[Mode, ...] = ("auto", "bar", "lines", "off")
#: Seconds between two lines of one stage (its beginning and end are always written).
INTERVAL = 5.0


class Progress:
    """The progress reporter of one run, labelled ``label`` (e.g. ``"leuven-rt identify"``).

    ``mode``: :data:`Mode`. ``stream``: where to write (default: the ``sys.stderr`` of the moment
    of each write). ``interval``: seconds between two lines of one stage in the lines mode.
    ``clock``: seconds since some origin (for the intervals; tests give their own). Use it as a
    context manager, or call :meth:`close` at the end (it removes the bar).
    """

    def __init__(
        self,
        label: str,
        mode: Mode = "auto",
        *,
        stream: TextIO | None = None,
        interval: float = INTERVAL,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        if mode not in MODES:
            raise InputError(
                f"`mode` must be one of {', '.join(MODES)}, got {shown(mode)!r:.80}",
                kind="invalid_choice",
                field="mode",
                value=mode,
                expected=MODES,
            )
        self.label = label
        self.interval = float(interval)
        self._stream = stream
        self._clock = clock
        if mode == "auto":
            isatty = getattr(self.stream, "isatty", None)
            mode = "bar" if isatty is not None and bool(isatty()) else "lines"
        self.mode: Mode = mode
        self._bar: tqdm[NoReturn] | None = None
        self._stage: str | None = None
        self._written = -float("inf")
        self._last: tuple[str, int, int | None] | None = None

    @property
    def stream(self) -> TextIO:
        return self._stream if self._stream is not None else sys.stderr

    def stage(self, name: str, done: int = 0, total: int | None = None, detail: str = "") -> None:
        """The run is at ``done`` of ``total`` (None: not known) in its stage ``name``;
        ``detail`` says what it is doing (e.g. the candidate being fitted)."""
        if self.mode == "off":
            return
        began = name != self._stage
        self._stage = name
        if self.mode == "bar":
            self._show(name, done, total, detail, began)
            return
        now = self._clock()
        ended = total is not None and done >= total and (name, done, total) != self._last
        if began or ended or now - self._written >= self.interval:
            self._written, self._last = now, (name, done, total)
            count = f" {done}/{total}" if total is not None else (f" {done}" if done else "")
            extra = f" ({detail})" if detail else ""
            stamp = time.strftime("%H:%M:%S")
            print(f"{self.label}: {stamp} {name}{count}{extra}", file=self.stream, flush=True)

    def _show(self, name: str, done: int, total: int | None, detail: str, began: bool) -> None:
        from tqdm import tqdm

        bar = self._bar
        if bar is None:
            bar = self._bar = tqdm(desc=name, total=total, file=self.stream, leave=False, dynamic_ncols=True)
        if began:
            bar.reset(total=total)
            bar.set_description_str(name, refresh=False)
        elif total != bar.total:
            bar.total = total
        bar.n = done
        bar.set_postfix_str(detail, refresh=False)
        bar.refresh()

    def close(self) -> None:
        """Removes the bar (the lines stay); the reporter can be used again."""
        if self._bar is not None:
            self._bar.close()
            self._bar = None
        self._stage = self._last = None

    def __enter__(self) -> Progress:
        return self

    def __exit__(
        self, kind: type[BaseException] | None, error: BaseException | None, trace: TracebackType | None
    ) -> None:
        self.close()


@contextlib.contextmanager
def reporting(progress: bool | Progress, label: str) -> Iterator[Progress]:
    """The reporter for a library function's ``progress`` argument: the caller's :class:`Progress`
    as it is (the caller closes it), or one of its own labelled ``label`` (``"auto"`` for True,
    ``"off"`` for False), closed at the end."""
    if isinstance(progress, Progress):
        yield progress
        return
    if not isinstance(progress, bool):
        raise InputError(
            f"`progress` must be a bool or a leuven_rt.progress.Progress, got {shown(progress)!r:.80}",
            kind="wrong_type",
            field="progress",
            value=progress,
        )
    with Progress(label, "auto" if progress else "off") as own:
        yield own


__all__ = ["INTERVAL", "MODES", "Mode", "Progress", "reporting"]
