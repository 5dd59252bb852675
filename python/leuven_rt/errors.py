"""Every exception and warning of leuven_rt.

The three the Rust core raises (:class:`ParameterError`, :class:`InputError`,
:class:`DivergenceError`) and the one of the file reader (:class:`ModelFileError`, a
:class:`ParameterError` with the refusal's ``kind``, ``field``, ``line`` and ``column``) are defined
in the extension, so that the core and the Python modules
raise the same classes; the rest are Python-only and subclass them or ``ValueError``, so that
``except ValueError`` (or ``except InputError`` for bad data) catches every refusal.

The one exception outside ``ValueError`` is :class:`ConcurrentUseError` (a ``RuntimeError``): an
object that is busy in another thread (inside ``run``, which releases the GIL) was called again.
It says nothing about the arguments, and the same call succeeds once the other one returns.
"""

from __future__ import annotations

from ._core import DivergenceError, InputError, ModelFileError, ParameterError

__all__ = [
    "ConcurrentUseError",
    "DataError",
    "DivergenceError",
    "InputError",
    "ModelFileError",
    "OutputError",
    "ParameterError",
    "ResamplingWarning",
    "StackOverflowError",
    "UnitsWarning",
]


class DataError(InputError):
    """Measured data that cannot be identified from: the message names the column and says what
    was expected and what came."""


class OutputError(InputError):
    """An output path that cannot be written: it is one of the inputs, it exists (and overwriting
    was not asked for), its folder cannot be made, or its extension is not an image format the
    figure can be saved in. Raised before any work is done."""


class ConcurrentUseError(RuntimeError):
    """A model, mass system, compensator or online identifier was called while another thread
    was inside one of its calls (``run`` releases the GIL): nothing was changed by this call.
    Give each thread its own object, or serialise the calls with a lock."""


class ResamplingWarning(UserWarning):
    """The time stamps were not uniform, so the data was interpolated onto a uniform grid."""


class UnitsWarning(UserWarning):
    """A loaded log looks as if a column were not in the units expected (time in milliseconds, a
    linear position in millimetres, an angle in degrees): the message names the column and says
    what was expected. The data is used as it is; the warning is also kept in its ``notes``."""


class StackOverflowError(ValueError):
    """A stack of extrema of the original Leuven model (:mod:`leuven_rt.reference.original_leuven`)
    is full: more reversals without a closed loop than its depth."""

    def __init__(self, stack: str, sample: int, depth: int) -> None:
        self.stack, self.sample, self.depth = stack, sample, depth
        super().__init__(
            f"the stack of {stack} overflowed at sample {sample}: it holds depth = {depth} extrema "
            "and the motion reversed once more without closing a loop"
        )
