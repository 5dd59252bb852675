"""The table of model-file cases (tests/fixtures/model_files/cases.json) through the Python
package: every case accepted or refused by ``leuven_rt.ModelFile`` as the table says, a refusal
raising :class:`ModelFileError` with the table's kind and key path. The C library is tested
against the same table (crates/gms-ffi/tests/model_file_cases.rs), and so is gms-file itself
(crates/gms-file/tests/cases.rs): the referee is docs/data-and-reports.md#model-file."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from leuven_rt import ModelFile, _core
from leuven_rt.errors import ModelFileError, ParameterError

TABLE = Path(__file__).parents[1] / "fixtures" / "model_files" / "cases.json"
CASES: list[dict[str, Any]] = json.loads(TABLE.read_text(encoding="utf-8"))["cases"]


def _strict_json(text: str) -> Any:
    """``text`` parsed by Python's json, or None where Python's parser would read it otherwise
    than JSON does (a key given twice: the last kept; NaN and Infinity: accepted; more digits than
    Python converts: refused)."""

    def pairs(items: list[tuple[str, Any]]) -> dict[str, Any]:
        if len({key for key, _ in items}) != len(items):
            raise ValueError("a key given twice")
        return dict(items)

    def constant(name: str) -> Any:
        raise ValueError(name)

    try:
        return json.loads(text, object_pairs_hook=pairs, parse_constant=constant)
    except ValueError:
        return None


#: The names of ``ModelFileError.kind`` each category of the table allows: a ``value`` refusal is
#: named by the rule broken (gms-core's variant in snake case, or the file's own rule).
NAMES = {
    "syntax": {"not_json"},
    "format": {"invalid_choice", "missing_key"},
    "shape": {"unknown_key", "missing_key", "repeated", "wrong_type", "wrong_length", "out_of_range"},
}
#: The name of the refusal, for the issue's cases and a few others.
NAMED = {
    "duplicate_key_top": "repeated",
    "duplicate_key_report": "repeated",
    "units_missing": "missing_key",
    "measurement_null": "wrong_type",
    "report_list": "wrong_type",
    "empty_harmonics": "harmonic_lengths",
    "nan_in_report": "not_json",
    "huge_integer": "out_of_range",
    "syntax_error": "not_json",
    "version_3": "invalid_choice",
    "version_missing": "missing_key",
    "unknown_key_top": "unknown_key",
    "trend_three": "wrong_length",
    "Fs_below_Fc": "static_below_coulomb",
    "W_negative": "element",
    "both_hysteresis": "both_hysteresis",
    "reconstruction_cutoff_zero": "not_positive",
}


def _outcome(call: Any) -> tuple[str | None, str | None]:
    try:
        call()
    except ModelFileError as error:
        return error.kind, error.field
    return None, None


@pytest.mark.parametrize("case", CASES, ids=[case["name"] for case in CASES])
def test_every_case_is_read_as_the_table_says(case: dict[str, Any]) -> None:
    text = case["text"]
    if case["accept"]:
        model = ModelFile.from_json(text)
        assert ModelFile.from_json(model.to_json()) == model
        return
    with pytest.raises(ModelFileError) as caught:
        ModelFile.from_json(text)
    error = caught.value
    assert isinstance(error, ParameterError) and isinstance(error, ValueError)
    assert error.field == case["key"], str(error)
    assert error.kind == NAMED.get(case["name"], error.kind), str(error)
    assert error.kind in _core.ERROR_KINDS, error.kind
    if case["kind"] == "value":
        assert not any(error.kind in names for names in NAMES.values()), (error.kind, str(error))
    else:
        assert error.kind in NAMES[case["kind"]], (error.kind, str(error))
    if case["kind"] == "syntax":
        assert error.line is not None and error.column is not None
        assert str(error).startswith("not JSON: ") and f"line {error.line}, column {error.column}" in str(
            error
        )
    else:
        assert error.line is None and error.column is None
    if case["key"] is not None:
        assert str(error).startswith(f"`{case['key']}`"), str(error)


@pytest.mark.parametrize("case", CASES, ids=[case["name"] for case in CASES])
def test_from_dict_agrees_with_from_json(case: dict[str, Any]) -> None:
    """Where Python's json reads the text as JSON does, ModelFile.from_dict of that object gives
    the same outcome as the text: the same reader decides."""
    mapping = _strict_json(case["text"])
    if mapping is None:
        assert case["kind"] in ("syntax", "shape")  # only texts that Python reads its own way
        return
    assert _outcome(lambda: ModelFile.from_dict(mapping)) == _outcome(
        lambda: ModelFile.from_json(case["text"])
    )


def test_the_table_covers_the_issue() -> None:
    """The seven kinds of input on which the two readers disagreed, and the syntax message."""
    names = {case["name"] for case in CASES}
    assert {
        "duplicate_key_top", "duplicate_key_report", "units_missing", "measurement_null", "report_list",
        "empty_harmonics", "nan_in_report", "huge_integer", "syntax_error",
    } <= names  # fmt: skip
    kinds = {case["kind"] for case in CASES}
    assert kinds == {None, "syntax", "format", "shape", "value"}
