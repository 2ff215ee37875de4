"""Mistake detection scored leaving one demonstration out (evaluation/mistakes.py): the counts, worked by hand
on a small labelled task, the two baselines, and the reference scored on the task's true orders."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import TaskFileError
from supportive.evaluation.mistakes import (
    DETECTOR,
    METHODS,
    REFERENCE,
    MethodScores,
    MistakeEvaluation,
    _true_precondition,
    evaluate_mistakes,
    kind_rows,
    shown_rates,
)
from supportive.tasks.htn import Leaf
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


TEA_RULES = {(("boil", 1), ("pour", 1)), (("cup", 1), ("teabag", 1)), (("teabag", 1), ("pour", 1)),
             (("pour", 1), ("steep", 1)), (("steep", 1), ("serve", 1))}
"""The tea's true orders: the water boiled and the teabag in the cup before pouring, steeping, serving."""


def test_the_true_orders_are_scored_beside_the_methods_as_the_reference(scored: MistakeEvaluation) -> None:
    """The early pour (teabag not in) is flagged and names the teabag; the skipped steep is named at the serve;
    the second steep needs nothing the first did not: the reference finds two of the three, flags nothing
    else. It learns nothing, so it is the same learned from the correct demonstrations."""
    known = evaluate_mistakes(_tea(), thresholds=(0.5, 0.99), truth=TEA_RULES)
    reference = known.method(REFERENCE)
    assert (reference.positives, reference.found, reference.flagged, reference.right) == (3, 2, 2, 2)
    assert reference.clean_flagged == 0 and reference.invisible_flagged == 0
    assert list(known.as_dict()["methods"]) == [*METHODS, REFERENCE]  # type: ignore[call-overload]
    for name in METHODS:  # the methods' own scores do not depend on it
        assert known.method(name).as_dict() == scored.method(name).as_dict()
    correct = evaluate_mistakes(_tea(), learn_from="correct", truth=TEA_RULES).method(REFERENCE)
    assert correct.as_dict() == reference.as_dict()
    total = MistakeEvaluation("both", scored.thresholds)
    total.merge(scored)
    total.merge(known)
    assert total.method(REFERENCE).found == 2 and total.held_out == 24


def test_true_orders_naming_an_action_the_task_lacks_are_refused() -> None:
    with pytest.raises(TaskFileError, match="the true orders name 'kettle', an action the task does not have"):
        evaluate_mistakes(_tea(), truth={(("kettle", 1), ("pour", 1))})


@given(
    st.lists(st.tuples(st.integers(0, 3), st.integers(1, 2), st.integers(0, 3), st.integers(1, 2)), max_size=6),
    st.lists(st.integers(0, 3), min_size=1, max_size=8),
)
def test_the_reference_flags_a_step_exactly_when_a_step_it_truly_needs_is_not_done_yet(
    rules: list[tuple[int, int, int, int]], sequence: list[int]
) -> None:
    """Against positions: a step is flagged when some rule puts a leaf ``(a, k)`` before its own leaf and the
    ``k``-th ``a`` is not among the steps before it; the flag names those actions."""
    actions = ["a", "b", "c", "d"]
    truth: set[tuple[Leaf, Leaf]] = {((actions[x], i), (actions[y], j)) for x, i, y, j in rules if (x, i) != (y, j)}
    demo = Demonstration.from_entries([Step(actions[n]) for n in sequence], "d")
    spec = TaskSpec("t", (), None, (demo, Demonstration.from_entries([Step(a) for a in actions], "every")))
    flags = _true_precondition(truth, spec)(demo)
    assert len(flags) == len(sequence) + 1 and flags[-1] == (False, None, ())
    for position, action in enumerate(demo.actions):
        occurrence = demo.actions[: position + 1].count(action)
        unmet = [a for (a, k), then in sorted(truth) if then == (action, occurrence) and demo.actions[:position].count(a) < k]
        assert flags[position] == (bool(unmet), "order", tuple(dict.fromkeys(unmet)))


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


