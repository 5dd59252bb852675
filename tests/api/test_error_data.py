"""Errors carry their data (docs/errors.md#error-data): ``kind``, ``field``, ``value`` and the rest
are attributes of every error of the package, whether Rust or Python raised it, so that callers
match on them instead of on the message. Every kind that can be raised is documented."""

from __future__ import annotations

import ast
import copy
import inspect
import pickle
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import leuven_rt as lr
from conftest import LUGRE, MAXWELL
from leuven_rt import _core
from leuven_rt.data.records import as_motion_data
from leuven_rt.errors import (
    DATA,
    KINDS,
    PYTHON_KINDS,
    ConcurrentUseError,
    DataError,
    DivergenceError,
    InputError,
    ModelFileError,
    OutputError,
    ParameterError,
    StackOverflowError,
    data_of,
)
from leuven_rt.modelfile import VERSION

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "python" / "leuven_rt"
DT = 1e-3
STIFF = dict(LUGRE, sigma0=1e6)  # explicit steps of 1e-2 s at 1e-2 m/s diverge (test_bad_input.py)
DIVERGING = np.concatenate([np.zeros(5), np.full(400, 1e-2)])
CLASSES = (ParameterError, InputError, DivergenceError, DataError, OutputError, ConcurrentUseError)


def maxwell(**changes: Any) -> dict[str, Any]:
    return {**MAXWELL, **changes}


def documented_kinds() -> dict[str, str]:
    """The rows of docs/errors.md#kinds: kind -> the classes column."""
    text = (ROOT / "docs" / "errors.md").read_text(encoding="utf-8")
    section = text.split("### Kinds", 1)[1].split("\n## ", 1)[0]
    return dict(re.findall(r"^\| `([a-z_]+)` \| ([^|]+) \|", section, flags=re.MULTILINE))


def test_every_kind_is_documented_and_every_documented_kind_exists() -> None:
    """The kinds of the extension (gms-core's variants, gms-dyn's, the bindings' own: listed by
    the extension itself) and of the Python modules (the registry in leuven_rt.errors) are each a
    row of docs/errors.md, and the table has no row for a kind that cannot be raised."""
    documented = documented_kinds()
    assert set(_core.ERROR_KINDS) <= KINDS
    assert sorted(KINDS - set(documented)) == []
    assert sorted(set(documented) - KINDS) == []


def test_the_extension_lists_gms_core_variants() -> None:
    """ERROR_KINDS comes from the Rust enums, not from a list kept by hand beside them."""
    for kind in ("not_finite", "elements_too_weak", "static_below_coulomb", "ripple_coefficient"):
        assert kind in _core.ERROR_KINDS
    for kind in ("too_many_elements", "both_hysteresis", "break_deflection", "concurrent_use"):
        assert kind in _core.ERROR_KINDS
    # The wrappers of gms-dyn's Error take the kind of what they wrap.
    assert not {"core", "channel", "state"} & set(_core.ERROR_KINDS)
    assert not PYTHON_KINDS & set(_core.ERROR_KINDS)


def _raised_class(call: ast.Call) -> str | None:
    """The name of the class a ``raise Name(...)`` makes (``error`` for a class passed in)."""
    return call.func.id if isinstance(call.func, ast.Name) else None


