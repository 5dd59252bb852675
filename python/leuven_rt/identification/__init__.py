"""Identification: fit the modified Leuven model to measured position and force, offline.

- :func:`identify` (re-exported as ``leuven_rt.identify``): the whole model from a log, with a
  report (errors per stage, held-out error, conditioning, warnings);
- building blocks, reusable by other fits: :mod:`.data` (loading, validation, zero-phase
  derivatives), :mod:`.regression` (linear least squares on named regressor columns),
  :mod:`.inverse_model` (IDIM-LS: inertia, viscous, Coulomb, offset, as in the EMPS benchmark),
  :mod:`.motion` (reversals, presliding range), :mod:`.sliding`, :mod:`.presliding`,
  :mod:`.refine` (simulation-error fits through the Rust core), :mod:`.report`.
"""

from .data import MotionData, as_motion_data, estimate_derivatives, load_columns
from .errors import DataError, ResamplingWarning
from .inverse_model import REGRESSORS, RIGID_BODY, fit_inverse_model
from .pipeline import identify
from .regression import LinearFit, fit_linear
from .report import IdentificationReport, IdentificationResult, Stage

__all__ = [
    "REGRESSORS",
    "RIGID_BODY",
    "DataError",
    "IdentificationReport",
    "IdentificationResult",
    "LinearFit",
    "MotionData",
    "ResamplingWarning",
    "Stage",
    "as_motion_data",
    "estimate_derivatives",
    "fit_inverse_model",
    "fit_linear",
    "identify",
    "load_columns",
]
