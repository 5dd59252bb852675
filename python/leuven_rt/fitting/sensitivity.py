"""The simulated friction force and its exact derivatives by every parameter, through gms-fit.

The forces are those of :func:`leuven_rt.simulate` (or :func:`~leuven_rt.simulate_position`) bit
for bit: each step is gms-core's. The derivatives are propagated along the same run (forward
sensitivities, docs/sensitivities.md), so one call costs about one simulation plus O(P·N) work per
step, where finite differences would cost P + 1 simulations.

The columns are always the asymmetric parameterisation, ``Fc, Fs, Vs, delta, n, sigma1, sigma2,
Fc_neg, Fs_neg, sigma2_neg``, then ``W[0] … W[N-1]`` (or ``sigma0`` for a linear spring). A
symmetric parameter set uses ``Fc`` on v ≥ 0 steps and the same value on v < 0 steps, so its
derivative by a common ``Fc`` is ``column("Fc") + column("Fc_neg")``; the same for ``Fs`` and
``sigma2``. The caller ties the columns it fits.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Literal, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _core
from .._checks import as_signal, as_step, check_scheme
from .._typing import FloatArray, Scheme
from ..errors import InputError, ParameterError, data_of, shown
from ..params import ParamsLike, core_params

#: What the samples of a signal are: velocities, or positions (v = (xₖ − xₖ₋₁)/dt, v = 0 first).
InputKind = Literal["velocity", "position"]

INPUT_KINDS = ("velocity", "position")

__all__ = ["INPUT_KINDS", "InputKind", "Sensitivities", "sensitivities", "simulate_sets"]


class Sensitivities(NamedTuple):
    """One run's forces and their derivatives at the chosen rows."""

    force: FloatArray
    """The friction force at every sample, shape (T,) [N]."""
    jacobian: FloatArray
    """dF/dθ at the chosen rows, shape (R, P), one column per name of ``columns``."""
    columns: tuple[str, ...]
    """The parameter of each column of ``jacobian``."""


def _as_input_kind(input: Any) -> bool:
    """Whether the signal is positions."""
    if input not in INPUT_KINDS:
        raise InputError(
            f"`input` must be 'velocity' or 'position', got {shown(input)!r}",
            kind="invalid_choice",
            field="input",
            value=input,
            expected=INPUT_KINDS,
        )
    return bool(input == "position")


def _as_one_signal(signal: ArrayLike) -> FloatArray:
    array, one_dimensional = as_signal(signal, "signal")
    if not one_dimensional:
        raise InputError(
            f"`signal` must have shape (T,), got shape {np.shape(signal)}",
            kind="shape",
            field="signal",
            expected="(T,)",
            got=np.shape(signal),
        )
    row: FloatArray = array[0]
    return row


def _as_rows(rows: ArrayLike | None, samples: int) -> NDArray[np.int64] | NDArray[np.uint64]:
    """Sample indices as a 1-D int64 (or uint64) array: every sample when ``rows`` is None. Their
    values (increasing, within the signal) are gms-fit's to check."""
    if rows is None:
        return np.arange(samples, dtype=np.int64)
    if isinstance(rows, (str, bytes, bytearray)):
        raise InputError(
            f"`rows` must be integer sample indices, got {type(rows).__name__}",
            kind="not_integer",
            field="rows",
            value=rows,
        )
    array = np.asarray(rows)
    if array.ndim != 1:
        raise InputError(
            f"`rows` must have shape (R,), got shape {array.shape}",
            kind="shape",
            field="rows",
            expected="(R,)",
            got=array.shape,
        )
    if array.size == 0:
        return np.zeros(0, dtype=np.int64)
    if array.dtype.kind == "i":
        return np.ascontiguousarray(array, dtype=np.int64)
    if array.dtype.kind == "u":
        return np.ascontiguousarray(array, dtype=np.uint64)
    raise InputError(
        f"`rows` must be integer sample indices, got dtype {array.dtype}",
        kind="not_integer",
        field="rows",
        value=str(array.dtype),
    )


def sensitivities(
    params: ParamsLike,
    signal: ArrayLike,
    dt: float,
    *,
    input: InputKind = "velocity",
    scheme: Scheme = "implicit",
    rows: ArrayLike | None = None,
) -> Sensitivities:
    """The friction force of ``params`` along ``signal`` (T,) from a relaxed channel, and its
    derivatives by every parameter at the samples ``rows`` (strictly increasing; every sample
    when None).

    ``input`` says whether ``signal`` holds velocities or positions; ``scheme`` is the step's
    (docs/model.md#discrete-step). The force equals :func:`leuven_rt.simulate`'s bit for bit.
    Rows let a long record be fitted on a subsample without holding T × P numbers.

    Raises :class:`~leuven_rt.InputError` for a bad signal, ``dt``, ``rows`` or option (naming
    the sample or row), :class:`~leuven_rt.DivergenceError` when the explicit step diverges and
    :class:`~leuven_rt.ParameterError` for a parameter set that breaks a rule.
    """
    validated = core_params(params)
    position = _as_input_kind(input)
    checked_scheme = check_scheme(scheme)
    values = _as_one_signal(signal)
    step = as_step(dt)
    indices = _as_rows(rows, values.shape[0])
    force, jacobian, columns = _core.sensitivities(validated, values, step, position, checked_scheme, indices)
    return Sensitivities(force, jacobian, tuple(columns))


def simulate_sets(
    params: Sequence[ParamsLike],
    signal: ArrayLike,
    dt: float,
    *,
    input: InputKind = "velocity",
    scheme: Scheme = "implicit",
) -> FloatArray:
    """The friction force of every parameter set of ``params`` along one ``signal`` (T,), each
    from a relaxed channel: shape (B, T), the sets run in parallel with the GIL released.

    Row b equals ``leuven_rt.simulate(params[b], signal, dt, scheme)`` (or
    ``simulate_position``) bit for bit. The sets may differ in their number of elements.
    """
    given: Any = params  # typed as a sequence; checked as what it really is
    if isinstance(given, (str, bytes, bytearray)) or not isinstance(given, Sequence):
        raise ParameterError(
            f"`params` must be a sequence of parameter sets, got {type(given).__name__}",
            kind="wrong_type",
            field="params",
        )
    validated = []
    for index, item in enumerate(given):
        try:
            validated.append(core_params(item))
        except ParameterError as error:
            # The set's own data (the parameter at fault), under a message naming the set, which
            # `channel` gives as a refused run of one set does.
            raise ParameterError(
                f"params[{index}]: {error}", **{**data_of(error), "channel": index}
            ) from None
    position = _as_input_kind(input)
    checked_scheme = check_scheme(scheme)
    values = _as_one_signal(signal)
    step = as_step(dt)
    return _core.simulate_sets(validated, values, step, position, checked_scheme)