def _kinds_of(node: ast.expr) -> list[str] | None:
    """The literal kinds an expression can give: a string, or the branches of ``a if c else b``."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return [node.value]
    if isinstance(node, ast.IfExp):
        body, orelse = _kinds_of(node.body), _kinds_of(node.orelse)
        return None if body is None or orelse is None else body + orelse
    return None


def raise_sites() -> list[tuple[str, int, ast.Call]]:
    """Every ``raise C(...)`` of the package whose C is one of its error classes (or the class a
    helper was given, named ``error``)."""
    names = {cls.__name__ for cls in CLASSES} | {"error"}
    sites = []
    for path in sorted(PACKAGE.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.Raise) and isinstance(node.exc, ast.Call):
                if _raised_class(node.exc) in names:
                    sites.append((str(path.relative_to(ROOT)), node.lineno, node.exc))
    return sites


def test_every_raise_site_of_the_package_gives_a_known_kind() -> None:
    """Each error the Python modules raise names its kind (a literal of the registry, or the data
    of the error it re-raises); keywords are the documented data only."""
    sites = raise_sites()
    assert len(sites) > 150  # the walk found the package's raise sites
    problems = []
    dictionaries = {}  # `refused = {"kind": ...}` literals passed on as **refused
    for path in sorted(PACKAGE.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Assign) and isinstance(node.value, ast.Dict):
                keys = [key.value for key in node.value.keys if isinstance(key, ast.Constant)]
                if "kind" in keys:
                    dictionaries[path.name, ast.unparse(node.targets[0])] = node.value
    for path, line, call in sites:
        keywords = {keyword.arg: keyword.value for keyword in call.keywords if keyword.arg}
        unpacked = [keyword.value for keyword in call.keywords if keyword.arg is None]
        unknown = set(keywords) - set(DATA)
        if unknown:
            problems.append(f"{path}:{line} passes {sorted(unknown)}")
        if "kind" in keywords:
            kinds = _kinds_of(keywords["kind"])
            if kinds is None or not set(kinds) <= KINDS:
                problems.append(f"{path}:{line} kind {ast.unparse(keywords['kind'])}")
        elif unpacked:
            for value in unpacked:
                source = ast.unparse(value)
                literal = dictionaries.get((Path(path).name, source))
                if literal is not None:
                    kind = literal.values[[key.value for key in literal.keys].index("kind")]
                    if not set(_kinds_of(kind) or ["?"]) <= KINDS:
                        problems.append(f"{path}:{line} kind {ast.unparse(kind)}")
                elif "data_of(" not in source:
                    problems.append(f"{path}:{line} unpacks {source} without a kind")
        else:
            problems.append(f"{path}:{line} gives no kind")
    assert problems == []


def test_the_constructor_takes_the_data_and_the_message_stays() -> None:
    error = DataError("missing columns ['f']", kind="missing_column", field="f", expected=["t", "x", "f"])
    assert str(error) == "missing columns ['f']" and error.args == ("missing columns ['f']",)
    assert (error.kind, error.field, error.expected) == ("missing_column", "f", ["t", "x", "f"])
    assert (error.value, error.bound, error.index, error.sample, error.channel, error.got) == (None,) * 6
    assert isinstance(error, InputError) and isinstance(error, ValueError)
    assert data_of(error) == {"kind": "missing_column", "field": "f", "expected": ["t", "x", "f"]}
    for again in (pickle.loads(pickle.dumps(error)), copy.deepcopy(error)):
        assert type(again) is DataError and str(again) == str(error) and data_of(again) == data_of(error)
    with pytest.raises(TypeError):
        InputError("m", kinds="x")  # type: ignore[call-arg]
    keywords = [name for name, parameter in inspect.signature(InputError.__new__).parameters.items()
                if parameter.kind is inspect.Parameter.KEYWORD_ONLY]  # fmt: skip
    assert tuple(keywords) == DATA


def test_the_classes_are_the_extensions() -> None:
    """ConcurrentUseError moved into the extension beside the other three; all four carry data."""
    for cls in (ParameterError, InputError, DivergenceError, ConcurrentUseError):
        assert getattr(_core, cls.__name__) is cls
        assert cls.__module__ == "leuven_rt"
        assert all(getattr(cls, name) is None for name in DATA)
    assert issubclass(ConcurrentUseError, RuntimeError) and not issubclass(ConcurrentUseError, ValueError)
    assert issubclass(DivergenceError, ValueError)


def test_the_file_readers_class_is_a_parameter_error_of_the_extension() -> None:
    """ModelFileError is made beside the other four (a ParameterError subclass): the same data,
    and ``line`` and ``column`` of a syntax error, kept through pickling."""
    assert _core.ModelFileError is ModelFileError is lr.ModelFileError
    assert ModelFileError.__module__ == "leuven_rt"
    assert issubclass(ModelFileError, ParameterError)
    assert all(getattr(ModelFileError, name) is None for name in (*DATA, "line", "column"))
    error = refusal(lambda: lr.ModelFile.from_json('{"format": "leuven-rt model",\n "version": }'))
    assert type(error) is ModelFileError
    assert (error.kind, error.field, error.line, error.column) == ("not_json", None, 2, 13)
    again = pickle.loads(pickle.dumps(error))
    assert type(again) is ModelFileError and str(again) == str(error)
    assert (again.kind, again.line, again.column) == ("not_json", 2, 13)
    made = ModelFileError("m", kind="unknown_key", field="level.slope")
    assert (made.kind, made.field, made.line) == ("unknown_key", "level.slope", None)


def refusal(call: Any) -> Any:
    with pytest.raises(ValueError) as raised:
        call()
    return raised.value


RUST = [
    pytest.param(
        lambda: lr.Params(**maxwell(Fs=0.5)),
        ParameterError,
        {"kind": "static_below_coulomb", "field": "Fs", "value": 0.5, "bound": 1.0},
        id="Fs",
    ),
    pytest.param(
        lambda: lr.Params(**maxwell(W=[0.2, 0.2, -0.1, 0.2])),
        ParameterError,
        {"kind": "element", "field": "W[2]", "value": -0.1, "index": 2},
        id="W[2]",
    ),
    pytest.param(
        lambda: lr.Params(**maxwell(W=[0.1] * 4)),
        ParameterError,
        {"kind": "elements_too_weak", "field": "W", "bound": 1.5},
        id="weak",
    ),
    pytest.param(
        lambda: lr.Params(**maxwell(W=[0.5] * 40, Delta=[1e-6] * 40)),
        ParameterError,
        {"kind": "too_many_elements", "field": "W", "value": 40, "bound": 32},
        id="too-many",
    ),
    pytest.param(
        lambda: lr.Params(**maxwell(Delta=[1e-6] * 3)),
        ParameterError,
        {"kind": "element_lengths", "field": "Delta", "expected": 4, "got": 3},
        id="lengths",
    ),
    pytest.param(
        lambda: lr.simulate(MAXWELL, [0.0, 0.0, 0.0, np.nan], DT),
        InputError,
        {"kind": "not_finite", "field": "v", "sample": 3, "channel": None},
        id="nan",
    ),
    pytest.param(
        lambda: lr.simulate(MAXWELL, [[0.0, 0.0], [0.0, np.inf]], DT),
        InputError,
        {"kind": "not_finite", "field": "v", "value": np.inf, "sample": 1, "channel": 1},
        id="channel",
    ),
    pytest.param(
        lambda: lr.simulate(MAXWELL, [0.0], 0.0),
        InputError,
        {"kind": "not_positive", "field": "dt", "value": 0.0},
        id="dt",
    ),
    pytest.param(
        lambda: lr.LeuvenModel(MAXWELL).step("1", DT),
        InputError,
        {"kind": "not_real", "field": "v", "value": "1"},
        id="step-text",
    ),
    pytest.param(
        lambda: lr.LeuvenModel(MAXWELL, channels=2).step(0.0, DT),
        InputError,
        {"kind": "channel_mismatch", "expected": 1, "got": 2},
        id="one-channel",
    ),
    pytest.param(
        lambda: lr.Compensator(MAXWELL, DT, "observer").step(np.nan),
        InputError,
        {"kind": "not_finite", "field": "x", "sample": 0},
        id="compensator",
    ),
    pytest.param(
        lambda: lr.OnlineIdentifier([1e-6], forgetting=1.5),
        ParameterError,
        {"kind": "not_in_unit_interval", "field": "forgetting", "value": 1.5},
        id="forgetting",
    ),
    pytest.param(
        lambda: lr.OnlineIdentifier([1e-6]).update(np.nan, 0.0, 0.0),
        InputError,
        {"kind": "not_finite", "field": "x", "sample": 0},
        id="update",
    ),
    pytest.param(
        lambda: lr.MassSystem(MAXWELL, mass=-1.0),
        ParameterError,
        {"kind": "not_positive", "field": "mass", "value": -1.0},
        id="mass",
    ),
    pytest.param(
        lambda: lr.level.PositionLevel(ripples=(lr.level.Ripple(0.0, (0.1,), (0.0,)),)),
        ParameterError,
        {"kind": "ripple_period", "field": "ripples[0].period", "value": 0.0, "index": 0},
        id="period",
    ),
    pytest.param(
        lambda: lr.level.PositionLevel(ripples=(lr.level.Ripple(1.0, (0.1, np.inf), (0.0, 0.0)),)),
        ParameterError,
        {"kind": "ripple_coefficient", "field": "ripples[0].cos[1]", "index": 1},
        id="coefficient",
    ),
    pytest.param(
        lambda: lr.level.PositionLevel(trend=(0.7, 0.5)),
        ParameterError,
        {"kind": "level_too_deep", "field": None, "bound": 1.0},
        id="deep",
    ),
    pytest.param(
        lambda: lr.PositionForce(ripples=(lr.level.Ripple(1e-12, (0.1,), (0.0,)),)),
        ParameterError,
        # The bound is the finest period resolved: 2^20 ulps of max(|middle| + half_stroke, 1) = 1.
        {
            "kind": "phase_unresolved",
            "field": "ripples[0].period",
            "value": 1e-12,
            "bound": 2.0**-32,
            "index": 0,
        },
        id="period-unresolved",
    ),
    pytest.param(
        lambda: lr.level.PositionLevel(half_stroke=1e-300),
        ParameterError,
        {"kind": "phase_unresolved", "field": "half_stroke", "value": 1e-300, "bound": 2.0**-32},
        id="half-stroke-unresolved",
    ),
    pytest.param(
        lambda: lr.level.PositionLevel(middle=1e12, half_stroke=1e-6),
        ParameterError,
        {"kind": "phase_unresolved", "field": "middle", "value": 1e12, "bound": None},
        id="middle-unresolved",
    ),
    pytest.param(
        lambda: lr.Params(**maxwell(sigma2_neg=-1.0)),
        ParameterError,
        {"kind": "negative", "field": "sigma2_neg", "value": -1.0},
        id="sigma2_neg",
    ),
    pytest.param(
        lambda: lr.Compensator(MAXWELL, DT, level=lr.level.PositionLevel(trend=(0.1, 0.0))),
        InputError,
        {"kind": "missing", "field": "x", "value": None},
        id="start-position",
    ),
    pytest.param(
        lambda: lr.Compensator(MAXWELL, DT, "observer").step_trajectory(0.0, np.nan),
        InputError,
        {"kind": "not_finite", "field": "x", "sample": 0},
        id="step-trajectory",
    ),
    pytest.param(
        lambda: lr.simulate(STIFF, DIVERGING, 1e-2, "explicit"),
        DivergenceError,
        {"kind": "diverged", "field": None, "value": None},
        id="diverged",
    ),
]


@pytest.mark.parametrize(("call", "cls", "data"), RUST)
def test_errors_raised_in_rust_carry_their_data(
    call: Any, cls: type[Exception], data: dict[str, Any]
) -> None:
    """gms-py builds the exception from gms-dyn's error (kind, field, value, …), not from the text."""
    error = refusal(call)
    assert type(error) is cls
    assert {name: getattr(error, name) for name in data} == data


