"""leuven-rt: the modified Leuven friction model, a real-time Rust core with a Python front.

- :class:`Params`: a validated parameter set (DESIGN.md §2 keys).
- :func:`simulate`, :func:`simulate_position`: run velocity or position signals, (T,) or (B, T).
- :class:`LeuvenModel`: stateful channels stepped sample by sample, with checkpoints.
- :mod:`leuven_rt.reference`: the same discrete step in plain numpy, written as the specification.
"""

from . import reference
from ._core import MAX_ELEMENTS, MAX_ITERATIONS
from .errors import DivergenceError, InputError, ParameterError
from .model import LeuvenModel, ModelState
from .params import Params
from .simulation import simulate, simulate_position

__all__ = [
    "MAX_ELEMENTS",
    "MAX_ITERATIONS",
    "DivergenceError",
    "InputError",
    "LeuvenModel",
    "ModelState",
    "ParameterError",
    "Params",
    "reference",
    "simulate",
    "simulate_position",
]
