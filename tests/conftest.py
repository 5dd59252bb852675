"""Shared hypothesis strategies and helpers for the Rust-vs-reference and API tests.

Parameter sets are drawn as plain dicts with the keys of docs/parameters.md#keys (the parameter-file form),
so that every test can pass them to either implementation or to ``Params``.
"""

from __future__ import annotations

import ctypes
import functools
import importlib.util
import json
import shutil
import subprocess
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

from leuven_rt import ModelFile, Params

#: The fuzzing suite's budget (tests/fuzz): a fixed number of inputs per test, drawn from a fixed
#: seed (derandomize), so that every run tries the same inputs and the suite stays within about a
#: minute. No deadline: the machines are shared and slow. Nothing is written to a database.
settings.register_profile(
    "fuzz",
    max_examples=150,
    stateful_step_count=30,
    deadline=None,
    derandomize=True,
    database=None,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much],
)
#: Use in the fuzz tests as ``@FUZZ`` (or ``FUZZ`` as a state machine's ``TestCase.settings``).
FUZZ = settings.get_profile("fuzz")

#: A fixed Maxwell-slip model (asymmetric, N = 4) for the example-based tests.
MAXWELL: dict[str, Any] = dict(
    Fc=1.0, Fs=1.5, Fc_neg=0.7, Fs_neg=1.2, Vs=1e-3, delta=2.0, n=2.0,
    sigma1=30.0, sigma2=0.4, W=[0.5, 0.5, 0.5, 0.5], Delta=[2e-6, 4e-6, 8e-6, 1.6e-5],
)  # fmt: skip
#: A fixed LuGre model (linear hysteresis, n = 1).
LUGRE: dict[str, Any] = dict(
    Fc=1.0, Fs=1.5, Vs=1e-3, delta=2.0, n=1.0, sigma0=1e5, sigma1=30.0, sigma2=0.4,
)  # fmt: skip


def log_uniform(low: float, high: float) -> st.SearchStrategy[float]:
    """Floats spread evenly in log between ``low`` and ``high``."""
    return st.floats(np.log10(low), np.log10(high)).map(lambda e: float(10.0**e))


@st.composite
def params_dicts(draw: st.DrawFn, linear: bool | None = None) -> dict[str, Any]:
    """Any valid parameter set: Maxwell slip with 1..32 elements, or linear ``sigma0``.

    n is in (0.5, 4) and is exactly 1 or 2 about half of the time; ``Fs == Fc`` and
    asymmetric ``Fc_neg``/``Fs_neg`` both occur, and so does a ``sigma2_neg`` of its own;
    ``sum(W)`` exceeds ``max(Fs, Fs_neg)`` by a drawn margin.
    """
    fc = draw(log_uniform(0.1, 10.0))
    fs = fc * draw(st.sampled_from([1.0]) | st.floats(1.0, 3.0))
    p: dict[str, Any] = dict(
        Fc=fc,
        Fs=fs,
        Vs=draw(log_uniform(1e-4, 1e-1)),
        delta=draw(st.floats(0.5, 3.0)),
        n=draw(st.sampled_from([1.0, 2.0]) | st.floats(0.5, 4.0, exclude_min=True, exclude_max=True)),
        sigma1=draw(st.sampled_from([0.0]) | st.floats(0.0, 100.0)),
        sigma2=draw(st.sampled_from([0.0]) | st.floats(0.0, 10.0)),
    )
    if draw(st.booleans()):
        p["Fc_neg"] = fc * draw(st.floats(0.3, 2.0))
        p["Fs_neg"] = p["Fc_neg"] * draw(st.floats(1.0, 3.0))
    if draw(st.booleans()):
        p["sigma2_neg"] = draw(st.sampled_from([0.0]) | st.floats(0.0, 10.0))
    if linear is None:
        linear = draw(st.integers(0, 3)) == 0
    if linear:
        p["sigma0"] = draw(log_uniform(1e3, 1e6))
        return p
    count = draw(st.integers(1, 32))
    weights = np.array(draw(st.lists(st.floats(0.05, 1.0), min_size=count, max_size=count)))
    peak = max(fs, p.get("Fs_neg", fs))
    total = peak * draw(st.floats(1.05, 3.0))
    p["W"] = (weights / weights.sum() * total).tolist()
    p["Delta"] = draw(st.lists(log_uniform(1e-7, 1e-4), min_size=count, max_size=count))
    return p


