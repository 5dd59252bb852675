"""leuven-rt: the modified Leuven friction model, a real-time Rust core with a Python front.

- :class:`Params`: a validated parameter set (docs/parameters.md#keys).
- :class:`ModelFile`: the versioned model file: friction, its position-dependent level
  (:class:`PositionLevel`, :class:`Ripple`), position force, measurement terms, units, how the
  motion signal is made from a log (:class:`Reconstruction`) and the fit's report.
- :class:`PositionForce`: a force of the position alone (cogging, gear mesh, gravity along the
  stroke), of the level's shape.
- :func:`simulate`, :func:`simulate_position`: run velocity or position signals, (T,) or (B, T),
  with a level and a position force placed by the positions.
- :class:`LeuvenModel`: stateful channels stepped sample by sample, with checkpoints.
- :class:`Compensator`: friction compensation for a control loop (feedforward or observer).
- :class:`MassSystem`, :func:`simulate_mass`: a mass on the friction model driven by a force.
- :func:`diagnose`: name the effects a friction model misses in a log (:mod:`leuven_rt.discrepancy`).
- :func:`identify`: the friction model a log supports, as a model file (the fit of :func:`diagnose`).
- :func:`predict`: a model's force along a log's motion, next to the measured force (:class:`Prediction`).
- :class:`OnlineIdentifier`: recursive least squares on the terms that enter linearly, in the loop.
- :mod:`leuven_rt.reference`: the same discrete steps in plain numpy, written as the specification.
- ``__version__``: the version of the package (the workspace version of Cargo.toml).

``pip install leuven-rt`` needs numpy only; identification, diagnosis, the data loaders and the
oracles need ``leuven-rt[analysis]`` (scipy, tqdm), the figures ``leuven-rt[plot]``
(matplotlib), and say so when it is missing.

The package's rooms: this public face at the top (with :mod:`.errors`), :mod:`.data` (logs in,
signals out), the two workflows :mod:`.identification` and :mod:`.discrepancy`,
:mod:`.reference` (the numpy oracles) and :mod:`.studies` (what the command line reproduces).
The workflows and the oracles load on first use, so that ``import leuven_rt`` stays light.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from ._core import MAX_ELEMENTS, MAX_ITERATIONS
from ._core import __version__ as __version__
from .compensation import Compensator
from .errors import DataError, DivergenceError, InputError, ModelFileError, ParameterError
from .level import PositionForce, PositionLevel, Ripple
from .mechanics import MassState, MassSystem, MassTrajectory, simulate_mass
from .model import LeuvenModel, ModelState, Trace
from .modelfile import ModelFile, Reconstruction
from .online import OnlineIdentifier
from .params import Params
from .simulation import simulate, simulate_position

if TYPE_CHECKING:
    from . import reference
    from .data.records import MotionData
    from .discrepancy.diagnose import diagnose
    from .discrepancy.identify import Identification, identify
    from .discrepancy.report import Diagnosis
    from .prediction import Prediction, predict

#: Names served on first use, and the module each comes from.
_LAZY = {
    "Diagnosis": "discrepancy",
    "diagnose": "discrepancy",
    "Identification": "discrepancy.identify",
    "identify": "discrepancy.identify",
    "MotionData": "data.records",
    "Prediction": "prediction",
    "predict": "prediction",
}

__all__ = [
    "MAX_ELEMENTS",
    "MAX_ITERATIONS",
    "Compensator",
    "DataError",
    "Diagnosis",
    "DivergenceError",
    "Identification",
    "InputError",
    "LeuvenModel",
    "MassState",
    "MassSystem",
    "MassTrajectory",
    "ModelFile",
    "ModelFileError",
    "ModelState",
    "MotionData",
    "OnlineIdentifier",
    "ParameterError",
    "Params",
    "PositionForce",
    "PositionLevel",
    "Prediction",
    "Reconstruction",
    "Ripple",
    "Trace",
    "__version__",
    "diagnose",
    "identify",
    "predict",
    "reference",
    "simulate",
    "simulate_mass",
    "simulate_position",
]


def __getattr__(name: str) -> Any:
    if name == "reference":
        return importlib.import_module(f"{__name__}.reference")
    if name in _LAZY:
        value = getattr(importlib.import_module(f"{__name__}.{_LAZY[name]}"), name)
        globals()[name] = value  # later look-ups skip this function
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
