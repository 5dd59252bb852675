"""Identification: fit the modified Leuven model to measured position and force, offline.

- :func:`identify_staged`: the modified Leuven model from a log in stages, with a
  report (errors per stage, held-out error, conditioning, warnings);
- the stages: :mod:`.inverse_model` (IDIM-LS: inertia, viscous, Coulomb, offset, as in the EMPS
  benchmark), :mod:`.sliding`, :mod:`.presliding`, :mod:`.refine` (simulation-error fits through
  the Rust core), :mod:`.pipeline` (the order they run in), :mod:`.report`;
- :func:`model_file_from_identification`: the model file (:class:`~leuven_rt.ModelFile`) that
  ``leuven-rt identify -o`` writes from a result.

The data toolkit it works from (loading, derivatives, reversals, regression) is
:mod:`leuven_rt.data`; its names are re-exported here as before.
"""

from .._extras import require

require("scipy", "tqdm", extra="analysis", needed_by="leuven_rt.identification")


from ..data.records import MotionData, as_motion_data, load_columns
from ..data.regression import LinearFit, fit_linear
from ..data.signals import estimate_derivatives
from ..errors import DataError, ResamplingWarning
from .inverse_model import REGRESSORS, RIGID_BODY, fit_inverse_model
from .model_file import model_file_from_identification
from .pipeline import identify_staged
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
    "identify_staged",
    "load_columns",
    "model_file_from_identification",
]