def test_learning_from_the_correct_ones_leaves_out_every_demonstration_that_shows_a_mistake(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Each fold learns from the others with no skipped step and no visible label: the technique-labelled one
    (its order is right) is kept; the held-out one never is. The baselines learn from the same ones."""
    import supportive.evaluation.mistakes as module

    learned: list[list[str]] = []
    baseline: list[list[str]] = []
    model, precondition = module.detection_model, module._precondition

    def recording_model(training: TaskSpec, settings: object = None) -> object:
        learned.append([d.id for d in training.demonstrations])
        return model(training)

    def recording_precondition(training: list[tuple[str, ...]]) -> object:
        baseline.append([" ".join(actions) for actions in training])
        return precondition(training)

    monkeypatch.setattr(module, "detection_model", recording_model)
    monkeypatch.setattr(module, "_precondition", recording_precondition)
    spec = _tea()
    scored = evaluate_mistakes(spec, learn_from="correct")
    correct = [f"c{i}" for i in range(len(CLEAN))] + ["dropped-cup"]
    ids = [d.id for d in spec.demonstrations]
    assert learned == [[c for c in correct if c != held] for held in ids]
    assert [len(b) for b in baseline] == [len(fold) for fold in learned]
    ours = scored.method(DETECTOR)
    assert scored.as_dict()["learned_from"] == "correct"
    assert (ours.positives, ours.found, ours.clean_flagged) == (3, 3, 0)
    with pytest.raises(TaskFileError, match="learned from different demonstrations"):
        scored.merge(MistakeEvaluation("tea", scored.thresholds))


def test_learning_from_the_correct_ones_needs_two_of_them() -> None:
    spec = _tea()
    last = spec.demonstrations[len(CLEAN) - 1 :]  # c7, then the four labelled: c7 and dropped-cup are correct
    assert evaluate_mistakes(spec.with_demonstrations(last), learn_from="correct").held_out == 5
    with pytest.raises(TaskFileError, match=r"needs at least two of them .*: 1 of the 4 show no skipped step"):
        evaluate_mistakes(spec.with_demonstrations(last[1:]), learn_from="correct")
    with pytest.raises(TaskFileError, match="learn from all or correct"):
        evaluate_mistakes(spec, learn_from="some")


def test_the_tables_leave_undefined_rates_blank() -> None:
    """A kind no label has (a claim where the labels say only `mistake: true`) has no recall and no F1; a kind
    or method that claimed nothing has no precision; they were shown as 0.000, as if measured."""
    scores = MethodScores(positives=6, found=4)
    assert shown_rates(scores.as_dict()) == ("–", "0.667", "–")  # nothing flagged
    assert shown_rates(MethodScores(flagged=2, right=0).as_dict()) == ("0.000", "–", "–")  # nothing to find
    scores.kinds = {"order": [3, 2, 0, 0], "true": [0, 0, 4, 3], "missing": [2, 1, 2, 1]}
    rows = kind_rows({DETECTOR: scores.as_dict()})
    assert rows == [
        [DETECTOR, "missing", "2", "0.500", "2", "0.500", "0.500"],
        [DETECTOR, "order", "3", "0.667", "0", "–", "–"],
        [DETECTOR, "true", "0", "–", "4", "0.750", "–"],
    ]


def test_the_json_gives_undefined_rates_as_null() -> None:
    """A rate that is not defined is None (null), not a 0 a reader would average in: precision of a method
    that claimed nothing, recall where there was nothing to find, F1 where either is, the share flagged when no
    demonstration was clean; a defined rate of 0 stays 0."""
    quiet = MethodScores(positives=6, found=4).as_dict()
    assert (quiet["precision"], quiet["recall"], quiet["f1"], quiet["clean_flagged"]) == (None, 0.6667, None, None)
    wrong = MethodScores(flagged=2, right=0, positives=3, found=0, clean_steps=10).as_dict()
    assert (wrong["precision"], wrong["recall"], wrong["f1"], wrong["clean_flagged"]) == (0.0, 0.0, 0.0, 0.0)
    kinds = MethodScores(kinds={"order": [3, 2, 0, 0]}).as_dict()["kinds"]
    assert kinds == {"order": {"claimed": 3, "positives": 0, "precision": 0.6667, "recall": None, "f1": None}}