def test_a_divergence_names_its_sample() -> None:
    for simulate in (lr.simulate, lr.reference.simulate):
        error = refusal(lambda simulate=simulate: simulate(STIFF, DIVERGING, 1e-2, "explicit"))
        assert type(error) is DivergenceError and error.kind == "diverged"
        assert isinstance(error.sample, int) and f"sample {error.sample}:" in str(error)


def test_a_state_outside_a_window_names_channel_element_and_limit() -> None:
    model = lr.LeuvenModel(MAXWELL)
    model.run(np.sin(np.linspace(0.0, 6.0, 300)) * 1e-3, DT)
    good = model.state
    zeta = good.zeta.copy()
    zeta[0, 1] = good.z[0] - 5e-6  # Delta[1] = 4e-6
    error = refusal(
        lambda: model.set_state(lr.ModelState(good.z, zeta, good.last_position, good.has_last_position))
    )
    assert (error.kind, error.field, error.index, error.channel, error.bound) == (
        "state_outside_window", "zeta[1]", 1, 0, 4e-6)  # fmt: skip
    assert error.value == pytest.approx(5e-6)


def test_a_swap_to_other_elements_gives_the_counts() -> None:
    compensator = lr.Compensator(MAXWELL, DT)
    error = refusal(lambda: compensator.set_params(maxwell(W=[1.0] * 3, Delta=[1e-6, 2e-6, 3e-6])))
    assert (error.kind, error.field, error.expected, error.got) == ("incompatible", "params", 4, 3)


