"""The numpy oracles: the specification of each discrete step, written one sample at a time with
nothing traded for speed, that the tests hold the Rust core to.

- this package's namespace and :mod:`.leuven`: the friction step (:func:`simulate`,
  :func:`simulate_position`, :func:`step`, :class:`MaxwellSlip`, ...) and the position-dependent
  terms (:func:`position_series`);
- :mod:`.mechanics`: the force-driven mass (:func:`leuven_rt.reference.mechanics.simulate_mass`);
- :mod:`.online`: the regressors of the online identifier;
- :mod:`.original_leuven`: the original Leuven model with its stacks of extrema, for comparison.

Nothing in the public face imports these; ``leuven_rt.reference`` is loaded on first use.
"""

from .._extras import require

require("scipy", extra="analysis", needed_by="leuven_rt.reference")


from . import mechanics, online, original_leuven
from .leuven import (
    RTOL,
    Hysteresis,
    LinearSpring,
    MaxwellSlip,
    explicit_point,
    hysteresis_of,
    implicit_root,
    phi,
    position_series,
    simulate,
    simulate_position,
    step,
    stribeck_level,
    viscous_coefficient,
)

__all__ = [
    "RTOL",
    "Hysteresis",
    "LinearSpring",
    "MaxwellSlip",
    "explicit_point",
    "hysteresis_of",
    "implicit_root",
    "mechanics",
    "online",
    "original_leuven",
    "phi",
    "position_series",
    "simulate",
    "simulate_position",
    "step",
    "stribeck_level",
    "viscous_coefficient",
]
