"""The two kinds of axis a log or a model describes, and the unit names that go with each.

A linear axis has its position in m, velocity in m/s and force in N; a rotary axis (a robot
joint) has rad, rad/s and N·m. The numbers are the same SI numbers either way: the kind only
changes what messages, summaries and plot labels call them, and which plausibility checks a log
gets (docs/data-and-reports.md#units).
"""

from __future__ import annotations

from typing import Any, Literal, NamedTuple

from .errors import ErrorClass, InputError, shown

#: The kind of axis: ``"linear"`` (m, m/s, N) or ``"rotary"`` (rad, rad/s, N·m).
Units = Literal["linear", "rotary"]
#: Every kind, the default first.
UNITS: tuple[Units, ...] = ("linear", "rotary")


class UnitNames(NamedTuple):
    """What the quantities of one kind of axis are measured in."""

    position: str
    velocity: str
    acceleration: str
    force: str
    inertia: str


_NAMES: dict[Units, UnitNames] = {
    "linear": UnitNames("m", "m/s", "m/s²", "N", "kg"),
    "rotary": UnitNames("rad", "rad/s", "rad/s²", "N·m", "kg·m²"),
}


def check_units(value: Any, name: str = "units", error: ErrorClass = InputError) -> Units:
    """``value`` if it is ``"linear"`` or ``"rotary"``; otherwise ``error`` naming ``name``."""
    if isinstance(value, str) and value in UNITS:
        return "linear" if value == "linear" else "rotary"
    raise error(
        f"`{name}` must be 'linear' or 'rotary', got {shown(value)!r:.80}",
        kind="invalid_choice",
        field=name,
        value=value,
        expected=UNITS,
    )


def unit_names(units: Units) -> UnitNames:
    """The unit of each quantity for ``units`` (checked)."""
    return _NAMES[check_units(units)]


__all__ = ["UNITS", "UnitNames", "Units", "check_units", "unit_names"]
