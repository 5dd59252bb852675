"""Where the motion reverses, how far it has travelled since, and how far presliding reaches.

Friction after a reversal runs through presliding (a hysteresis curve in the displacement since
the reversal) before it settles on the sliding curve. The fits split the samples by that
displacement, so this module finds the reversals and estimates the presliding range.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import pairwise

import numpy as np
from numpy.typing import NDArray
from scipy.signal import find_peaks

from .._typing import FloatArray

#: A reversal must swing back by this many position-noise levels (and by a millionth of the
#: stroke) to count: smaller wiggles are noise or quantization.
REVERSAL_SWING = 10.0
#: The presliding transition ends where the force change since the reversal reaches this share
#: of its sliding value.
TRANSITION_SHARE = 0.95


@dataclass(frozen=True, eq=False)
class Segments:
    """The record cut at its reversals."""

    starts: NDArray[np.intp]
    """First sample of every segment: 0, then each reversal."""
    travel: FloatArray
    """|x̂ − x̂(segment start)| at every sample [m]."""
    direction: FloatArray
    """+1 or −1 at every sample: the direction of the segment it belongs to."""
    swing: float
    """The smallest swing counted as a reversal [m]."""

    @property
    def reversals(self) -> int:
        return int(self.starts.size - 1)

    def segment_of(self) -> NDArray[np.intp]:
        """The segment index of every sample."""
        index = np.zeros(self.travel.size, dtype=np.intp)
        index[self.starts[1:]] = 1
        return np.cumsum(index)


def find_segments(x: FloatArray, x_filtered: FloatArray) -> Segments:
    """Reversals are the extrema of the filtered position whose prominence exceeds
    :data:`REVERSAL_SWING` times the position noise (the spread of x − x̂)."""
    noise = float(np.std(x - x_filtered))
    swing = max(REVERSAL_SWING * noise, 1e-6 * float(np.ptp(x_filtered)))
    maxima = find_peaks(x_filtered, prominence=swing)[0]
    minima = find_peaks(-x_filtered, prominence=swing)[0]
    starts = np.unique(np.concatenate(([0], maxima, minima))).astype(np.intp)
    ends = np.append(starts[1:], x.size - 1)
    travel = np.empty_like(x_filtered)
    direction = np.empty_like(x_filtered)
    for start, end in zip(starts, ends, strict=True):
        stop = x.size if end == x.size - 1 else end
        piece = x_filtered[start:stop] - x_filtered[start]
        travel[start:stop] = np.abs(piece)
        direction[start:stop] = 1.0 if x_filtered[end] >= x_filtered[start] else -1.0
    return Segments(starts=starts, travel=travel, direction=direction, swing=swing)


def transition_lengths(
    segments: Segments, force: FloatArray, noise_std: float, from_start: bool = False
) -> FloatArray:
    """Travel after each reversal until the force change reaches :data:`TRANSITION_SHARE` of its
    value in the second half of the segment, for the segments that clearly reach sliding (the
    transition takes less than a quarter of the travel, and the force change is well above the
    noise). The first segment starts from rest, not from a reversal: it is measured instead of
    the others when ``from_start``."""
    lengths = []
    bounds = np.append(segments.starts, force.size)
    pairs = pairwise(bounds[:2]) if from_start else pairwise(bounds[1:])
    for start, stop in pairs:
        travel = segments.travel[start:stop]
        total = float(travel[-1]) if travel.size else 0.0
        if travel.size < 8 or total <= 0.0:
            continue
        change = segments.direction[start] * (force[start:stop] - force[start])
        settled = float(np.median(change[travel >= 0.5 * total]))
        if settled <= 10.0 * noise_std:
            continue
        reached = np.nonzero(change >= TRANSITION_SHARE * settled)[0]
        if reached.size and travel[reached[0]] < 0.25 * total:
            lengths.append(float(travel[reached[0]]))
    return np.asarray(lengths)
