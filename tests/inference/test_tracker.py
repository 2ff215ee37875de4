"""The progress-aware tracker: hand-computed posteriors, slips, the end of the task, and the next-step
predictor's contract (the brute-force oracle over both forms of the belief: test_tracker_oracle.py)."""

from __future__ import annotations

import math
from typing import Any

import pytest

from supportive.errors import NotFittedError
from supportive.inference import END_LABEL, ObservationModel, ProgressHMM, StepPredictor
from supportive.learning.distribution import END, ProgressModel
from supportive.tasks.htn import HTN, ActionNode, ChainNode, CliqueNode, Counts

Shape = str | tuple[str, list["Shape"]]

A, B, C = (ActionNode(x) for x in "abc")


def _next(htn: HTN, prefix: list[str], **settings: Any) -> dict[str, float]:
    tracker = ProgressHMM(htn, **settings).fit().filter()
    for action in prefix:
        tracker.observe(action)
    return tracker.last.next_actions


def test_hand_computed_clique_of_three() -> None:
    # uniform (no counts): the first of three, then one of the two left, then the last, then the end
    htn = HTN("t", (CliqueNode((A, B, C)),))
    slip = 0.04
    floor = slip / 4  # three actions and <end> share the slip mass
    first = _next(htn, [], slip=slip)
    assert first["a"] == pytest.approx((1 - slip) / 3 + floor) and first[END_LABEL] == pytest.approx(floor)
    after_b = _next(htn, ["b"], slip=slip)
    assert after_b["a"] == pytest.approx((1 - slip) / 2 + floor) and after_b["b"] == pytest.approx(floor)
    done = _next(htn, ["b", "a", "c"], slip=slip)
    assert done[END_LABEL] == pytest.approx(1 - slip + floor)


def test_hand_computed_counts_weight_the_choices() -> None:
    counts = Counts(performed=4, first=(3, 1, 0), after=((0, 2, 1), (1, 0, 0), (0, 0, 0)))
    htn = HTN("t", (CliqueNode((A, B, C), counts=counts),))
    model = ProgressModel(htn, smoothing=1.0)
    start = model.outcomes(model.executions.initial()[0])
    assert {model.leaves[i][0]: p for i, (p, _) in start.items()} == pytest.approx(
        {"a": 4 / 7, "b": 2 / 7, "c": 1 / 7}  # first = (3, 1, 0), +1 each
    )
    (state,) = model.executions.run(["a"])
    after_a = {model.leaves[i][0]: p for i, (p, _) in model.outcomes(state).items()}
    assert after_a == pytest.approx({"b": 3 / 5, "c": 2 / 5})  # after[a] = (_, 2, 1), +1 each


def test_hand_computed_chain_with_an_optional_step() -> None:
    sugar = ActionNode("sugar", optional=True, counts=Counts(performed=1, skipped=3))
    htn = HTN("t", (ChainNode((ActionNode("boil"), sugar, ActionNode("pour"))),))
    model = ProgressModel(htn, smoothing=1.0)
    (state,) = model.executions.run(["boil"])
    after_boil = {model.leaves[i][0]: p for i, (p, _) in model.outcomes(state).items()}
    take = (1 + 0.5) / (4 + 1)
    assert after_boil == pytest.approx({"sugar": take, "pour": 1 - take})
    (state,) = model.executions.run(["boil", "pour"])
    assert set(model.outcomes(state)) == {END}


def test_a_slip_does_not_zero_the_belief_and_is_flagged() -> None:
    htn = HTN("t", (ChainNode((A, B, C)),))
    tracker = ProgressHMM(htn, slip=0.01).fit().filter()
    tracker.observe("a")
    belief = tracker.observe("c")  # b skipped: off-script
    assert belief.off_script > 0.99 and belief.surprise > 5
    # re-synchronised to the nearest execution in which c was just done: the task may end
    assert belief.next_actions[END_LABEL] > 0.9 and belief.next_actions["c"] < 0.01
    unknown = tracker.observe("juggle")
    assert unknown.off_script == pytest.approx(1.0) and math.isfinite(unknown.surprise)
    assert sum(unknown.next_actions.values()) == pytest.approx(1.0)


def test_contact_events_drive_the_same_tracker() -> None:
    htn = HTN("t", (ChainNode((A, B)),))
    events = ObservationModel({"a": {"hand-a": 0.9}, "b": {"hand-b": 0.9}})
    tracker = ProgressHMM(htn, events, mean_duration=2.0).fit().filter()
    for moment in [{"hand-a"}, {"hand-a"}, {"hand-b"}]:
        belief = tracker.update(moment)
    assert belief.subgoals.argmax() == 1 and belief.done[0] > 0.99
    assert belief.next_actions[END_LABEL] > 0.9
    mixed = tracker.observe("b")  # known actions and events, one tracker
    assert mixed.next_actions[END_LABEL] > 0.9


def test_predictor_contract() -> None:
    demos = [list("abcd"), list("acbd"), list("abcd"), list("acbd")]
    predictor = StepPredictor(slip=0.01).fit(demos)
    for prefix in ([], ["a"], ["a", "b"], ["a", "b", "c", "d"], ["zz"]):
        next_step = predictor.next_step(prefix)
        assert set(next_step) == {"a", "b", "c", "d", END_LABEL}
        assert sum(next_step.values()) == pytest.approx(1.0)
    assert max(predictor.next_step(list("abcd")).items(), key=lambda kv: kv[1])[0] == END_LABEL
    with pytest.raises(NotFittedError):
        StepPredictor().next_step([])
    with pytest.raises(TypeError, match="unexpected keyword argument 'colour'"):
        StepPredictor(colour="red")  # type: ignore[call-arg]