PYTHON = [
    pytest.param(
        lambda: lr.Params.from_dict({**MAXWELL, "Fv": 1.0}),
        ParameterError,
        {"kind": "unknown_key", "field": "Fv"},
        id="unknown-key",
    ),
    pytest.param(
        lambda: lr.Params.from_dict({"Fc": 1.0}),
        ParameterError,
        {"kind": "missing_key", "field": "Fs"},
        id="missing-key",
    ),
    pytest.param(
        lambda: lr.Params(**{**MAXWELL, "Fc": "1"}),
        ParameterError,
        {"kind": "not_real", "field": "Fc", "value": "1"},
        id="text",
    ),
    pytest.param(
        lambda: lr.Params(**{**MAXWELL, "W": [0.5, 10**400, 0.5, 0.5]}),
        ParameterError,
        {"kind": "not_finite_value", "field": "W[1]", "index": 1},
        id="huge-int",
    ),
    pytest.param(
        lambda: lr.simulate(MAXWELL, np.zeros((2, 3, 4)), DT),
        InputError,
        {"kind": "shape", "field": "v", "got": (2, 3, 4)},
        id="shape",
    ),
    pytest.param(
        lambda: lr.LeuvenModel(MAXWELL).run(np.zeros((3, 5)), DT),
        InputError,
        {"kind": "shape", "field": "v", "got": (3, 5)},
        id="rows",
    ),
    pytest.param(
        lambda: lr.simulate(MAXWELL, [0.0], DT, "rk4"),
        InputError,
        {"kind": "invalid_choice", "field": "scheme", "value": "rk4"},
        id="scheme",
    ),
    pytest.param(
        lambda: lr.reference.simulate(MAXWELL, [0.0, np.nan], DT),
        InputError,
        {"kind": "not_finite", "field": "v", "sample": 1},
        id="reference",
    ),
    pytest.param(
        lambda: lr.OnlineIdentifier([1e-6]).run([0.0] * 3, [0.0] * 2, [0.0] * 3),
        InputError,
        {"kind": "input_length_mismatch", "field": "v", "expected": 3, "got": 2},
        id="log-lengths",
    ),
    pytest.param(
        lambda: lr.level.PositionLevel(ripples=({"period": 1.0, "cos": [0.1]},)),
        ParameterError,
        {"kind": "missing_key", "field": "ripples[0].sin", "index": 0},
        id="ripple-keys",
    ),
    pytest.param(
        lambda: lr.level.PositionLevel(ripples=({"period": "1", "cos": [0.1], "sin": [0.0]},)),
        ParameterError,
        {"kind": "not_real", "field": "ripples[0].period"},
        id="ripple-rewrapped",
    ),
    pytest.param(
        lambda: lr.ModelFile.from_dict(
            {"format": "leuven-rt model", "version": 1, "units": "linear", "friction": {**MAXWELL, "Fs": 0.5}}
        ),
        ModelFileError,
        {"kind": "static_below_coulomb", "field": "friction.Fs", "value": 0.5, "bound": 1.0},
        id="model-file-friction",
    ),
    pytest.param(
        lambda: lr.ModelFile.from_dict(
            {"format": "leuven-rt model", "version": VERSION + 1, "friction": MAXWELL}
        ),
        ModelFileError,
        {"kind": "invalid_choice", "field": "version", "line": None},
        id="version",
    ),
    pytest.param(
        lambda: lr.simulate(MAXWELL, [0.0, 0.0], DT, level=lr.level.PositionLevel(trend=(0.1, 0.0))),
        InputError,
        {"kind": "missing", "field": "x"},
        id="simulate-no-x",
    ),
    pytest.param(
        lambda: lr.simulate(MAXWELL, [0.0, 0.0], DT, x=[0.0, 0.0]),
        InputError,
        {"kind": "not_applicable", "field": "x"},
        id="simulate-x-alone",
    ),
    pytest.param(
        lambda: lr.simulate(
            MAXWELL, [0.0, 0.0], DT, x=[0.0], position_force=lr.PositionForce(trend=(1.0, 0.0))
        ),
        InputError,
        {"kind": "shape", "field": "x", "expected": (2,), "got": (1,)},
        id="simulate-x-shape",
    ),
    pytest.param(
        lambda: lr.reference.simulate(
            MAXWELL, [0.0, 0.0], DT, level=lr.level.PositionLevel(trend=(0.1, 0.0))
        ),
        InputError,
        {"kind": "missing", "field": "x"},
        id="reference-no-x",
    ),
    pytest.param(
        lambda: lr.reference.simulate(MAXWELL, [0.0, 0.0], DT, x=[0.0, 0.0]),
        InputError,
        {"kind": "not_applicable", "field": "x"},
        id="reference-x-alone",
    ),
    pytest.param(
        lambda: lr.reference.simulate(
            MAXWELL, [0.0, 0.0], DT, x=[0.0], position_force=lr.PositionForce(trend=(1.0, 0.0))
        ),
        InputError,
        {"kind": "shape", "field": "x", "expected": (1, 2), "got": (1, 1)},
        id="reference-x-shape",
    ),
    pytest.param(
        lambda: lr.PositionForce.from_dict([]),  # type: ignore[arg-type]
        ParameterError,
        {"kind": "wrong_type", "value": []},
        id="position-force-list",
    ),
    pytest.param(
        lambda: lr.PositionForce.from_dict({"amplitude": 1.0}),
        ParameterError,
        {"kind": "unknown_key", "field": "amplitude", "got": ["amplitude"]},
        id="position-force-key",
    ),
    pytest.param(
        lambda: lr.Compensator(MAXWELL, DT, position_force="cogging", x=0.0),  # type: ignore[arg-type]
        ParameterError,
        {"kind": "wrong_type", "field": "position_force", "value": "cogging"},
        id="position-force-type",
    ),
    pytest.param(
        lambda: lr.ModelFile.from_dict(
            {
                "format": "leuven-rt model",
                "version": 1,
                "units": "linear",
                "friction": MAXWELL,
                "level": {"ripples": [{"period": 1e-12, "cos": [0.1], "sin": [0.0]}]},
            }
        ),
        ModelFileError,
        {"kind": "phase_unresolved", "field": "level.ripples[0].period", "value": 1e-12, "index": 0},
        id="model-file-phase",
    ),
    pytest.param(
        lambda: as_motion_data({"t": np.arange(50.0), "f": np.zeros(50)}),
        DataError,
        {"kind": "missing_column", "field": "x", "expected": ["t", "x", "f"], "got": ["f", "t"]},
        id="missing-column",
    ),
]


