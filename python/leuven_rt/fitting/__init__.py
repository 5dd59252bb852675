"""The output-error engine: fit the model file itself by simulating it.

An output-error fit adjusts the parameters of a friction model until its simulated force matches
the measured one, with Gauss–Newton or Levenberg–Marquardt steps. This room holds what such a fit
runs on:

- :func:`sensitivities`: the force along a signal and its exact derivatives by every parameter,
  propagated along one simulation (the Rust crate gms-fit), at chosen rows of the record;
- :func:`simulate_sets`: the force of many parameter sets along one signal, in parallel (line
  searches, screening of candidates).

It needs numpy only. The equations are in docs/sensitivities.md.
"""

from .sensitivity import Sensitivities, sensitivities, simulate_sets

__all__ = ["Sensitivities", "sensitivities", "simulate_sets"]
