"""The demo's diagnose story: the hidden effects of the built-in log are named, the gap shrinks,
and the figure is written."""

from __future__ import annotations

from pathlib import Path

from leuven_rt.studies.demo import run_story


def test_story_names_the_hidden_effects_and_writes_the_figure(tmp_path: Path) -> None:
    story = run_story(tmp_path)
    assert sorted(story.diagnosis.named_effects) == sorted(story.hidden)
    assert story.diagnosis.rms_after < 0.2 * story.diagnosis.rms_before
    assert story.figure.stat().st_size > 10_000
    text = story.text()
    assert "where the baseline and the data disagree" in text and "step 2" in text
