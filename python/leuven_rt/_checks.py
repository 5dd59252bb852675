"""Coercion shared by every entry point that takes signals, step sizes and scheme names.

One owner per check: Python coerces types, dtypes and shapes; the values (finite samples, a
finite, positive, normal ``dt``) are gms-core's to check on the Rust paths, which scan each
signal once. The numpy reference has no Rust call behind it, so it adds the value checks
(:func:`require_finite`, :func:`check_dt`), with gms-core's messages, and the same bad input gets
the same error from either.
"""

from __future__ import annotations

import numbers
import sys
from collections.abc import Sequence
from typing import Any, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._typing import FloatArray, Scheme
from .errors import ErrorClass, InputError, ParameterError, shown

SCHEMES = ("implicit", "explicit")


def real_number(value: Any, name: str, error: ErrorClass = InputError) -> float:
    """A real number (not a bool, not text) as a float, refused with ``error`` naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise error(
            f"`{name}` must be a real number, got {shown(value)!r:.80}",
            kind="not_real",
            field=name,
            value=value,
        )
    try:
        return float(value)
    except OverflowError:  # an int beyond the float range
        raise error(
            f"`{name}` must be finite, got an integer of {len(str(value))} digits",
            kind="not_finite_value",
            field=name,
            value=value,
        ) from None


def real_array(
    values: Any, name: str, error: ErrorClass = InputError, *, label: str | None = None
) -> NDArray[Any]:
    """``values`` as a numpy array of an integer or float dtype (any shape), without copying when
    it already is one: text, bytes, booleans, dates, objects, structured records, complex numbers
    and masked arrays are refused with ``error`` naming ``name`` (or saying ``label``, e.g.
    "column `t`"), never read as numbers."""
    label = f"`{name}`" if label is None else label
    refused = {"kind": "not_real", "field": name, "value": values}
    if isinstance(values, (str, bytes, bytearray)):
        raise error(
            f"{label} must be real numbers, got {type(values).__name__} {shown(values)!r:.60}", **refused
        )
    if np.ma.isMaskedArray(values):
        raise error(
            f"{label} must be a plain array of real numbers, got a masked array: fill it "
            "(`.filled(value)`) or compress it (`.compressed()`) first, so that no mask is lost",
            **refused,
        )
    try:
        array = np.asarray(values)
    except (TypeError, ValueError, OverflowError) as failure:
        raise error(f"{label} must be an array of real numbers: {failure}", **refused) from None
    kind = array.dtype.kind
    if kind == "c":
        raise error(f"{label} must be real, got a complex array", **refused)
    if kind not in "iuf":
        what = "structured records" if array.dtype.names else f"dtype {array.dtype}"
        raise error(f"{label} must hold real numbers (an integer or float dtype), got {what}", **refused)
    return array


def as_signal(values: ArrayLike, name: str) -> tuple[FloatArray, bool]:
    """A (B, T) C-contiguous float64 array of its own, and whether ``values`` was (T,).

    The array never shares memory with ``values``: the Rust paths read it with the GIL released,
    and another thread writing the caller's array meanwhile must not change the result.

    Raises :class:`InputError` for values that are not real numbers (see :func:`real_array`) and
    for shapes other than (T,) or (B, T) with B ≥ 1. The samples are not scanned: gms-core refuses
    non-finite ones (naming channel and sample) on the Rust paths, :func:`require_finite` on the
    others.
    """
    raw = real_array(values, name)
    if raw.ndim not in (1, 2):
        raise InputError(
            f"`{name}` must have shape (T,) or (B, T), got shape {raw.shape}",
            kind="shape",
            field=name,
            expected="(T,) or (B, T)",
            got=raw.shape,
        )
    shared = raw is values or raw.base is not None  # the caller's memory, or a view of it
    array: FloatArray = np.asarray(raw, dtype=np.float64, order="C")
    if shared and np.may_share_memory(array, raw):
        array = array.copy()
    one_dimensional = array.ndim == 1
    if one_dimensional:
        array = array.reshape(1, -1)
    if array.shape[0] == 0:
        raise InputError(
            f"`{name}` must have at least one channel, got shape {array.shape}",
            kind="shape",
            field=name,
            expected="(T,) or (B, T) with B >= 1",
            got=array.shape,
        )
    return array, one_dimensional


def require_finite(array: FloatArray, name: str, one_dimensional: bool) -> None:
    """Refuses a non-finite sample of ``array`` ((T,) or (B, T)) with gms-core's message, naming
    the first one: only where no Rust call follows (the numpy reference, Python-side state)."""
    rows = array.reshape(1, -1) if array.ndim == 1 else array
    finite = np.isfinite(rows)
    if not finite.all():
        channel, sample = (int(index) for index in np.unravel_index(int(np.argmin(finite)), rows.shape))
        value = float(rows[channel, sample])
        where = f"sample {sample}" if one_dimensional else f"channel {channel}, sample {sample}"
        raise InputError(
            f"`{name}` must be finite, got {value} at {where}",
            kind="not_finite",
            field=name,
            value=value,
            sample=sample,
            channel=None if one_dimensional else channel,
        )


def as_channel_signal(values: ArrayLike, name: str, channels: int) -> tuple[FloatArray, bool]:
    """:func:`as_signal` for an object of ``channels`` channels: (T,) only when it has one
    channel, otherwise (``channels``, T)."""
    array, one_dimensional = as_signal(values, name)
    if array.shape[0] != channels or (one_dimensional and channels != 1):
        expected = "(T,) or (1, T)" if channels == 1 else f"({channels}, T)"
        raise InputError(
            f"`{name}` must have shape {expected}, got shape {np.shape(values)}",
            kind="shape",
            field=name,
            expected=expected,
            got=np.shape(values),
        )
    return array, one_dimensional


def as_channels(values: ArrayLike, name: str, channels: int) -> FloatArray:
    """One sample per channel: a float64 array of shape (channels,), and nothing else."""
    try:
        shape = np.shape(values)
    except ValueError:
        shape = None  # ragged: as_signal says what is wrong with it
    if shape is not None and shape != (channels,):
        raise InputError(
            f"`{name}` must have shape ({channels},), got shape {shape}",
            kind="shape",
            field=name,
            expected=(channels,),
            got=shape,
        )
    array, _ = as_signal(values, name)
    row: FloatArray = array[0]
    return row


def as_step(dt: Any) -> float:
    """The step size as a float: a real number, not a bool. Its value (finite, > 0, not
    subnormal) is gms-core's to check on the Rust paths; :func:`check_dt` checks it elsewhere."""
    if isinstance(dt, bool) or not isinstance(dt, numbers.Real):
        raise InputError(
            f"`dt` must be a real number, got {shown(dt)!r}", kind="not_real", field="dt", value=dt
        )
    try:
        return float(dt)
    except OverflowError:  # an int beyond the float range: as infinite as it gets
        raise InputError(
            f"`dt` must be finite and > 0, got an integer of {len(str(dt))} digits",
            kind="not_positive",
            field="dt",
            value=dt,
        ) from None


