"""The presliding bank driven by the modified Leuven model's own state.

In the model (docs/model.md#hysteresis-force) the Maxwell-slip elements are driven not by the position x
but by the deflection z of the state equation, dz/dt = v − |v|·sgn(Fh)·|Fh/g(v)|ⁿ: right after a
reversal z runs ahead of x (up to twice as fast), and as Fh nears the sliding level it stops
following x. A bank driven by x alone (rate-independent Maxwell slip) misses both, by about
the noise level on the generated logs. A :class:`Drive` is the nonlinear part of the
presliding effect, like the Stribeck curve's shape: given the element weights W and the
exponent n, the project's simulator (:meth:`leuven_rt.LeuvenModel.trace_position`) gives z(t),
and the element deflections driven by z are the effect's columns, linear in W again.

The sliding level of the simulation is sum(W)/MARGIN, constant: z depends only on W relative
to that level, and the model's Coulomb column, the Stribeck curve and an asymmetry do not enter
it (on the generated logs, counting the Coulomb column in the level changes the final rms by
about 3 %).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from .._typing import FloatArray
from ..data.slip import element_deflections
from ..model import LeuvenModel
from ..params import Params
from .features import Features

#: The exponents n tried (the paper's transition shapes, from soft to sharp).
EXPONENTS = (1.0, 2.0, 4.0)
#: sum(W) over the sliding level of the simulation (the model needs sum(W) > the level).
MARGIN = 1.02


@dataclass(frozen=True)
class Drive:
    n: float
    weights: tuple[float, ...]
    """W of every bank element (0 for an element the fit left out)."""

    def deflection(self, features: Features) -> FloatArray:
        """z(t) of the state equation driven by the filtered position of ``features``."""
        weights = np.asarray(self.weights)
        # Only the ratios W/level matter: scaled to a unit level, tiny fitted weights stay valid
        # parameters, and weights that are nothing next to the largest are left out.
        keep = weights > 1e-9 * weights.max(initial=0.0)
        if not keep.any():
            unmoved: FloatArray = features.x.copy()
            return unmoved
        scaled = weights[keep] / weights[keep].sum() * MARGIN
        params = Params(Fc=1.0, Fs=1.0, Vs=1.0, delta=1.0, n=self.n, sigma1=0.0, sigma2=0.0,
                        W=tuple(scaled), Delta=tuple(features.scales.deflections[keep]))  # fmt: skip
        return LeuvenModel(params).trace_position(features.x, features.dt).z

    def apply(self, features: Features) -> Features:
        """``features`` with the bank driven by z instead of x. Thinned features
        (:func:`~.features.thin`) are driven by the z of every sample, kept on their samples."""
        deflections = features.scales.deflections
        if features.full is None or features.index is None:
            return dataclasses.replace(
                features, bank=element_deflections(self.deflection(features), deflections)
            )
        z = self.deflection(features.full)
        bank = np.empty((features.index.size, deflections.size))
        for j in range(deflections.size):  # one element at a time: no bank of every sample
            bank[:, j] = element_deflections(z, deflections[j : j + 1])[features.index, 0]
        return dataclasses.replace(features, bank=bank)
