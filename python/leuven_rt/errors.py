"""Every exception and warning of leuven_rt, and the data each error carries.

The five the Rust extension raises (:class:`ParameterError`, :class:`InputError`,
:class:`DivergenceError`, :class:`ConcurrentUseError`, and the file reader's
:class:`ModelFileError`, a :class:`ParameterError` that also carries ``line`` and ``column``) are
defined in the extension, so that the core and the Python modules raise the same classes; the rest
are Python-only and subclass them or ``ValueError``, so that ``except ValueError`` (or ``except
InputError`` for bad data) catches every refusal.

Every error carries its data as attributes, whoever raised it (docs/errors.md#error-data):
``kind`` (what rule was broken: gms-core's variant in snake case, such as ``"not_finite"``, or a
kind of the Python modules, such as ``"missing_column"``; one of :data:`KINDS`), ``field`` (the
parameter, argument or column at fault, such as ``"Fs"``, ``"W[2]"``, ``"x"``), ``value`` (what
came), and where there is one ``bound``, ``index``, ``sample``, ``channel``, ``expected``,
``got``; each is None where the error has no such datum. The Python modules raise them as
``DataError(message, kind="missing_column", field="f")``.

The one exception outside ``ValueError`` is :class:`ConcurrentUseError` (a ``RuntimeError``): an
object that is busy in another thread (inside ``run``, which releases the GIL) was called again.
It says nothing about the arguments, and the same call succeeds once the other one returns.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._core import (
    ERROR_KINDS,
    ConcurrentUseError,
    DivergenceError,
    InputError,
    ModelFileError,
    ParameterError,
)

__all__ = [
    "DATA",
    "KINDS",
    "ConcurrentUseError",
    "DataError",
    "DivergenceError",
    "ErrorClass",
    "InputError",
    "ModelFileError",
    "OutputError",
    "ParameterError",
    "ResamplingWarning",
    "StackOverflowError",
    "UnitsWarning",
    "data_of",
    "shown",
]

#: The data every error of the package carries as attributes (None where it has no such datum),
#: in the order of the keywords its class takes after the message.
DATA = ("kind", "field", "value", "bound", "index", "sample", "channel", "expected", "got")

#: The kinds only the Python modules raise (the extension's are ``_core.ERROR_KINDS``); each is
#: documented in docs/errors.md#kinds.
PYTHON_KINDS = frozenset(
    {
        # arguments and parameters
        "not_integer",
        "malformed",
        "not_applicable",
        "units_mismatch",
        # files
        "not_text",
        "no_such_file",
        "empty_file",
        "no_header",
        "ragged",
        # measured data
        "missing_column",
        "too_few",
        "not_uniform",
        "gap",
        "implausible_units",
        "no_motion",
        "no_sliding_motion",
        "wrong_sign",
        # output paths
        "empty_path",
        "is_input",
        "is_folder",
        "exists",
        "same_file",
        "no_folder",
        "no_permission",
        "write_failed",
        # the original Leuven model's stack of extrema
        "stack_overflow",
    }
)

#: Every kind an error of the package can have: the extension's (gms-core's rules, gms-dyn's,
#: gms-fit's, gms-file's and the bindings' own) and the Python modules'.
KINDS = frozenset(ERROR_KINDS) | PYTHON_KINDS


#: A class of the package's refusals: it takes the message and the data keywords.
ErrorClass = type[ParameterError | InputError]


def data_of(error: BaseException) -> dict[str, Any]:
    """The data of ``error`` that is not None, as the keywords that raise it again: ``raise
    ParameterError(f"{path}: {error}", **data_of(error))`` keeps the data under a longer
    message."""
    return {name: value for name in DATA if (value := getattr(error, name, None)) is not None}


def shown(value: Any) -> Any:
    """``value`` as a message shows it: a numpy scalar as the Python scalar it holds (also inside a
    list or a tuple), so that ``repr`` spells ``1.0`` and ``'x'``, not ``np.float64(1.0)`` and
    ``np.str_('x')``."""
    if isinstance(value, np.generic):
        return value.item()
    if type(value) in (list, tuple):
        return type(value)(shown(item) for item in value)
    return value


class DataError(InputError):
    """Measured data that cannot be identified from: the message names the column and says what
    was expected and what came; ``field`` is the column (or the file's key) at fault."""


class OutputError(InputError):
    """An output path that cannot be written: it is one of the inputs, it exists (and overwriting
    was not asked for), its folder cannot be made, or its extension is not an image format the
    figure can be saved in. Raised before any work is done. ``field`` is the option (such as
    ``-o/--output``), ``value`` the path."""


class ResamplingWarning(UserWarning):
    """The time stamps were not uniform, so the data was interpolated onto a uniform grid."""


class UnitsWarning(UserWarning):
    """A loaded log looks as if a column were not in the units expected (time in milliseconds, a
    linear position in millimetres, an angle in degrees): the message names the column and says
    what was expected. The data is used as it is; the warning is also kept in its ``notes``."""


class StackOverflowError(ValueError):
    """A stack of extrema of the original Leuven model (:mod:`leuven_rt.reference.original_leuven`)
    is full: more reversals without a closed loop than its depth. Its kind is
    ``"stack_overflow"``, ``field`` the stack (``"maxima"`` or ``"minima"``), ``sample`` the
    sample and ``bound`` the depth; ``stack`` and ``depth`` repeat the first and the last."""

    kind: str | None = "stack_overflow"
    field: str | None = None
    value: object = None
    bound: object = None
    index: int | None = None
    sample: int | None = None
    channel: int | None = None
    expected: object = None
    got: object = None

    def __init__(self, stack: str, sample: int, depth: int) -> None:
        self.stack, self.sample, self.depth = stack, sample, depth
        self.field, self.bound = stack, depth
        super().__init__(
            f"the stack of {stack} overflowed at sample {sample}: it holds depth = {depth} extrema "
            "and the motion reversed once more without closing a loop"
        )
