"""The model file a fit writes: the values of a fitted structure as a :class:`~leuven_rt.ModelFile`.

The structure's parameters are already the file's numbers (:mod:`.structure`); this turns them
into the file's objects: the friction model (:class:`~leuven_rt.Params`; elements whose weight is
negligible left out), the position-dependent level or the position force with the positions'
middle and half stroke, the measurement terms, the units and the reconstruction. A drift fitted
alongside while selecting is never written.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np

from ..modelfile import ModelFile, Reconstruction
from ..params import Params
from ..units import Units
from .evaluate import params_of, position_terms
from .structure import Scales, Values

#: An element whose weight is below this share of the largest is left out of the file.
NEGLIGIBLE = 1e-9


def friction_params(values: Values) -> Params:
    """The friction model of ``values``, without elements of negligible weight."""
    weights = np.asarray(values.W, dtype=float)
    keep = weights > NEGLIGIBLE * float(weights.max())
    return params_of(replace(values, W=weights[keep], Delta=np.asarray(values.Delta)[keep]))


def model_file(
    values: Values,
    scales: Scales,
    units: Units,
    reconstruction: Reconstruction,
    report: Mapping[str, Any] | None = None,
) -> ModelFile:
    """The model file of a fit's ``values`` (module documentation)."""
    level, force = position_terms(values, scales)
    return ModelFile(
        friction=friction_params(values),
        level=level,
        position_force=force,
        offset=float(values.offset),
        inertia=float(values.inertia),
        units=units,
        reconstruction=reconstruction,
        report=report,
    )


__all__ = ["NEGLIGIBLE", "friction_params", "model_file"]