def check_dt(dt: Any) -> float:
    """:func:`as_step` and gms-core's rules on its value, for the paths that do not reach Rust
    (the numpy reference): finite and > 0, and not subnormal, with gms-core's messages."""
    value = as_step(dt)
    if not (np.isfinite(value) and value > 0.0):
        raise InputError(
            f"`dt` must be finite and > 0, got {value}", kind="not_positive", field="dt", value=value
        )
    if value < np.finfo(np.float64).tiny:  # its reciprocal would overflow
        raise InputError(
            f"`dt` must be finite and > 0, got {value} (a subnormal number: at least 2.2e-308 is needed)",
            kind="not_positive",
            field="dt",
            value=value,
        )
    return value


def check_channels(channels: Any) -> int:
    """A channel count: an integer (not a bool) from 1 to ``sys.maxsize``."""
    if isinstance(channels, bool) or not isinstance(channels, numbers.Integral):
        raise InputError(
            f"`channels` must be an integer >= 1, got {shown(channels)!r}",
            kind="not_integer",
            field="channels",
            value=channels,
        )
    count = int(channels)  # exact for any Integral
    if not 1 <= count <= sys.maxsize:
        raise InputError(
            f"`channels` must be an integer from 1 to {sys.maxsize}, got {channels}",
            kind="out_of_range",
            field="channels",
            value=count,
            bound=1 if count < 1 else sys.maxsize,
        )
    return count


def check_scheme(scheme: Any) -> Scheme:
    """'implicit' or 'explicit'."""
    if scheme not in SCHEMES:
        raise InputError(
            f"`scheme` must be 'implicit' or 'explicit', got {shown(scheme)!r}",
            kind="invalid_choice",
            field="scheme",
            value=scheme,
            expected=SCHEMES,
        )
    return cast("Scheme", str(scheme))


def as_real_list(name: str, values: Any, length: int | None = None) -> list[float]:
    """A flat sequence of real numbers (of ``length`` values, when given) as floats."""
    if isinstance(values, (str, bytes, bytearray)) or not (
        isinstance(values, Sequence) or hasattr(values, "__array__")
    ):
        raise ParameterError(
            f"`{name}` must be a sequence of real numbers, got {shown(values)!r:.80}",
            kind="not_real",
            field=name,
            value=values,
        )
    array = real_array(values, name, ParameterError)
    if array.ndim != 1:
        raise ParameterError(
            f"`{name}` must be a flat sequence of real numbers, got {shown(values)!r}",
            kind="shape",
            field=name,
            expected="(N,)",
            got=array.shape,
        )
    if length is not None and array.shape[0] != length:
        raise ParameterError(
            f"`{name}` must have {length} values, got {array.shape[0]}",
            kind="wrong_length",
            field=name,
            expected=length,
            got=array.shape[0],
        )
    return [float(value) for value in array.tolist()]


def as_log(x: ArrayLike, v: ArrayLike, f: ArrayLike | None) -> list[FloatArray]:
    """x, v (and f) as float64 arrays of one common shape (T,), T ≥ 1 (not scanned for
    finiteness: gms-core does that on the Rust path, :func:`require_finite` elsewhere)."""
    named = [("x", x), ("v", v)] + ([("f", f)] if f is not None else [])
    arrays = []
    for name, values in named:
        array, one_dimensional = as_signal(values, name)
        if not one_dimensional:
            raise InputError(
                f"`{name}` must have shape (T,), got shape {np.shape(values)}",
                kind="shape",
                field=name,
                expected="(T,)",
                got=np.shape(values),
            )
        arrays.append(array[0])
    length = arrays[0].shape[0]
    for (name, _), array in zip(named[1:], arrays[1:], strict=True):
        if array.shape[0] != length:
            raise InputError(
                f"`{name}` must have the length of `x`, {length}, got {array.shape[0]}",
                kind="input_length_mismatch",
                field=name,
                expected=length,
                got=array.shape[0],
            )
    return arrays
