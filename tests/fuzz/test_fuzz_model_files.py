"""Fuzzing the model-file readers against each other: model files built by hypothesis (valid ones,
and the same mutated: a key dropped, added, repeated or retyped, a number out of range, NaN, a
version changed, the text cut) are fed to Python's ``ModelFile.from_json`` and to the C library's
``leuven_rt_compensator_create_from_json`` (the shared library, through ctypes), which must agree:
both accept, or both refuse naming the same key path (the C message starts with it).

The C library is the one ``cargo build -p gms-ffi`` makes from this checkout
(``conftest.built_c_library``); without cargo the test skips, saying so. Budget: the ``fuzz``
profile of tests/conftest.py.
"""

from __future__ import annotations

import ctypes
import json
from typing import Any

import pytest
from hypothesis import given
from hypothesis import strategies as st

from conftest import FUZZ, MESSAGE_SIZE, CError, built_c_library
from leuven_rt import ModelFile
from leuven_rt.errors import ModelFileError

OK, INVALID_FILE, INVALID_PARAMETER = 0, 8, 2
#: The kinds of the reader's own refusals (syntax, format, keys and types), which C gives as
#: LEUVEN_RT_INVALID_FILE; a rule of the model (gms-core's kinds) may be LEUVEN_RT_INVALID_PARAMETER.
READER_KINDS = {"not_json", "invalid_choice", "missing_key", "unknown_key", "repeated", "wrong_type",
                "wrong_length", "out_of_range"}  # fmt: skip


@pytest.fixture(scope="module")
def c_library() -> ctypes.CDLL:
    return built_c_library()


def _c_read(library: ctypes.CDLL, text: str) -> tuple[int, str]:
    """The status and the message of the C library on ``text``; the compensator is destroyed."""
    data = text.encode("utf-8")
    out = ctypes.c_void_p()
    error = CError()
    status = library.leuven_rt_compensator_create_from_json(
        data, len(data), 1e-3, 1, ctypes.byref(out), ctypes.byref(error)
    )
    assert (status == OK) == (out.value is not None), "*out is written exactly on success"
    library.leuven_rt_compensator_destroy(out)
    return status, error.message.decode("utf-8", errors="replace")


# --- valid model files -------------------------------------------------------------------------

positive = st.floats(1e-3, 1e3)
small = st.floats(-0.05, 0.05)


@st.composite
def frictions(draw: st.DrawFn) -> dict[str, Any]:
    fc = draw(positive)
    out: dict[str, Any] = {"Fc": fc, "Fs": fc * draw(st.floats(1.0, 3.0)), "Vs": draw(positive),
                           "delta": draw(st.floats(0.5, 3.0)), "n": draw(st.floats(0.5, 3.0))}  # fmt: skip
    for key in ("sigma1", "sigma2"):
        if draw(st.booleans()):
            out[key] = draw(st.floats(0.0, 100.0))
    if draw(st.booleans()):
        out["sigma0"] = draw(st.floats(1.0, 1e6))
    else:
        count = draw(st.integers(1, 6))
        out["W"] = [out["Fs"] / count * draw(st.floats(1.1, 2.0)) for _ in range(count)]
        out["Delta"] = [draw(st.floats(1e-7, 1e-4)) for _ in range(count)]
    return out


@st.composite
def position_terms(draw: st.DrawFn) -> dict[str, Any] | None:
    if draw(st.booleans()):
        return None
    ripples = []
    for harmonics in draw(st.lists(st.integers(1, 3), max_size=2)):
        cos = [draw(small) for _ in range(harmonics)]
        sin = [draw(small) for _ in range(harmonics)]
        ripples.append({"period": draw(st.floats(1e-3, 1.0)), "cos": cos, "sin": sin})
    trend = [draw(small), draw(small)]
    return {
        "middle": draw(small),
        "half_stroke": draw(st.floats(1e-3, 1.0)),
        "trend": trend,
        "ripples": ripples,
    }


# Empty containers are leaves: a container the recursion draws holds at least one value, since
# hypothesis deprecates an `extend` that can come back without drawing from its argument.
scalars = (
    st.none()
    | st.booleans()
    | st.integers(-(10**20), 10**20)
    | st.text(max_size=8)
    | st.just([])
    | st.just({})
)
json_values = st.recursive(
    scalars | st.floats(allow_nan=False, allow_infinity=False),
    lambda inner: (
        st.lists(inner, min_size=1, max_size=3)
        | st.dictionaries(st.text(max_size=6), inner, min_size=1, max_size=3)
    ),
    max_leaves=10,
)


