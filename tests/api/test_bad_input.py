"""Bad input: every entry point rejects it with a ValueError subclass of leuven_rt
(ParameterError, InputError, DivergenceError) that names the argument and carries what came as
data (``kind``, ``field``, ``value``, …; docs/errors.md#error-data), with a message that says what
was expected; a model that rejects a call keeps its state bit for bit; nothing crashes the
interpreter."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import leuven_rt
from conftest import LUGRE, MAXWELL, assert_same_state
from leuven_rt import (
    MAX_ELEMENTS,
    DivergenceError,
    InputError,
    LeuvenModel,
    ModelState,
    ParameterError,
    Params,
    reference,
)

DT = 1e-4
V = 1e-2 * np.sin(np.linspace(0.0, 6.0, 300))


def busy_model(channels: int = 1, params: dict[str, Any] = MAXWELL, scheme: str = "implicit") -> LeuvenModel:
    """A model whose state is not the relaxed one (z ≠ 0, elements moved, a last position)."""
    model = LeuvenModel(params, channels=channels, scheme=scheme)
    x = np.tile(np.cumsum(V) * DT * (0.1 if scheme == "explicit" else 1.0), (channels, 1))
    model.run_position(x, DT)
    return model


def same(got: Any, expected: Any) -> bool:
    """Equal, NaN equal to NaN."""
    if isinstance(got, float) and isinstance(expected, float) and np.isnan(got) and np.isnan(expected):
        return True
    return bool(got == expected)


def rejects(
    model: LeuvenModel | None,
    call: Callable[[], object],
    error: type[Exception],
    match: str | None = None,
    **data: Any,
) -> Any:
    """``call`` raises ``error`` (a ValueError) with the attributes ``data`` (and a message matching
    ``match``, where the text is the point) and leaves ``model``'s state as it was; returns the
    error."""
    assert issubclass(error, ValueError)
    before = model.state if model is not None else None
    with pytest.raises(error, match=match) as caught:
        call()
    if model is not None:
        assert_same_state(before, model.state)
    got = {name: getattr(caught.value, name) for name in data}
    assert all(same(got[name], value) for name, value in data.items()), (got, data)
    return caught.value


# --- signals ----------------------------------------------------------------------------------

#: Entry points taking a whole signal: name → (argument name, call(signal, dt, scheme) and model).
SignalCall = Callable[[Any, Any], tuple[Callable[[], object], "LeuvenModel | None"]]


def _function(function: Callable[..., object]) -> SignalCall:
    return lambda signal, dt: ((lambda: function(MAXWELL, signal, dt)), None)


def _method(position: bool) -> SignalCall:
    def make(signal: Any, dt: Any) -> tuple[Callable[[], object], LeuvenModel]:
        try:
            shape = np.shape(signal)
        except ValueError:  # ragged
            shape = ()
        model = busy_model(shape[0] if len(shape) == 2 and shape[0] > 0 else 1)
        run = model.run_position if position else model.run
        return (lambda: run(signal, dt)), model

    return make


SIGNAL_ENTRIES: dict[str, tuple[str, SignalCall]] = {
    "simulate": ("v", _function(leuven_rt.simulate)),
    "simulate_position": ("x", _function(leuven_rt.simulate_position)),
    "reference.simulate": ("v", _function(reference.simulate)),
    "reference.simulate_position": ("x", _function(reference.simulate_position)),
    "LeuvenModel.run": ("v", _method(position=False)),
    "LeuvenModel.run_position": ("x", _method(position=True)),
}
entries = pytest.mark.parametrize("entry", list(SIGNAL_ENTRIES))


def _with_bad_sample(shape: tuple[int, ...], index: tuple[int, ...], value: float) -> np.ndarray:
    signal = np.full(shape, 1e-3)
    signal[index] = value
    return signal


BAD_SHAPES = [
    pytest.param(np.float64(0.1), (), id="0-d"),
    pytest.param(np.zeros((1, 2, 3)), (1, 2, 3), id="3-d"),
    pytest.param(np.zeros((0, 5)), (0, 5), id="(0,T)"),
]


@entries
@pytest.mark.parametrize(("signal", "shape"), BAD_SHAPES)
def test_wrong_ndim_is_rejected(entry: str, signal: Any, shape: tuple[int, ...]) -> None:
    """0-d, 3-d and (0, T) signals raise InputError naming the argument, the expected shapes and
    the shape that came."""
    name, make = SIGNAL_ENTRIES[entry]
    call, model = make(signal, DT)
    error = rejects(model, call, InputError, kind="shape", field=name, got=shape)
    assert "(T,) or (B, T)" in error.expected


@entries
@pytest.mark.parametrize(
    ("shape", "index", "value", "where"),
    [
        ((20,), (7,), np.nan, "got nan at sample 7"),
        ((20,), (0,), np.inf, "got inf at sample 0"),
        ((20,), (19,), -np.inf, "got -inf at sample 19"),
        ((3, 20), (1, 4), np.nan, "got nan at channel 1, sample 4"),
        ((3, 20), (2, 0), -np.inf, "got -inf at channel 2, sample 0"),
    ],
)
def test_non_finite_samples_are_located(
    entry: str, shape: tuple[int, ...], index: tuple[int, ...], value: float, where: str
) -> None:
    """A NaN or ±inf sample raises InputError naming the argument, the rule (finite), the value,
    and the first bad sample (for 2-D input, channel and sample), as data and in the message."""
    name, make = SIGNAL_ENTRIES[entry]
    signal = _with_bad_sample(shape, index, value)
    signal.reshape(-1)[-1] = np.nan  # a later bad sample (row-major order) is not the one reported
    signal[index] = value
    call, model = make(signal, DT)
    channel = index[0] if len(shape) == 2 else None
    rejects(model, call, InputError, f"(?i)`{name}` must be finite, {where}$",
            kind="not_finite", field=name, value=value, sample=index[-1], channel=channel)  # fmt: skip


@entries
@pytest.mark.parametrize(
    ("signal", "message"),
    [
        pytest.param(["0.1", "abc"], r"must hold real numbers \(an integer or float dtype\), got dtype <U3",
                     id="strings"),
        pytest.param(np.array([0.1, object()], dtype=object), r"must hold real numbers .*got dtype object",
                     id="objects"),
        pytest.param(np.array([0.1, 1j]), r"must be real, got a complex array", id="complex"),
        pytest.param([0.1 + 0j, 0.2], r"must be real, got a complex array", id="complex-list"),
        pytest.param({"a": 1}, r"must hold real numbers .*got dtype object", id="dict"),
        pytest.param(None, r"must hold real numbers .*got dtype object", id="None"),
        pytest.param([[0.1, 0.2], [0.3]], r"must be an array of real numbers: .*inhomogeneous", id="ragged"),
    ],
)  # fmt: skip
def test_values_that_are_not_real_numbers_are_rejected(entry: str, signal: Any, message: str) -> None:
    """Strings, objects, complex numbers, None and ragged lists raise InputError naming the
    argument (with the value that came) and saying what was wrong with it."""
    name, make = SIGNAL_ENTRIES[entry]
    call, model = make(signal, DT)
    error = rejects(model, call, InputError, f"`{name}` ({message})", kind="not_real", field=name)
    assert error.value is signal


#: (dt, its kind); the message of each is in BAD_DT_MESSAGES, where the spelling of the value is
#: the point (Python's float spelling, the subnormal note).
BAD_DT = [
    pytest.param(0.0, "not_positive", id="zero"),
    pytest.param(-1e-3, "not_positive", id="negative"),
    pytest.param(float("nan"), "not_positive", id="nan"),
    pytest.param(float("inf"), "not_positive", id="inf"),
    pytest.param(-float("inf"), "not_positive", id="-inf"),
    pytest.param(1e-310, "not_positive", id="subnormal"),
    pytest.param("1e-3", "not_real", id="string"),
    pytest.param(True, "not_real", id="bool"),
    pytest.param(None, "not_real", id="None"),
]
BAD_DT_MESSAGES = [
    pytest.param(0.0, r"`dt` must be finite and > 0, got 0\.0$", id="zero"),
    pytest.param(-1e-3, r"`dt` must be finite and > 0, got -0\.001$", id="negative"),
    pytest.param(float("nan"), r"`dt` must be finite and > 0, got nan$", id="nan"),
    pytest.param(-float("inf"), r"`dt` must be finite and > 0, got -inf$", id="-inf"),
    pytest.param(
        1e-310,
        r"`dt` must be finite and > 0, got 1e-310 \(a subnormal number: at least 2.2e-308 is needed\)$",
        id="subnormal",
    ),
    pytest.param("1e-3", r"`dt` must be a real number, got '1e-3'", id="string"),
]


@entries
@pytest.mark.parametrize(("dt", "kind"), BAD_DT)
def test_bad_dt_is_rejected(entry: str, dt: Any, kind: str) -> None:
    """dt ≤ 0, NaN, ±inf, a string, a bool or None raise InputError naming `dt`, the rule and
    what came."""
    _, make = SIGNAL_ENTRIES[entry]
    call, model = make(V, dt)
    rejects(model, call, InputError, kind=kind, field="dt", value=dt)


@entries
@pytest.mark.parametrize(("dt", "message"), BAD_DT_MESSAGES)
def test_bad_dt_messages_spell_the_value_as_python_does(entry: str, dt: Any, message: str) -> None:
    """Rust and the numpy reference spell the value alike: 0.0, -0.001, nan, -inf, the note on a
    subnormal number."""
    _, make = SIGNAL_ENTRIES[entry]
    call, model = make(V, dt)
    rejects(model, call, InputError, message)


@pytest.mark.parametrize("method", ["step", "step_position"])
@pytest.mark.parametrize(("dt", "kind"), BAD_DT)
def test_bad_dt_is_rejected_by_step(method: str, dt: Any, kind: str) -> None:
    """The per-sample fast path (step, step_position) rejects the same dt values with the same
    InputError as the block calls, and keeps the state."""
    model = busy_model()
    rejects(model, lambda: getattr(model, method)(1e-3, dt), InputError, kind=kind, field="dt", value=dt)


@pytest.mark.parametrize("method", ["step_channels", "step_channels_position"])
@pytest.mark.parametrize(("dt", "kind"), BAD_DT)
def test_bad_dt_is_rejected_by_step_channels(method: str, dt: Any, kind: str) -> None:
    """step_channels and step_channels_position reject bad dt with InputError, state kept."""
    model = busy_model(channels=2)
    rejects(
        model, lambda: getattr(model, method)([1e-3, 2e-3], dt), InputError, kind=kind, field="dt", value=dt
    )


@pytest.mark.parametrize(
    ("method", "name", "value", "kind"),
    [
        ("step", "v", float("nan"), "not_finite"),
        ("step", "v", float("-inf"), "not_finite"),
        ("step_position", "x", float("inf"), "not_finite"),
        pytest.param("step", "v", "0.1", "not_real", id="v-string"),
        pytest.param("step", "v", None, "not_real", id="v-None"),
        pytest.param("step", "v", True, "not_real", id="v-bool"),
        pytest.param("step_position", "x", "0.1", "not_real", id="x-string"),
    ],
)
def test_bad_sample_is_rejected_by_step(method: str, name: str, value: Any, kind: str) -> None:
    """A non-finite (or non-numeric) sample given to step/step_position raises InputError
    naming the argument and the value, state kept."""
    model = busy_model()
    rejects(model, lambda: getattr(model, method)(value, DT), InputError, kind=kind, field=name, value=value)


def test_position_differences_that_overflow_are_reported() -> None:
    """Finite positions whose difference overflows ((x_k − x_{k−1})/dt = ±inf) raise InputError
    naming the velocity, the value inf and the sample, in Rust and in the reference alike."""
    x = np.array([0.0, 1e308, -1e308, 0.0])
    for simulate in (leuven_rt.simulate_position, reference.simulate_position):
        rejects(
            None,
            lambda simulate=simulate: simulate(MAXWELL, x, DT),
            InputError,
            r"`v` must be finite, got inf at sample 1$",
            kind="not_finite",
            field="v",
            value=np.inf,
            sample=1,
        )
    rejects(None, lambda: LeuvenModel(MAXWELL).run_position(x, DT), InputError, kind="not_finite", sample=1)


def test_position_overflow_leaves_the_state_untouched() -> None:
    """run_position rejected because a position difference overflows keeps the model's state
    (runs are all-or-nothing: sample 0 is not committed either)."""
    model = LeuvenModel(MAXWELL)
    rejects(model, lambda: model.run_position(np.array([0.0, 1e308, -1e308]), DT), InputError, sample=1)


# --- model-bound shapes -----------------------------------------------------------------------


@pytest.mark.parametrize(
    ("channels", "signal", "expected"),
    [
        (2, np.zeros(5), "(2, T)"),
        (2, np.zeros((3, 5)), "(2, T)"),
        (1, np.zeros((2, 5)), "(T,) or (1, T)"),
    ],
)
def test_run_with_the_wrong_number_of_channels(channels: int, signal: np.ndarray, expected: str) -> None:
    """run (and run_position) want (B, T) for a B-channel model, (T,) or (1, T) for one channel;
    anything else raises InputError with the expected and the given shape, state kept."""
    model = busy_model(channels)
    data = {"kind": "shape", "expected": expected, "got": signal.shape}
    rejects(model, lambda: model.run(signal, DT), InputError, field="v", **data)
    rejects(model, lambda: model.run_position(signal, DT), InputError, field="x", **data)


@pytest.mark.parametrize(
    ("signal", "data"),
    [
        pytest.param(np.zeros(3), {"kind": "shape", "expected": (2,), "got": (3,)}, id="(3,)"),
        pytest.param(np.zeros(1), {"kind": "shape", "expected": (2,), "got": (1,)}, id="(1,)"),
        pytest.param(np.zeros((2, 1)), {"kind": "shape", "expected": (2,), "got": (2, 1)}, id="(2,1)"),
        pytest.param(0.0, {"kind": "shape", "expected": (2,), "got": ()}, id="0-d"),
        pytest.param(np.zeros((1, 2)), {"kind": "shape", "expected": (2,), "got": (1, 2)}, id="(1,2)"),
        pytest.param([0.0, np.nan], {"kind": "not_finite", "value": np.nan, "channel": 1}, id="nan"),
    ],
)  # fmt: skip
def test_step_channels_wants_one_sample_per_channel(signal: Any, data: dict[str, Any]) -> None:
    """step_channels on a 2-channel model wants shape (2,) and finite samples; anything else
    raises InputError with what was expected and what came, state kept."""
    model = busy_model(channels=2)
    rejects(model, lambda: model.step_channels(signal, DT), InputError, field="v", **data)
    rejects(model, lambda: model.step_channels_position(signal, DT), InputError, field="x", **data)


@pytest.mark.parametrize("method", ["step", "step_position"])
def test_step_on_a_multi_channel_model(method: str) -> None:
    """step/step_position advance one channel; on a 3-channel model they raise InputError that
    says so and points to step_channels, state kept."""
    model = busy_model(channels=3)
    rejects(model, lambda: getattr(model, method)(1e-3, DT), InputError,
            rf"`{method}` steps one channel, this model has 3: use `step_channels`",
            kind="channel_mismatch", expected=1, got=3)  # fmt: skip


def _replace(state: ModelState, **changes: Any) -> ModelState:
    fields = {name: getattr(state, name) for name in ("z", "zeta", "last_position", "has_last_position")}
    return ModelState(**{**fields, **changes})


def _shape(field: str, expected: tuple[int, ...], got: tuple[int, ...]) -> dict[str, Any]:
    return {"kind": "shape", "field": f"state.{field}", "expected": expected, "got": got}


@pytest.mark.parametrize(
    ("change", "data"),
    [
        pytest.param(lambda s: _replace(s, z=s.z[:1]), _shape("z", (2,), (1,)), id="z"),
        pytest.param(lambda s: _replace(s, z=s.z[:, None]), _shape("z", (2,), (2, 1)), id="z-2d"),
        pytest.param(lambda s: _replace(s, zeta=s.zeta[:, :3]), _shape("zeta", (2, 4), (2, 3)), id="zeta"),
        pytest.param(
            lambda s: _replace(s, zeta=s.zeta.ravel()), _shape("zeta", (2, 4), (8,)), id="zeta-flat"
        ),
        pytest.param(
            lambda s: _replace(s, last_position=np.zeros(3)), _shape("last_position", (2,), (3,)), id="last"
        ),
        pytest.param(
            lambda s: _replace(s, has_last_position=np.ones((2, 2), bool)),
            _shape("has_last_position", (2,), (2, 2)),
            id="has_last",
        ),
        pytest.param(
            lambda s: _replace(s, z=np.array([0.0, np.nan])),
            {"kind": "not_finite", "field": "state.z"},
            id="z-nan",
        ),
        pytest.param(
            lambda s: _replace(s, zeta=np.full((2, 4), np.inf)),
            {"kind": "not_finite", "field": "state.zeta"},
            id="zeta-inf",
        ),
        pytest.param(
            lambda s: (s.z, s.zeta, s.last_position, s.has_last_position),
            {"kind": "wrong_type", "field": "state"},
            id="tuple",
        ),
        pytest.param(
            lambda s: LeuvenModel(MAXWELL, channels=3).state, _shape("z", (2,), (3,)), id="other-model"
        ),
        pytest.param(
            lambda s: LeuvenModel(LUGRE, channels=2).state, _shape("zeta", (2, 4), (2, 0)), id="linear-model"
        ),
        pytest.param(
            lambda s: _replace(s, z=np.array(["a", "b"])),
            {"kind": "not_real", "field": "state.z"},
            id="z-strings",
        ),
        pytest.param(
            lambda s: _replace(s, has_last_position=np.array([1.0, 0.0])),
            {"kind": "wrong_type", "field": "state.has_last_position"},
            id="has_last-float",
        ),
    ],
)
def test_set_state_checks_shapes_and_values(
    change: Callable[[ModelState], Any], data: dict[str, Any]
) -> None:
    """set_state accepts only a ModelState with this model's shapes and finite values; anything
    else raises InputError naming the field, expected and given shape, and the state is kept."""
    model = busy_model(channels=2)
    bad = change(model.state)
    rejects(model, lambda: model.set_state(bad), InputError, **data)


# --- model construction -----------------------------------------------------------------------


@pytest.mark.parametrize(
    ("channels", "kind", "bound"),
    [
        (0, "out_of_range", 1),
        (-3, "out_of_range", 1),
        (sys.maxsize + 1, "out_of_range", sys.maxsize),
        (1.0, "not_integer", None),
        (2.5, "not_integer", None),
        ("2", "not_integer", None),
        (True, "not_integer", None),
        (None, "not_integer", None),
    ],
)
def test_channels_must_be_a_positive_int(channels: Any, kind: str, bound: int | None) -> None:
    """channels < 1, > sys.maxsize or not an int raises InputError naming `channels`, the
    accepted range and what came."""
    rejects(
        None,
        lambda: LeuvenModel(MAXWELL, channels=channels),
        InputError,
        kind=kind,
        field="channels",
        value=channels,
        bound=bound,
    )


BAD_SCHEMES = [
    pytest.param("Implicit", r"got 'Implicit'|got \"Implicit\"", id="capitalised"),
    pytest.param("rk4", r"got 'rk4'|got \"rk4\"", id="unknown"),
    pytest.param("", r"got ''|got \"\"", id="empty"),
    pytest.param(3, r"got 3", id="int"),
    pytest.param(None, r"got None", id="None"),
]


@pytest.mark.parametrize(("scheme", "message"), BAD_SCHEMES)
@pytest.mark.parametrize(
    "call",
    [
        pytest.param(lambda scheme: leuven_rt.simulate(MAXWELL, V, DT, scheme), id="simulate"),
        pytest.param(
            lambda scheme: leuven_rt.simulate_position(MAXWELL, V, DT, scheme), id="simulate_position"
        ),
        pytest.param(lambda scheme: reference.simulate(MAXWELL, V, DT, scheme), id="reference"),
        pytest.param(lambda scheme: LeuvenModel(MAXWELL, scheme=scheme), id="LeuvenModel"),
    ],
)
def test_unknown_scheme(call: Callable[[Any], object], scheme: Any, message: str) -> None:
    """An unknown scheme (or one that is not a str) raises InputError naming `scheme`, the two
    accepted names and what came."""
    rejects(
        None,
        lambda: call(scheme),
        InputError,
        rf"`scheme` must be 'implicit' or 'explicit', ({message})",
        kind="invalid_choice",
        field="scheme",
        value=scheme,
        expected=("implicit", "explicit"),
    )


@pytest.mark.parametrize("channels", [2**33, 2**62])
def test_absurd_channel_counts_do_not_crash_the_interpreter(channels: int) -> None:
    """LeuvenModel with a channel count that cannot be allocated raises a ValueError (or
    MemoryError) in a child interpreter, which survives and exits normally."""
    code = (
        "import leuven_rt\n"
        "try:\n"
        f"    leuven_rt.LeuvenModel({MAXWELL!r}, channels={channels})\n"
        "except (ValueError, MemoryError) as error:\n"
        "    print(type(error).__name__)\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60,
                            env={"RUST_BACKTRACE": "0", "PATH": ""})  # fmt: skip
    assert result.returncode == 0, result.stderr[-500:]
    assert result.stdout.strip() in ("InputError", "MemoryError")


# --- parameters -------------------------------------------------------------------------------

LUGRE_BASE = dict(LUGRE)
MAXWELL_SYMMETRIC = {k: v for k, v in MAXWELL.items() if k not in ("Fc_neg", "Fs_neg")}


def _rule(kind: str, field: str | None, value: Any = None, **more: Any) -> dict[str, Any]:
    """The data of a refused parameter set (value None: not checked)."""
    return {"kind": kind, "field": field, **({} if value is None else {"value": value}), **more}


NAN, INF = float("nan"), float("inf")
BAD_PARAMS = [
    # (changes to the symmetric Maxwell set (None deletes a key), the error's data)
    ({"Fc": 0.0}, _rule("not_positive", "Fc", 0.0)),
    ({"Fc": -1.0}, _rule("not_positive", "Fc", -1.0)),
    ({"Fc": NAN}, _rule("not_positive", "Fc", NAN)),
    ({"Fc": INF, "Fs": INF}, _rule("not_positive", "Fc", INF)),
    ({"Fc": 1e-310}, _rule("not_positive", "Fc", 1e-310)),
    ({"Fs": 0.5}, _rule("static_below_coulomb", "Fs", 0.5, bound=1.0)),
    ({"Vs": 0.0}, _rule("not_positive", "Vs", 0.0)),
    ({"Vs": -1e-3}, _rule("not_positive", "Vs", -1e-3)),
    ({"delta": 0.0}, _rule("not_positive", "delta", 0.0)),
    ({"delta": -2.0}, _rule("not_positive", "delta", -2.0)),
    ({"n": 0.0}, _rule("not_positive", "n", 0.0)),
    ({"n": -1.0}, _rule("not_positive", "n", -1.0)),
    ({"n": INF}, _rule("not_positive", "n", INF)),
    ({"sigma1": -1.0}, _rule("negative", "sigma1", -1.0)),
    ({"sigma1": NAN}, _rule("negative", "sigma1", NAN)),
    ({"sigma2": -0.5}, _rule("negative", "sigma2", -0.5)),
    ({"W": [1.0, 0.0, 1.0, 1.0]}, _rule("element", "W[1]", 0.0, index=1)),
    ({"W": [1.0, 1.0, -1.0, 1.0]}, _rule("element", "W[2]", -1.0, index=2)),
    ({"W": [1.0, 1.0, 1.0, NAN]}, _rule("element", "W[3]", NAN, index=3)),
    ({"Delta": [1e-6, 1e-6, 0.0, 1e-6]}, _rule("element", "Delta[2]", 0.0, index=2)),
    ({"Delta": [-1e-6, 1e-6, 1e-6, 1e-6]}, _rule("element", "Delta[0]", -1e-6, index=0)),
    ({"Delta": [1e-6, INF, 1e-6, 1e-6]}, _rule("element", "Delta[1]", INF, index=1)),
    ({"Fc_neg": 0.0}, _rule("not_positive", "Fc_neg", 0.0)),
    ({"Fc_neg": -0.5, "Fs_neg": 1.0}, _rule("not_positive", "Fc_neg", -0.5)),
    ({"Fc_neg": 0.8, "Fs_neg": 0.5}, _rule("static_below_coulomb", "Fs_neg", 0.5, bound=0.8)),
    ({"Fs_neg": 0.5}, _rule("static_below_coulomb", "Fs_neg", 0.5, bound=1.0)),  # Fc_neg defaults to Fc
    ({"Fs_neg": NAN}, _rule("not_positive", "Fs_neg", NAN)),
    ({"W": [0.25] * 4}, _rule("elements_too_weak", "W", 1.0, bound=1.5)),
    ({"W": [0.375] * 4}, _rule("elements_too_weak", "W", 1.5, bound=1.5)),
    ({"Fs_neg": 2.5}, _rule("elements_too_weak", "W", 2.0, bound=2.5)),
    (
        {"W": [1.0] * (MAX_ELEMENTS + 1), "Delta": [1e-6] * (MAX_ELEMENTS + 1)},
        _rule("too_many_elements", "W", MAX_ELEMENTS + 1, bound=MAX_ELEMENTS),
    ),
    ({"W": [], "Delta": []}, _rule("empty_elements", "W")),
    ({"W": [1.0, 1.0, 1.0]}, _rule("element_lengths", "Delta", expected=3, got=4)),
    ({"Delta": [1e-6] * 5}, _rule("element_lengths", "Delta", expected=4, got=5)),
    ({"Delta": None}, _rule("missing_key", "Delta")),
    ({"W": None}, _rule("missing_key", "W")),
    ({"W": None, "Delta": None}, _rule("neither_hysteresis", "sigma0")),
    ({"sigma0": 1e5}, _rule("both_hysteresis", "sigma0")),
    ({"Fc": "1.0"}, _rule("not_real", "Fc", "1.0")),
    ({"Vs": True}, _rule("not_real", "Vs", True)),
    ({"n": None}, _rule("not_real", "n")),
    ({"sigma1": None}, _rule("not_real", "sigma1")),
    ({"Fc": 1 + 0j}, _rule("not_real", "Fc", 1 + 0j)),
    ({"W": "abcd"}, _rule("not_real", "W", "abcd")),
    ({"W": 2.0}, _rule("not_real", "W", 2.0)),
    ({"W": [[1.0, 1.0], [1.0, 1.0]]}, _rule("shape", "W")),
    ({"W": np.ones((2, 2))}, _rule("shape", "W", got=(2, 2))),
    ({"W": [1.0, "x", 1.0, 1.0]}, _rule("not_real", "W[1]", "x", index=1)),
    ({"Delta": [1e-6, 1e-6, None, 1e-6]}, _rule("not_real", "Delta[2]", index=2)),
]
LUGRE_BAD = [
    ({"sigma0": 0.0}, _rule("not_positive", "sigma0", 0.0)),
    ({"sigma0": -1e5}, _rule("not_positive", "sigma0", -1e5)),
    ({"sigma0": NAN}, _rule("not_positive", "sigma0", NAN)),
    ({"sigma0": "1e5"}, _rule("not_real", "sigma0", "1e5")),
    ({"W": [1.0]}, _rule("missing_key", "Delta")),
    ({"W": [1.0], "Delta": [1e-6]}, _rule("both_hysteresis", "sigma0")),
]
#: Where the text is the point: how values are spelled, the subnormal note, what each rule says.
PARAM_MESSAGES = [
    (
        {"Fc": 1e-310},
        r"`Fc` must be finite and > 0, got 1e-310 \(a subnormal number: at least 2.2e-308 is needed\)",
    ),
    ({"Fc": NAN}, r"`Fc` must be finite and > 0, got nan$"),
    ({"Fs": 0.5}, r"`Fs` must be >= `Fc` = 1\.0, got 0\.5$"),
    ({"Fc_neg": 0.8, "Fs_neg": 0.5}, r"`Fs_neg` must be >= `Fc_neg` = 0\.8, got 0\.5$"),
    ({"W": [0.25] * 4}, r"`sum\(W\)` must be > max\(`Fs`, `Fs_neg`\) = 1\.5, got sum\(W\) = 1\.0"),
    ({"W": [1.0, 1.0, 1.0]}, r"`W` and `Delta` must have the same length, got 3 and 4$"),
    ({"W": None, "Delta": None}, r"give either `sigma0` .* or `W` \+ `Delta` .*got neither$"),
    ({"Fc": 1 + 0j}, r"`Fc` must be a real number, got \(1\+0j\)$"),
]


def _changed(base: dict[str, Any], changes: dict[str, Any]) -> dict[str, Any]:
    out = dict(base)
    for key, value in changes.items():
        if value is None and key in ("W", "Delta", "sigma0", "Fc_neg", "Fs_neg"):
            out.pop(key, None)
        else:
            out[key] = value
    return out


BAD_PARAM_CASES = [pytest.param(_changed(MAXWELL_SYMMETRIC, c), d, id=f"maxwell-{i}-{'-'.join(c)}")
                   for i, (c, d) in enumerate(BAD_PARAMS)] + [
                  pytest.param(_changed(LUGRE_BASE, c), d, id=f"lugre-{i}-{'-'.join(c)}")
                   for i, (c, d) in enumerate(LUGRE_BAD)]  # fmt: skip


@pytest.mark.parametrize(("params", "data"), BAD_PARAM_CASES)
def test_every_parameter_rule_is_enforced(params: dict[str, Any], data: dict[str, Any]) -> None:
    """Each rule of docs/parameters.md#rules broken on its own raises ParameterError naming the key, the rule
    and what came (its kind, field and value), whether the set is built as Params, from a dict, or
    given to simulate or to LeuvenModel."""
    rejects(None, lambda: Params(**params), ParameterError, **data)
    rejects(None, lambda: Params.from_dict(params), ParameterError, **data)
    rejects(None, lambda: leuven_rt.simulate(params, V, DT), ParameterError, **data)
    rejects(None, lambda: reference.simulate(params, V, DT), ParameterError, **data)
    rejects(None, lambda: LeuvenModel(params), ParameterError, **data)


@pytest.mark.parametrize(("changes", "message"), PARAM_MESSAGES)
def test_parameter_messages_say_the_rule_and_spell_the_value(changes: dict[str, Any], message: str) -> None:
    """The message says the rule, expected against got, with floats as Python spells them."""
    rejects(None, lambda: Params(**_changed(MAXWELL_SYMMETRIC, changes)), ParameterError, message)


def test_the_parameter_fixtures_are_valid() -> None:
    """The bases that the rule table modifies are themselves valid (so each error comes from the
    one change)."""
    for params in (MAXWELL_SYMMETRIC, LUGRE_BASE):
        Params(**params)


@pytest.mark.parametrize(
    ("mapping", "message", "data"),
    [
        ({**MAXWELL, "mu": 0.3}, r"unknown parameter keys \['mu'\]; expected keys among \[.*'Fc'",
         {"kind": "unknown_key", "field": "mu"}),
        ({**MAXWELL, "fc": 1.0, "Sigma1": 2.0}, r"unknown parameter keys \['Sigma1', 'fc'\]",
         {"kind": "unknown_key", "field": "Sigma1"}),
        ({k: v for k, v in MAXWELL.items() if k != "Vs"}, r"missing parameter keys \['Vs'\]",
         {"kind": "missing_key", "field": "Vs"}),
        ({"W": [1.0], "Delta": [1e-6]}, r"missing parameter keys \['Fc', 'Fs', 'Vs', 'delta', 'n'\]",
         {"kind": "missing_key", "field": "Fc", "got": ["Delta", "W"]}),
        ([("Fc", 1.0)], r"parameters must be a mapping, got list", {"kind": "wrong_type", "field": None}),
        ("Fc=1", r"parameters must be a mapping, got str", {"kind": "wrong_type", "value": "Fc=1"}),
    ],
)  # fmt: skip
def test_from_dict_rejects_unknown_and_missing_keys(mapping: Any, message: str, data: dict[str, Any]) -> None:
    """Params.from_dict (and every function taking a dict) names unknown keys, lists the known
    ones, names missing required keys, and rejects non-mappings."""
    error = rejects(None, lambda: Params.from_dict(mapping), ParameterError, message, **data)
    if isinstance(mapping, dict):
        assert error.got == sorted(mapping)
        rejects(None, lambda: leuven_rt.simulate(mapping, V, DT), ParameterError, **data)
        rejects(None, lambda: LeuvenModel(mapping), ParameterError, **data)


@pytest.mark.parametrize(
    ("text", "message", "kind", "field"),
    [
        ("{", r"not JSON: EOF while parsing an object at line 1, column 1", "not_json", None),
        ('{"Fc": 1.0,}', r"not JSON: trailing comma at line 1, column 12", "not_json", None),
        ("", r"not JSON: EOF while parsing a value at line 1, column 0", "not_json", None),
        ("[1, 2]", r"a model file or parameter file must be a JSON object, got a sequence",
         "wrong_type", None),
        ("null", r"a model file or parameter file must be a JSON object, got null", "wrong_type", None),
        (None, r"a parameter file's text must be a str, got NoneType", "wrong_type", "text"),
        ('{"Fc": 1.0, "Fs": 1.5, "Vs": 1e-3, "delta": 2, "n": 1, "sigma0": -1}',
         r"`sigma0`: `sigma0` must be finite and > 0, got -1", "not_positive", "sigma0"),
        ('{"Fc": 1.0, "Fs": 1.5, "Vs": 1e-3, "delta": 2, "n": 1, "sigma0": NaN}',
         r"not JSON: expected value", "not_json", None),
    ],
)  # fmt: skip
def test_from_json_rejects_invalid_json(text: Any, message: str, kind: str, field: str | None) -> None:
    """Params.from_json turns invalid JSON, JSON that is not an object, and invalid values into
    ParameterError saying what was expected."""
    error = rejects(None, lambda: Params.from_json(text), ParameterError, message)
    assert (error.kind, error.field) == (kind, field)


def test_params_argument_of_the_wrong_type() -> None:
    """simulate and LeuvenModel reject a params argument that is neither Params nor a mapping."""
    for call in (lambda: leuven_rt.simulate(42, V, DT), lambda: LeuvenModel([1, 2])):
        rejects(
            None,
            call,
            ParameterError,
            r"`params` must be a leuven_rt.Params or a mapping, got (int|list)",
            kind="wrong_type",
            field="params",
        )


# --- divergence -------------------------------------------------------------------------------

STIFF = dict(LUGRE, sigma0=1e6)  # dt·|v|·σ0/g = 1e-2 · 1e-2 · 1e6 / 1 = 100 ≫ 2


def test_explicit_stiff_spring_diverges_naming_the_sample() -> None:
    """The explicit scheme with a stiff linear spring at a large dt raises DivergenceError that
    names the sample, says why and what to do; simulate, run and a step loop agree on the sample."""
    v = np.concatenate([np.zeros(5), np.full(400, 1e-2)])
    error = rejects(None, lambda: leuven_rt.simulate(STIFF, v, 1e-2, "explicit"), DivergenceError,
                    r"the explicit step diverged at sample (\d+): dt is too large for the stiffness; "
                    r"use the implicit scheme", kind="diverged", field=None)  # fmt: skip
    sample = error.sample
    assert f"sample {sample}:" in str(error)
    assert 5 < sample < v.size  # it took some growth to overflow, and not at rest
    model = LeuvenModel(STIFF, scheme="explicit")
    rejects(None, lambda: model.run(v, 1e-2), DivergenceError, kind="diverged", sample=sample)
    stepper = LeuvenModel(STIFF, scheme="explicit")
    for vk in v[:sample]:
        stepper.step(float(vk), 1e-2)
    rejects(stepper, lambda: stepper.step(float(v[sample]), 1e-2), DivergenceError, kind="diverged", sample=0)
    # the implicit scheme has no such limit
    assert np.isfinite(leuven_rt.simulate(STIFF, v, 1e-2, "implicit")).all()


def _diverge_step_channels() -> tuple[LeuvenModel, ModelState, DivergenceError]:
    """Steps 3 stiff explicit channels until channel 1 diverges; the others keep moving slowly."""
    model = LeuvenModel(STIFF, channels=3, scheme="explicit")
    for _ in range(400):
        before = model.state
        try:
            model.step_channels([1e-5, 1e-2, -1e-5], 1e-2)
        except DivergenceError as error:
            return model, before, error
    pytest.fail("no divergence")


def test_explicit_divergence_in_step_channels_names_the_channel() -> None:
    """step_channels with one channel diverging raises DivergenceError naming that channel, and
    that channel keeps the state it had before the call."""
    model, before, error = _diverge_step_channels()
    assert (error.kind, error.channel, error.sample) == ("diverged", 1, 0)
    assert "channel 1" in str(error), str(error)
    assert model.state.z[1] == before.z[1]


def test_step_channels_that_diverges_leaves_every_channel_untouched() -> None:
    """A step_channels call rejected with DivergenceError leaves every channel's state as it was,
    including the channels that did not diverge."""
    model, before, _ = _diverge_step_channels()
    assert_same_state(before, model.state)


def test_run_that_diverges_leaves_the_state_untouched() -> None:
    """LeuvenModel.run rejected with DivergenceError leaves the state as it was before the call
    (runs are all-or-nothing: the samples before the divergent one are not kept)."""
    model = LeuvenModel(STIFF, scheme="explicit")
    model.run(np.full(3, 1e-3), 1e-2)
    rejects(model, lambda: model.run(np.full(400, 1e-2), 1e-2), DivergenceError, kind="diverged")


# --- nothing crashes --------------------------------------------------------------------------

junk = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(-(2**70), 2**70),
    st.floats(allow_nan=True, allow_infinity=True),
    st.complex_numbers(),
    st.text(max_size=5),
    st.binary(max_size=5),
    st.lists(st.one_of(st.floats(), st.text(max_size=2), st.none()), max_size=4),
    st.lists(st.lists(st.floats(), max_size=3), max_size=3),
    st.builds(np.zeros, st.tuples(*[st.integers(0, 3)] * 3)),
    st.builds(lambda n: np.arange(n, dtype=np.int8), st.integers(0, 4)),
    st.builds(lambda n: np.ones(n, dtype=np.float32), st.integers(0, 4)),
    st.builds(lambda n: np.array(["1.0"] * n), st.integers(0, 4)),
)


@settings(max_examples=150, deadline=None)
@given(signal=junk, dt=junk, data=st.data())
def test_junk_never_escapes_as_anything_but_a_value_error(signal: Any, dt: Any, data: st.DataObject) -> None:
    """Arbitrary junk (including ragged lists) for the signal and dt of every entry point, the
    per-sample step and step_position included, either runs or raises a ValueError subclass of
    leuven_rt (never a TypeError, numpy's own ValueError, a panic or a crash), and a model that
    rejects it keeps its state."""
    model = busy_model(channels=1)
    calls: dict[str, Callable[[], object]] = {
        "simulate": lambda: leuven_rt.simulate(MAXWELL, signal, dt),
        "simulate_position": lambda: leuven_rt.simulate_position(MAXWELL, signal, dt),
        "reference.simulate": lambda: reference.simulate(MAXWELL, signal, dt),
        "run": lambda: model.run(signal, dt),
        "run_position": lambda: model.run_position(signal, dt),
        "step": lambda: model.step(signal, dt),
        "step_position": lambda: model.step_position(signal, dt),
        "step_channels": lambda: model.step_channels(signal, dt),
        "step_channels_position": lambda: model.step_channels_position(signal, dt),
    }
    name = data.draw(st.sampled_from(sorted(calls)), label="entry")
    before = model.state
    try:
        calls[name]()
    except (InputError, ParameterError, DivergenceError):
        assert_same_state(before, model.state)
