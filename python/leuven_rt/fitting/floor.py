"""The floor a log allows: the error the right model would still have, driven by what the log
gives.

With a logged velocity the model is driven by the motion itself, and the floor is 0 (the force
noise alone remains). Driven by an encoder, a model places each friction flip at an encoder
count, not where the motion reversed, and in slow sliding it sees a staircase instead of a
smooth motion. Two parts:

- away from reversals (the samples the fit weighs), :func:`floor_estimate` runs the fitted
  friction model along a smooth version of the position (a Gaussian smoothing, which creates no
  reversal that is not in the record) and along the same smooth motion sensed again by an
  encoder of the log's resolution; the rms of the difference is the ``weighted`` floor;
- at the reversals an encoder cannot place (the samples the fit leaves out), where the motion
  reversed is unknown, so the flips' error is read from the fit itself (:func:`with_reversals`):
  what the model leaves there beyond what it leaves elsewhere.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.ndimage import gaussian_filter1d

from .._typing import FloatArray
from ..data.reconstruction import ambiguous_samples, filter_margin, resolution
from ..data.signals import lowpass
from ..modelfile import Reconstruction
from ..params import Params
from ..simulation import simulate_position

#: Width [samples] of the Gaussian that smooths the recorded position into a motion proxy.
SMOOTHING = 3.0


@dataclass(frozen=True)
class Floor:
    """The floor estimate [N or N·m]: over every usable sample, and over the weighted ones."""

    full: float
    weighted: float


def floor_estimate(
    params: Params, x: FloatArray, dt: float, reconstruction: Reconstruction, usable: FloatArray
) -> Floor:
    """The floor of a log with recorded position ``x`` for the friction model ``params`` under
    ``reconstruction`` (module documentation); ``usable`` is 1 on the samples a fit may use."""
    if reconstruction.source == "velocity":
        return Floor(0.0, 0.0)
    step = resolution(x)
    proxy = gaussian_filter1d(x, SMOOTHING, mode="nearest")
    sensed = np.round(proxy / step) * step if step > 0 else proxy
    drive = sensed if reconstruction.cutoff is None else lowpass(sensed, dt, reconstruction.cutoff)
    smooth = simulate_position(params, proxy, dt)
    seen = simulate_position(params, drive, dt)
    square = (smooth - seen) ** 2
    weighted = (usable > 0) & ~ambiguous_samples(sensed, filter_margin(reconstruction, dt))
    floor = _rms(square, weighted)
    return Floor(floor, floor)


def with_reversals(floor: Floor, mse_every: float, mse_weighted: float) -> Floor:
    """``floor`` with the error at the reversals an encoder cannot place: a fit that leaves
    ``mse_weighted`` on the samples it weighs and ``mse_every`` on every usable sample leaves
    the difference at those reversals."""
    return Floor(math.sqrt(max(mse_every - mse_weighted, 0.0) + floor.weighted**2), floor.weighted)


def _rms(square: FloatArray, rows: np.ndarray) -> float:
    return math.sqrt(float(np.mean(square[rows]))) if np.any(rows) else 0.0


__all__ = ["Floor", "floor_estimate", "with_reversals"]
