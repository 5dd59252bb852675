"""The one way figures are made: :class:`matplotlib.figure.Figure` objects built directly and saved
with ``savefig``.

No global figure manager and no backend switch: a figure made this way belongs to no window, so the
studies can draw from scripts, tests and notebooks alike without changing the caller's backend,
and nothing has to be closed afterwards.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ._extras import require

require("matplotlib", extra="plot", needed_by="leuven-rt's figures")

from matplotlib.figure import Figure

from ._output import image_format, write_files


def figure(
    rows: int = 1, columns: int = 1, *, size: tuple[float, float], **options: Any
) -> tuple[Figure, Any]:
    """A figure of ``size`` inches with a ``rows`` × ``columns`` grid of axes (``options`` go to
    :meth:`Figure.subplots`, e.g. ``sharex``); one axes, or an array of them."""
    layout = options.pop("layout", None)
    drawing = Figure(figsize=size, layout=layout)
    return drawing, drawing.subplots(rows, columns, **options)


def save(drawing: Figure, path: str | Path, dpi: int) -> Path:
    """Writes ``drawing`` to ``path`` (its folder is created if needed) and returns the path.

    The format is the extension's, which must be one matplotlib writes (:class:`OutputError`
    otherwise); the file is written atomically (:mod:`leuven_rt._output`), so a failure leaves
    no partial figure."""
    path = Path(path)
    kind = image_format(path)

    def write(temporary: Path) -> None:
        drawing.savefig(temporary, dpi=dpi, format=kind)

    write_files([(path, write)])
    return path
