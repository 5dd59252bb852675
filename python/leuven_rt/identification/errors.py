"""Errors and warnings of the identification package.

Python-only: they subclass the extension's :class:`leuven_rt.InputError` (a ``ValueError``), so
that ``except leuven_rt.InputError`` catches bad data from every entry point.
"""

from __future__ import annotations

from ..errors import InputError

__all__ = ["DataError", "ResamplingWarning"]


class DataError(InputError):
    """Measured data that cannot be identified from: the message names the column and says what
    was expected and what came."""


class ResamplingWarning(UserWarning):
    """The time stamps were not uniform, so the data was interpolated onto a uniform grid."""
