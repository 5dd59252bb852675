"""The part of a long record that the rounds name effects on: whole segments spread over it.

Every fit simulates the record from its first sample, so the rounds' cost grows with the length
of the log while what they decide does not: which effects the motion shows, and how the file
reconstructs it. On a record longer than ``Settings.rounds_samples`` they run on a sample of it
(docs/effects.md#long-records):

- :data:`SEGMENTS` segments of equal length, ``rounds_samples`` samples in all, spread evenly over
  the record from its first sample to its last: every part of the log is represented in
  proportion (its speeds, its positions, its reversals, and what changes over time, such as a
  drift);
- each segment is simulated from a lead-in that starts where the model's state no longer
  remembers where it started: the start of the last stretch of monotone travel before the
  segment that is :data:`LEAD_TRAVEL` times the widest element of the presliding bank long (z
  has then settled to its sliding value), or the record's first sample. The lead-in is simulated,
  never fitted nor judged, so that the forces on the segment are those of a simulation of the
  whole record. It is at least :data:`MIN_LEAD` samples and at most :data:`LONGEST_LEAD`
  segments long (past that, in a log that dwells in presliding, the segment starts from the
  state that lead-in gives).

The segments are joined into one signal: a position drive is shifted at each joint so that it
continues where the last segment ended (no step in position, a zero velocity across it), a
velocity drive is joined as it is.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from ..data.reconstruction import Motion, last_reversal
from .solve import Target

#: Segments of a sampled record: few and long, so that few lead-ins are simulated, and enough that
#: the sample sees the whole record's variety.
SEGMENTS = 8
#: A lead-in covers monotone travel of this many times the widest element's Δ: z settles towards
#: its sliding value at a rate set by the bank's stiffness there, which its wide elements make
#: slow (with equal weights over the grid, 4 times leaves the forces off by a third of the noise
#: in rms, 64 times by 1–2 % of it).
LEAD_TRAVEL = 64.0
#: The longest lead-in, in segment lengths: a log that dwells in presliding longer than that (its
#: small loops remember the last large stroke) starts the segment from the state it gives.
LONGEST_LEAD = 8
#: The shortest lead-in: the noise is read from differences of up to this many samples
#: (:data:`~leuven_rt.data.signals.RESIDUAL_LAGS`), which must not join two segments.
MIN_LEAD = 64


@dataclass(frozen=True, eq=False)
class Sample:
    """Which samples of the record the sample holds, in order, and which of them are lead-ins."""

    take: NDArray[np.int64]
    lead: NDArray[np.bool_]
    starts: NDArray[np.int64]
    """Where each piece (a lead-in and its segment) begins in the sample."""

    @property
    def size(self) -> int:
        """The samples fitted and judged (lead-ins excluded)."""
        return int(np.count_nonzero(~self.lead))

    def of(self, target: Target, fit_rows: int) -> Target:
        """``target`` on the sample: the segments' samples weighted and judged as in ``target``,
        the lead-ins simulated but neither fitted nor judged, the drive joined as the module
        documentation says; the fit takes every k-th weighted sample, at most ``fit_rows``."""
        motion = target.motion
        take = self.take
        drive, v = motion.drive[take], motion.v[take]
        if motion.input == "position":
            # Each piece continues where the last ended: the step from the previous piece's last
            # sample to this one's first, taken out of the whole piece.
            jumps = np.zeros(take.size)
            jumps[self.starts[1:]] = drive[self.starts[1:] - 1] - drive[self.starts[1:]]
            drive = drive + np.cumsum(jumps)
            v[self.starts] = 0.0
        else:
            v = drive
        x, a = motion.x[take], motion.a[take]
        sampled = Motion(motion.reconstruction, motion.input, drive, v, x, a, motion.dt)
        weight = np.where(self.lead, 0.0, target.weight[take])
        stride = max(1, math.ceil(np.count_nonzero(weight) / fit_rows))
        let_go = None if target.let_go is None else target.let_go[take] & ~self.lead
        return replace(target, force=target.force[take], weight=weight, motion=sampled, tau=target.tau[take],
                       recorded_x=target.recorded_x[take], judged=target.judged[take] & ~self.lead,
                       stride=stride, let_go=let_go)  # fmt: skip


def segments(motion: Motion, widest: float, budget: int) -> Sample | None:
    """The sample of a record with ``motion`` (module documentation) for a presliding bank whose
    widest element is ``widest``; None when the record holds no more than ``budget`` samples."""
    samples = motion.x.size
    if samples <= budget:
        return None
    length = budget // SEGMENTS
    starts = np.round(np.linspace(0, samples - length, SEGMENTS)).astype(np.int64)
    since = last_reversal(motion.v)
    travel = np.abs(motion.x - motion.x[since])
    # At every sample, the latest one at or before it whose monotone travel reaches the lead's.
    index = np.arange(samples)
    settled = np.maximum.accumulate(np.where(travel >= LEAD_TRAVEL * widest, index, -1))
    take: list[NDArray[np.int64]] = []
    lead: list[NDArray[np.bool_]] = []
    pieces: list[int] = []
    at = 0
    for start in starts.tolist():
        begin = 0
        if start > 0:
            last = int(settled[start - 1])
            begin = int(since[last]) if last >= 0 else 0
            begin = max(min(max(begin, start - LONGEST_LEAD * length), start - MIN_LEAD), 0)
        pieces.append(at)
        take.append(np.arange(begin, start + length, dtype=np.int64))
        lead.append(take[-1] < start)
        at += start + length - begin
    return Sample(np.concatenate(take), np.concatenate(lead), np.array(pieces, dtype=np.int64))


__all__ = ["LEAD_TRAVEL", "LONGEST_LEAD", "MIN_LEAD", "SEGMENTS", "Sample", "segments"]
