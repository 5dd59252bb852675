"""Every Python snippet of the README runs, in order, as a user would paste them one after another."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[2] / "README.md"
FENCE = re.compile(r"^```python\n(.*?)^```", re.MULTILINE | re.DOTALL)


def snippets() -> list[str]:
    return FENCE.findall(README.read_text(encoding="utf-8"))


def test_the_readme_has_python_snippets() -> None:
    assert len(snippets()) >= 2


def test_every_python_snippet_runs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # One namespace for all snippets: later snippets continue earlier ones, as in the README.
    monkeypatch.chdir(tmp_path)
    namespace: dict[str, object] = {"__name__": "__readme__"}
    for index, code in enumerate(snippets()):
        try:
            exec(compile(code, f"README.md python snippet {index + 1}", "exec"), namespace)
        except Exception as error:  # the snippet's number tells the reader which one broke
            raise AssertionError(f"README python snippet {index + 1} failed: {error!r}\n{code}") from error
