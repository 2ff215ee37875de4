"""Mistake detection scored leaving one demonstration out (evaluation/mistakes.py): the counts, worked by hand
on a small labelled task, and the two baselines."""

from __future__ import annotations

import pytest

from supportive.errors import TaskFileError
from supportive.evaluation.mistakes import (
    DETECTOR,
    METHODS,
    MethodScores,
    MistakeEvaluation,
    evaluate_mistakes,
)
from supportive.tasks.spec import Demonstration, Step, TaskSpec

CLEAN = [["boil", "cup", "teabag", "pour", "steep", "serve"], ["cup", "boil", "teabag", "pour", "steep", "serve"]] * 4


def _demo(entries: list[str | tuple[str, str]], name: str) -> Demonstration:
    steps = [Step(e) if isinstance(e, str) else Step(e[0], mistake=e[1]) for e in entries]
    return Demonstration.from_entries(steps, name)


def _tea() -> TaskSpec:
    demos = [_demo(list(d), f"c{i}") for i, d in enumerate(CLEAN)]
    demos += [
        _demo(["boil", "cup", ("pour", "order"), "teabag", "steep", "serve"], "early"),  # pour before the teabag
        _demo(["boil", "cup", "teabag", "pour", ("steep", "missing"), "serve"], "skip"),  # steep skipped
        _demo(["boil", "cup", "teabag", "pour", "steep", ("steep", "repeated"), "serve"], "again"),
        _demo(["boil", ("cup", "technique"), "teabag", "pour", "steep", "serve"], "dropped-cup"),  # not visible
    ]
    return TaskSpec("tea", (), None, tuple(demos))


@pytest.fixture(scope="module")
def scored() -> MistakeEvaluation:
    return evaluate_mistakes(_tea(), thresholds=(0.5, 0.99))


def test_the_detector_finds_every_visible_mistake_and_flags_nothing_clean(scored: MistakeEvaluation) -> None:
    ours = scored.method(DETECTOR)
    assert (scored.held_out, scored.steps) == (12, 72)
    assert (ours.positives, ours.found, ours.flagged, ours.right) == (3, 3, 3, 3)
    assert ours.clean_steps == 48 and ours.clean_flagged == 0
    assert (ours.invisible, ours.invisible_flagged) == (1, 0)
    assert ours.delays == [0]  # the skipped steep is named at the step done in its place
    rates = ours.as_dict()
    assert (rates["precision"], rates["recall"], rates["f1"]) == (1.0, 1.0, 1.0)
    assert set(scored.detector) == {0.5, 0.99} and scored.as_dict()["threshold"] == 0.5


def test_the_baselines_are_scored_alike(scored: MistakeEvaluation) -> None:
    pre = scored.method("precondition")  # steep needs pour, serve needs steep: the skip is flagged at serve
    bigram = scored.method("unseen bigram")
    assert pre.positives == bigram.positives == 3
    assert pre.found == 2  # the repeat is not a missing precondition
    assert bigram.found == 3  # pour after cup, serve after pour, steep after steep: none seen in training
    assert set(scored.as_dict()["methods"]) == set(METHODS)  # type: ignore[call-overload]


def test_scores_merge_across_tasks(scored: MistakeEvaluation) -> None:
    total = MistakeEvaluation("both", scored.thresholds)
    total.merge(scored)
    total.merge(scored)
    assert total.held_out == 24 and total.method(DETECTOR).found == 6
    with pytest.raises(TaskFileError):
        total.merge(MistakeEvaluation("other", (0.3,)))
    merged = MethodScores()
    merged.merge(scored.method("precondition"))
    assert merged.as_dict() == scored.method("precondition").as_dict()


def test_unlabelled_or_single_demonstrations_are_refused() -> None:
    clean = TaskSpec("tea", (), None, tuple(_demo(list(d), f"c{i}") for i, d in enumerate(CLEAN)))
    with pytest.raises(TaskFileError, match="no step carries a mistake label"):
        evaluate_mistakes(clean)
    with pytest.raises(TaskFileError, match="at least two"):
        evaluate_mistakes(clean.with_demonstrations(clean.demonstrations[:1]))
