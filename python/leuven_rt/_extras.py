"""The optional extras of the package, checked where they are first needed.

``pip install leuven-rt`` needs numpy only and gives the public face (parameters, simulation,
model, mechanics, compensation, online identification). The rooms that need more call
:func:`require` at their top, so that a missing extra is named in the error instead of surfacing
as a bare ``ModuleNotFoundError`` from deep inside scipy's import:

- ``leuven-rt[analysis]`` (scipy, tqdm): :mod:`.data`, :mod:`.identification`,
  :mod:`.discrepancy`, :mod:`.reference`, :mod:`.studies`;
- ``leuven-rt[plot]`` (matplotlib): the figures.
"""

from __future__ import annotations

import sys
from importlib.util import find_spec

__all__ = ["MissingExtraError", "require"]


class MissingExtraError(ImportError):
    """A module of leuven-rt needs a package of an extra that is not installed; the message names
    the extra (``pip install 'leuven-rt[analysis]'``)."""

    def __init__(self, package: str, extra: str, needed_by: str) -> None:
        self.package, self.extra = package, extra
        super().__init__(
            f"{needed_by} needs {package}, which is not installed: "
            f"install leuven-rt[{extra}] (pip install 'leuven-rt[{extra}]')",
            name=package,
        )


def require(*packages: str, extra: str, needed_by: str = "this part of leuven-rt") -> None:
    """Raises :class:`MissingExtraError` naming ``extra`` unless every one of ``packages`` is
    installed. Looks the packages up without importing them, so it costs microseconds."""
    for package in packages:
        if package in sys.modules:
            continue
        try:
            found = find_spec(package) is not None
        except (ImportError, ValueError):  # a finder that refuses it, a broken installation
            found = False
        if not found:
            raise MissingExtraError(package, extra, needed_by)
