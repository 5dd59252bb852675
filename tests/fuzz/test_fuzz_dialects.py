"""Fuzzing the CSV dialects users export (docs/data-and-reports.md#csv-dialects): a valid log
written with `,`, `;` (decimal commas or points) or tabs, names and numbers quoted or not, any
line ending, a byte-order mark, spaces around the names, blank lines, empty trailing columns;
valid, or broken in one way (no header, a units row, a header repeated among the rows, a ragged
line, a text cell, a name given twice, a missing column).

Each must load to the same numbers as the plain CSV of the same log, or be refused with a
DataError whose message names the cause; nothing else may escape. Budget: the ``fuzz`` profile
of tests/conftest.py.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from conftest import FUZZ
from leuven_rt.data.records import MIN_SAMPLES, as_motion_data, load_csv
from leuven_rt.errors import DataError

BREAKS = ("none", "no-header", "units-row", "repeated-header", "ragged", "text-cell", "twice", "missing")


@st.composite
def logs(draw: st.DrawFn) -> tuple[list[str], list[list[float]]]:
    """A valid log: names t, x, f (and v), MIN_SAMPLES to MIN_SAMPLES + 60 rows of a moving stage."""
    rows = draw(st.integers(MIN_SAMPLES, MIN_SAMPLES + 60))
    dt = draw(st.sampled_from([1e-3, 2e-4, 5e-4, 4e-3]))
    amplitude = draw(st.floats(1e-4, 1e-1))
    cycles = draw(st.floats(0.5, 5.0))
    t = np.arange(rows) * dt
    x = amplitude * np.sin(2.0 * np.pi * cycles * np.arange(rows) / rows) + draw(st.floats(-1.0, 1.0))
    f = np.array(draw(st.lists(st.floats(-1e3, 1e3), min_size=rows, max_size=rows)))
    names, columns = ["t", "x", "f"], [t, x, f]
    if draw(st.booleans()):
        names.append("v")
        columns.append(np.gradient(x, dt))
    return names, np.column_stack(columns).tolist()


@st.composite
def dialects(draw: st.DrawFn) -> dict[str, object]:
    separator = draw(st.sampled_from([",", ";", "\t"]))
    return {
        "separator": separator,
        "decimal_comma": separator == ";" and draw(st.booleans()),
        "quote": draw(st.sampled_from(["none", "names", "all"])),
        "ending": draw(st.sampled_from(["\n", "\r\n", "\r"])),
        "bom": draw(st.booleans()),
        "spaces": draw(st.booleans()),
        "blank_line": draw(st.booleans()),
        "trailing": draw(st.booleans()),
    }


def _render(names: list[str], rows: list[list[str]], dialect: dict[str, object]) -> str:
    separator = str(dialect["separator"])

    def cell(text: str, name: bool) -> str:
        if dialect["decimal_comma"] and not name:
            text = text.replace(".", ",")
        quoted = dialect["quote"] == "all" or (dialect["quote"] == "names" and name)
        text = f'"{text}"' if quoted else text
        return f" {text} " if name and dialect["spaces"] else text

    tail = separator * 2 if dialect["trailing"] else ""
    lines = [separator.join(cell(name, True) for name in names) + tail] if names else []
    lines += [separator.join(cell(text, False) for text in row) + tail for row in rows]
    if dialect["blank_line"]:
        lines.insert(len(lines) // 2, "")
    ending = str(dialect["ending"])
    return ("\ufeff" if dialect["bom"] else "") + ending.join(lines) + ending


def _break(
    kind: str, names: list[str], rows: list[list[str]], index: int
) -> tuple[list[str], list[list[str]], str]:
    """The log broken in one way, and the text its refusal must hold."""
    if kind == "no-header":
        return [], rows, "holds numbers"
    if kind == "units-row":
        return names, [["s", "m", "N", "m/s"][: len(names)], *rows], "a units row under the header"
    if kind == "repeated-header":  # right under the header, it is a units row
        index = max(index, 1)
        return names, [*rows[:index], list(names), *rows[index:]], "a header repeated among the rows"
    if kind == "ragged":  # a cell short (a cell more would fill an unnamed trailing column)
        return names, [*rows[:index], rows[index][:-1], *rows[index + 1 :]], "cells, the header has"
    if kind == "text-cell":
        spoiled = [*rows[index][:1], "abc", *rows[index][2:]]
        return (
            names,
            [*rows[:index], spoiled, *rows[index + 1 :]],
            f"`x` must be finite, got nan at sample {index}",
        )
    if kind == "twice":
        return [*names[:2], "x", *names[3:]], rows, "the header names ['x'] more than once"
    assert kind == "missing", kind
    return (
        [name for name in names if name != "f"],
        [row[:2] + row[3:] for row in rows],
        "missing columns ['f']",
    )


@FUZZ
@given(log=logs(), dialect=dialects(), kind=st.sampled_from(BREAKS), where=st.floats(0.0, 1.0))
def test_every_dialect_loads_the_same_numbers_or_is_refused_naming_the_cause(
    log: tuple[list[str], list[list[float]]], dialect: dict[str, object], kind: str, where: float
) -> None:
    names, values = log
    rows = [[repr(value) for value in row] for row in values]
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        plain = folder / "plain.csv"
        plain.write_text("\n".join([",".join(names), *map(",".join, rows)]) + "\n", encoding="utf-8")
        expected = load_csv(plain)
        path = folder / "dialect.csv"
        if kind == "none":
            path.write_bytes(_render(names, rows, dialect).encode("utf-8"))
            columns = load_csv(path)
            assert sorted(columns) == sorted(expected)
            for key, values_read in columns.items():
                np.testing.assert_array_equal(values_read, expected[key], strict=True)
            return
        index = min(int(where * len(rows)), len(rows) - 1)
        broken_names, broken_rows, cause = _break(kind, names, rows, index)
        path.write_bytes(_render(broken_names, broken_rows, dialect).encode("utf-8"))
        try:
            as_motion_data(path)
        except DataError as error:
            assert cause in str(error), (kind, str(error))
        else:
            raise AssertionError(f"a log broken by {kind} was accepted")