@pytest.mark.parametrize(("call", "cls", "data"), PYTHON)
def test_errors_raised_in_python_carry_their_data(
    call: Any, cls: type[Exception], data: dict[str, Any]
) -> None:
    error = refusal(call)
    assert type(error) is cls
    assert {name: getattr(error, name) for name in data} == data


def test_effect_names_are_refused_with_the_choices() -> None:
    from leuven_rt.fitting.structure import CATALOGUE, parse_effects

    error = refusal(lambda: parse_effects("coulomb,sticky"))
    assert (error.kind, error.field, error.value, error.expected) == (
        "invalid_choice", "baseline", "sticky", list(CATALOGUE))  # fmt: skip


def test_a_file_error_keeps_its_data_under_the_file_name(tmp_path: Path) -> None:
    path = tmp_path / "p.json"
    path.write_text(
        '{"Fc": 1.0, "Fs": 0.5, "Vs": 1e-3, "delta": 2.0, "n": 2.0, "sigma0": 1e5}', encoding="utf-8"
    )
    error = refusal(lambda: lr.Params.load(path))
    assert str(error).startswith(f"{path}: `Fs`: `Fs` must be >= `Fc`")
    assert (error.kind, error.field, error.value) == ("static_below_coulomb", "Fs", 0.5)
    assert type(error) is ModelFileError
    path.write_text('{"Fc": 1.0,\n "Fs": }', encoding="utf-8")
    syntax = refusal(lambda: lr.Params.load(path))
    assert type(syntax) is ModelFileError and str(syntax).startswith(f"{path}: not JSON")
    assert (syntax.kind, syntax.field, syntax.line, syntax.column) == ("not_json", None, 2, 8)
    missing = refusal(lambda: lr.Params.load(tmp_path / "missing.json"))
    assert (missing.kind, missing.value) == ("unreadable_file", str(tmp_path / "missing.json"))


