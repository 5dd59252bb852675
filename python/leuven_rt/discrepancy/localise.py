"""Where model and data disagree, in numbers: the residual's RMS and mean over named regions of
the record (near reversals, low-speed sliding, high speed, each direction, each third of the
positions visited, high acceleration), and which region a change of the model helped most."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .._typing import FloatArray
from ..data.reconstruction import travel_since_reversal

#: Regions smaller than this share of the usable samples are not reported.
MIN_SHARE = 0.03
#: Low speed: below this share of the top speed (99th percentile); high speed: above HIGH_SPEED.
LOW_SPEED = 0.1
HIGH_SPEED = 0.5
#: High acceleration: the top tenth of |a|.
HIGH_ACCELERATION = 90.0
#: A region stands out when its mean squared change is this many times the record's.
STANDS_OUT = 1.5


@dataclass(frozen=True)
class Region:
    name: str
    share: float
    """Share of the usable samples."""
    rms: float
    mean: float


@dataclass(frozen=True, eq=False)
class Layout:
    """The masks of the named regions on a log's usable samples."""

    masks: dict[str, NDArray[np.bool_]]
    usable: NDArray[np.bool_]

    @classmethod
    def of(
        cls, v: FloatArray, x: FloatArray, a: FloatArray, presliding: float, usable: NDArray[np.bool_]
    ) -> Layout:
        """``presliding``: the travel after a reversal counted as near it [m or rad]."""
        top = float(np.percentile(np.abs(v[usable]), 99)) if usable.any() else 0.0
        near = travel_since_reversal(x, v) <= presliding
        accel = np.abs(a)
        thirds = np.percentile(x[usable], [100.0 / 3.0, 200.0 / 3.0])
        masks = {
            "near reversals (presliding)": near,
            "low-speed sliding": ~near & (np.abs(v) < LOW_SPEED * top),
            "high speed": np.abs(v) > HIGH_SPEED * top,
            "moving in +x": v > 0,
            "moving in -x": v < 0,
            "lowest third of the positions": x < thirds[0],
            "middle third of the positions": (x >= thirds[0]) & (x <= thirds[1]),
            "highest third of the positions": x > thirds[1],
            "high acceleration": accel > np.percentile(accel[usable], HIGH_ACCELERATION),
        }
        kept = {name: mask & usable for name, mask in masks.items() if np.mean(mask[usable]) >= MIN_SHARE}
        return cls(kept, usable)

    def regions(self, residual: FloatArray) -> list[Region]:
        """Residual statistics per region; ``residual`` covers every sample."""
        total = int(np.count_nonzero(self.usable))
        out = []
        for name, mask in self.masks.items():
            part = residual[mask]
            out.append(
                Region(name, part.size / total, float(np.sqrt(np.mean(part**2))), float(np.mean(part)))
            )
        return out

    def where_improved(self, before: FloatArray, after: FloatArray, unit: str = "N") -> str:
        """The region where the residual's mean square dropped most against the whole record, or
        "everywhere" when no region stands out; ``unit`` is the force's."""
        usable = self.usable
        overall = float(np.mean(before[usable] ** 2 - after[usable] ** 2))
        best, best_drop = None, -np.inf
        for name, mask in self.masks.items():
            drop = float(np.mean(before[mask] ** 2 - after[mask] ** 2))
            if drop > best_drop:
                best, best_drop = name, drop
        rms_before = float(np.sqrt(np.mean(before[usable] ** 2)))
        rms_after = float(np.sqrt(np.mean(after[usable] ** 2)))
        if best is None or overall <= 0 or best_drop < STANDS_OUT * overall:
            return _describe("everywhere", 1.0, rms_before, rms_after, unit)
        mask = self.masks[best]
        return _describe(best, float(np.mean(mask[usable])), float(np.sqrt(np.mean(before[mask] ** 2))),
                         float(np.sqrt(np.mean(after[mask] ** 2))), unit)  # fmt: skip

    def where_unexplained(self, residual: FloatArray, noise_std: float, unit: str = "N") -> str:
        """The region with the largest excess of the residual over the noise (mean square − σ²)."""
        usable = self.usable
        overall = float(np.mean(residual[usable] ** 2)) - noise_std**2
        table = self.regions(residual)
        if not table:
            return _describe("everywhere", 1.0, float(np.sqrt(np.mean(residual[usable] ** 2))), None, unit)
        worst = max(table, key=lambda region: region.rms**2)
        if overall <= 0 or worst.rms**2 - noise_std**2 < STANDS_OUT * overall:
            return _describe("everywhere", 1.0, float(np.sqrt(np.mean(residual[usable] ** 2))), None, unit)
        return _describe(worst.name, worst.share, worst.rms, None, unit)


def _describe(name: str, share: float, before: float, after: float | None, unit: str = "N") -> str:
    numbers = f"rms {before:.3g} {unit}" if after is None else f"rms {before:.3g} -> {after:.3g} {unit}"
    return f"{name}: {numbers} over {share:.0%} of the samples"


__all__ = ["Layout", "Region"]
