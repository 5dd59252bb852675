"""leuven-rt: the modified Leuven friction model, a real-time Rust core with a Python front.

- :class:`Params`: a validated parameter set (DESIGN.md §2 keys).
- :func:`simulate`, :func:`simulate_position`: run velocity or position signals, (T,) or (B, T).
- :class:`LeuvenModel`: stateful channels stepped sample by sample, with checkpoints.
- :class:`Compensator`: friction compensation for a control loop (feedforward or observer).
- :class:`MassSystem`, :func:`simulate_mass`: a mass on the friction model driven by a force.
- :func:`diagnose`: name the effects a friction model misses in a log (:mod:`leuven_rt.discrepancy`).
- :func:`identify`: fit the model to a log of position and force (:mod:`leuven_rt.identification`).
- :class:`OnlineIdentifier`: recursive least squares on the terms that enter linearly, in the loop.
- :mod:`leuven_rt.reference`: the same discrete step in plain numpy, written as the specification.
"""

from . import reference
from ._core import MAX_ELEMENTS, MAX_ITERATIONS
from .compensation import Compensator
from .discrepancy import Diagnosis, diagnose
from .errors import DivergenceError, InputError, ParameterError
from .identification import DataError, IdentificationResult, MotionData, identify
from .mechanics import MassState, MassSystem, MassTrajectory, simulate_mass
from .model import LeuvenModel, ModelState, Trace
from .online import OnlineIdentifier
from .params import Params
from .simulation import simulate, simulate_position

__all__ = [
    "MAX_ELEMENTS",
    "MAX_ITERATIONS",
    "Compensator",
    "DataError",
    "Diagnosis",
    "DivergenceError",
    "IdentificationResult",
    "InputError",
    "LeuvenModel",
    "MassState",
    "MassSystem",
    "MassTrajectory",
    "ModelState",
    "OnlineIdentifier",
    "MotionData",
    "ParameterError",
    "Params",
    "Trace",
    "diagnose",
    "identify",
    "reference",
    "simulate",
    "simulate_mass",
    "simulate_position",
]