@st.composite
def velocity_signals(draw: st.DrawFn, samples: int, scale: float) -> np.ndarray:
    """A velocity signal of ``samples`` samples built from segments: sines, constant plateaus,
    exact zeros, and sign flips of what came before, with amplitudes up to ``scale``."""
    count = draw(st.integers(1, 6))
    cuts = sorted(draw(st.lists(st.integers(1, samples - 1), min_size=count - 1, max_size=count - 1)))
    pieces: list[np.ndarray] = []
    for start, stop in zip([0, *cuts], [*cuts, samples], strict=True):
        length = stop - start
        kind = draw(st.sampled_from(["sine", "plateau", "zeros", "flip"]))
        if kind == "sine":
            amplitude = scale * draw(st.floats(0.01, 1.0))
            cycles = draw(st.floats(0.2, 6.0))
            # Phases start at 0 or away from it; a first sample like 1e-189 (a tiny but nonzero
            # deflection) is covered on its own by
            # core/test_agreement.py::test_implicit_step_after_a_tiny_deflection_finds_the_root.
            phase = draw(st.sampled_from([0.0]) | st.floats(0.01, 2 * np.pi))
            piece = amplitude * np.sin(phase + 2 * np.pi * cycles * np.arange(length) / max(length, 1))
        elif kind == "plateau":
            level = draw(st.sampled_from([-1.0, 1.0])) * draw(st.floats(0.01, 1.0))
            piece = np.full(length, scale * level)
        elif kind == "zeros":
            piece = np.zeros(length)
        else:  # the signal so far, reversed in time and in sign
            previous = np.concatenate(pieces) if pieces else np.full(1, scale)
            piece = -np.resize(previous[::-1], length)
        pieces.append(piece)
    return np.concatenate(pieces)


#: Samples of :func:`small_log`.
SMALL_LOG_SAMPLES = 400


def small_log(**changes: Any) -> dict[str, Any]:
    """A valid small log (1 kHz, a slow sine) as columns, with ``changes`` applied (None drops one)."""
    t = np.arange(SMALL_LOG_SAMPLES) * 1e-3
    base: dict[str, Any] = {"t": t, "x": 1e-3 * np.sin(2 * np.pi * t), "f": np.cos(2 * np.pi * t)}
    base.update(changes)
    return {key: value for key, value in base.items() if value is not None}