def test_the_original_leuven_stack_has_the_same_attributes() -> None:
    error = StackOverflowError("maxima", 40, 10)
    assert (error.kind, error.field, error.sample, error.bound) == ("stack_overflow", "maxima", 40, 10)
    assert all(hasattr(error, name) for name in DATA)


def test_a_second_thread_gets_the_data_of_concurrent_use() -> None:
    """The guard is gms-py's own (try_borrow_mut), not a match on PyO3's message."""
    import threading

    model = lr.LeuvenModel(MAXWELL)
    long = 1e-3 * np.sin(np.linspace(0.0, 500.0, 2_000_000))
    started = threading.Event()
    errors: list[BaseException] = []

    def run() -> None:
        started.set()
        model.run(long, DT)

    worker = threading.Thread(target=run)
    worker.start()
    started.wait()
    while worker.is_alive() and not errors:
        try:
            model.step(0.0, DT)
        except ConcurrentUseError as error:
            errors.append(error)
    worker.join()
    assert errors, "no call met the run"
    error = errors[0]
    assert (error.kind, error.field) == ("concurrent_use", None)
    assert str(error).startswith("this LeuvenModel is in use by another thread")


class _Reentrant:
    """A number whose conversion calls ``call`` while the compensator is inside ``step``."""

    def __init__(self, call: Any) -> None:
        self.call, self.raised = call, None

    def __float__(self) -> float:
        try:
            self.call()
        except ConcurrentUseError as error:
            self.raised = error
        return 0.0


@pytest.mark.parametrize(
    "method",
    [
        lambda c: c.step_trajectory(0.0, 0.0),
        lambda c: c.set_position(0.0),
        lambda c: c.position,
        lambda c: c.reset(),
    ],
    ids=["step_trajectory", "set_position", "position", "reset"],
)
def test_the_compensators_calls_borrow_through_the_guard(method: Any) -> None:
    """A call that meets the compensator inside another of its calls gets ConcurrentUseError with
    its kind, never PyO3's bare 'Already borrowed' RuntimeError: every method borrows through
    gms-py's guard (here the other call is ``step``, which holds the compensator while it converts
    its argument)."""
    compensator = lr.Compensator(MAXWELL, DT, position_force=lr.PositionForce(trend=(1.0, 0.0)), x=0.0)
    inner = _Reentrant(lambda: method(compensator))
    compensator.step(inner)  # type: ignore[arg-type]
    assert isinstance(inner.raised, ConcurrentUseError)
    assert (inner.raised.kind, inner.raised.field) == ("concurrent_use", None)
    assert compensator.position == 0.0  # nothing changed; the outer step moved at v = 0