@st.composite
def model_files(draw: st.DrawFn) -> dict[str, Any]:
    version = draw(st.sampled_from([1, 2, 3]))
    units = draw(st.sampled_from(["linear", "rotary"]))
    out: dict[str, Any] = {"format": "leuven-rt model", "version": version, "units": units}
    out["friction"] = draw(frictions())
    optional: dict[str, Any] = {
        "level": draw(position_terms()),
        "measurement": {"offset": draw(small), "inertia": draw(st.floats(0.0, 10.0))},
        "report": draw(st.none() | st.dictionaries(st.text(max_size=6), json_values, max_size=4)),
    }
    if version >= 2:
        optional["position_force"] = draw(position_terms())
        cutoffs = st.none() | st.floats(0.1, 500.0)
        sources = st.sampled_from(["velocity", "position"])
        # The acceleration's own cutoff came with version 3.
        extra = {"acceleration_cutoff": st.floats(0.1, 500.0)} if version == 3 else {}
        optional["reconstruction"] = draw(
            st.none() | st.fixed_dictionaries({"source": sources, "cutoff": cutoffs}, optional=extra)
        )
    for key, value in optional.items():
        if draw(st.booleans()):
            out[key] = value
    if draw(st.booleans()):
        return out["friction"]  # a plain parameter file
    return out


# --- mutations ---------------------------------------------------------------------------------


def _paths(value: Any, prefix: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    """Every path to a value inside ``value`` (keys and indices)."""
    out = [prefix]
    if isinstance(value, dict):
        for key, item in value.items():
            out += _paths(item, (*prefix, key))
    elif isinstance(value, list):
        for index, item in enumerate(value):
            out += _paths(item, (*prefix, index))
    return out


def _parent(document: Any, path: tuple[Any, ...]) -> Any:
    for step in path[:-1]:
        document = document[step]
    return document


REPLACEMENTS = st.sampled_from(
    [None, True, "1.0", [], {}, [1.0, 2.0, 3.0], 0, -1.0, 0.0, 1e308, 2, 3, "linear"]
)


@st.composite
def mutated_texts(draw: st.DrawFn) -> str:
    document = draw(model_files())
    kind = draw(
        st.sampled_from(["none", "drop", "add", "replace", "duplicate", "nan", "huge", "cut", "version"])
    )
    paths = [path for path in _paths(document) if path]
    if kind in ("drop", "add", "replace") and paths:
        path = draw(st.sampled_from(paths))
        parent = _parent(document, path)
        if kind == "drop":
            del parent[path[-1]]
        elif kind == "add" and isinstance(parent, dict):
            parent[draw(st.sampled_from(["extra", "Fq", "phase", "mass", "order"]))] = 1.0
        else:
            parent[path[-1]] = draw(REPLACEMENTS)
    if kind == "version" and "format" in document:
        document["version"] = draw(st.sampled_from([0, 4, 2.0, "2", None, -1]))
    text = json.dumps(document)
    if kind == "duplicate":
        key = draw(st.sampled_from(['"units"', '"Fc"', '"middle"', '"offset"', '"cutoff"', '"period"']))
        if key in text:
            text = text.replace(f"{key}:", f"{key}: 1, {key}:", 1)
    elif kind == "nan":
        text = text.replace(
            draw(st.sampled_from(['"Fc": ', '"offset": ', '"middle": '])), '"Fc": NaN, "x": ', 1
        )
    elif kind == "huge":
        text = text.replace('"Vs": ', '"Vs": 1' + "0" * draw(st.integers(300, 5000)) + ', "y": ', 1)
    elif kind == "cut":
        text = text[: draw(st.integers(0, max(len(text) - 1, 0)))]
    return text


# --- the test ----------------------------------------------------------------------------------


@FUZZ
@given(text=mutated_texts())
def test_python_and_c_read_model_files_alike(c_library: ctypes.CDLL, text: str) -> None:
    """Both accept or both refuse; a refusal names the same key path (or is a syntax error in
    both), and a refusal of the reader's own is LEUVEN_RT_INVALID_FILE in C."""
    try:
        ModelFile.from_json(text)
        python: tuple[str | None, str | None] = (None, None)
    except ModelFileError as error:
        python = (error.kind, error.field)
    status, message = _c_read(c_library, text)
    kind, key = python
    if kind is None:
        assert status == OK, message
        return
    assert status in (INVALID_FILE, INVALID_PARAMETER), (python, status, message)
    assert status == INVALID_FILE or kind not in READER_KINDS, (python, status, message)
    if kind == "not_json":
        assert message.startswith("not JSON: "), (python, message)
    elif key is not None:
        named = f"`{key}`"
        assert message.startswith(named[: MESSAGE_SIZE - 1]), (python, message)