@functools.cache
def family() -> ModuleType:
    """``benches/family.py``, the generator of the family of logs, as a module."""
    path = Path(__file__).resolve().parents[1] / "benches" / "family.py"
    spec = importlib.util.spec_from_file_location("leuven_rt_bench_family", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclasses look their module up while being made
    spec.loader.exec_module(module)
    return module


def max_relative_error(a: np.ndarray, b: np.ndarray, magnitude: np.ndarray | None = None) -> float:
    """max|a − b| / max|b| over the whole run (0 when both are all zero); with ``magnitude``
    (per sample, the size of what was summed into b), max|a − b| / max(|b| + magnitude)."""
    scale = float(np.max(np.abs(b) if magnitude is None else np.abs(b) + magnitude, initial=0.0))
    difference = float(np.max(np.abs(a - b), initial=0.0))
    if scale == 0.0:
        return 0.0 if difference == 0.0 else np.inf
    return difference / scale


def state_arrays(state: Any) -> tuple[np.ndarray, ...]:
    """A ModelState as a tuple of copied arrays, for exact comparison."""
    return tuple(
        np.array(getattr(state, name), copy=True)
        for name in ("z", "zeta", "last_position", "has_last_position")
    )


def assert_same_state(before: Any, after: Any) -> None:
    """Both checkpoints hold bit-identical arrays."""
    for name, x, y in zip(("z", "zeta", "last_position", "has_last_position"), state_arrays(before),
                          state_arrays(after), strict=True):  # fmt: skip
        assert x.shape == y.shape, name
        np.testing.assert_array_equal(x, y, err_msg=name, strict=True)


@pytest.fixture
def maxwell() -> dict[str, Any]:
    return dict(MAXWELL)


@pytest.fixture
def lugre() -> dict[str, Any]:
    return dict(LUGRE)


class _DiagnosisStandIn:
    def to_json(self) -> str:
        return json.dumps({"named_effects": []})


class IdentifyStandIn:
    """A stand-in of :class:`leuven_rt.discrepancy.Identification` for the log it was given, for
    the command-line tests that replace the fit (MAXWELL's parameters, the log's units and notes)."""

    params = Params(**MAXWELL)
    diagnosis = _DiagnosisStandIn()
    warnings = ()

    def __init__(self, data: Any = None) -> None:
        report: dict[str, Any] = {"held_out_rms": 0.1}
        notes = getattr(data, "notes", ())
        if notes:
            report["data_notes"] = list(notes)
        self.model = ModelFile(friction=self.params, units=getattr(data, "units", "linear"), report=report)

    def summary(self) -> str:
        return "fitted"


# --- the C library, for the tests that compare it with Python ---------------------------------

#: LEUVEN_RT_ERROR_MESSAGE_SIZE of include/leuven_rt.h.
MESSAGE_SIZE = 160


class CError(ctypes.Structure):
    """``struct leuven_rt_error``."""

    _fields_ = [
        ("field", ctypes.c_char_p),
        ("index", ctypes.c_size_t),
        ("message", ctypes.c_char * MESSAGE_SIZE),
    ]


def cargo_built(arguments: list[str], target: str, what: str) -> list[str]:
    """The files ``cargo build arguments`` (debug) made for ``target``, from cargo's own report
    of what it built. Skips the calling test where cargo is not on PATH."""
    if shutil.which("cargo") is None:
        pytest.skip(f"cargo is not on PATH: {what} cannot be built to compare with")
    command = ["cargo", "build", "--quiet", *arguments, "--message-format=json"]
    root = Path(__file__).parents[1]
    done = subprocess.run(command, cwd=root, capture_output=True, text=True, timeout=1200, check=False)
    assert done.returncode == 0, done.stderr
    built: list[str] = []
    for message in map(json.loads, done.stdout.splitlines()):
        if message.get("reason") == "compiler-artifact" and message["target"]["name"] == target:
            # An example or binary is its executable; a library, its shared object.
            executable = message.get("executable")
            built += (
                [executable]
                if executable
                else [name for name in message["filenames"] if name.endswith(".so")]
            )
    assert built, f"cargo built nothing for {target}"
    return built


def built_c_library() -> ctypes.CDLL:
    """The C library of this checkout (``cargo build -p gms-ffi``, debug; the path from cargo's
    own report of what it built), with the argument types of the calls the tests make. Skips
    the calling test where cargo is not on PATH."""
    library = ctypes.CDLL(cargo_built(["-p", "gms-ffi"], "gms_ffi", "the C library")[0])
    handle, status = ctypes.c_void_p, ctypes.c_int32
    library.leuven_rt_compensator_create_from_json.argtypes = [
        ctypes.c_char_p, ctypes.c_size_t, ctypes.c_double, ctypes.c_int32,
        ctypes.POINTER(handle), ctypes.POINTER(CError),
    ]  # fmt: skip
    library.leuven_rt_compensator_create_from_json_at.argtypes = [
        ctypes.c_char_p, ctypes.c_size_t, ctypes.c_double, ctypes.c_int32, ctypes.c_double,
        ctypes.POINTER(handle), ctypes.POINTER(CError),
    ]  # fmt: skip
    library.leuven_rt_compensator_step.argtypes = [handle, ctypes.c_double, ctypes.POINTER(ctypes.c_double)]
    library.leuven_rt_compensator_step_trajectory.argtypes = [
        handle,
        ctypes.c_double,
        ctypes.c_double,
        ctypes.POINTER(ctypes.c_double),
    ]
    for name in ("create_from_json", "create_from_json_at", "step", "step_trajectory"):
        getattr(library, f"leuven_rt_compensator_{name}").restype = status
    library.leuven_rt_compensator_destroy.argtypes = [handle]
    library.leuven_rt_compensator_destroy.restype = None
    return library
