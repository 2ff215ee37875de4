from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import LearningError
from supportive.io import parse_task_file, parse_task_string
from supportive.language.demonstrated import BehaviorRecorder, _cross_validated, learn_region
from supportive.language.dnf import TruthTable
from supportive.language.explain import initiation_states, scope
from supportive.language.states import TaskStates

CHAIR = Path(__file__).parents[2] / "examples" / "ikea-chair.yaml"


def test_cross_validation_picks_the_likeliest_bandwidth() -> None:
    # two samples one apart in 3 dimensions: the leave-one-out likelihood peaks at h = 1/sqrt(3)
    samples = np.array([[1.0, 1.0, 0.0], [0.0, 1.0, 0.0]])
    assert _cross_validated(samples, [0.3, 0.58, 1.0, 2.0]) == 0.58
    assert _cross_validated(samples[:1], [0.3, 1.0, 2.0]) == 1.0


def test_chair_screw_states_generalise_but_not_across_a_hazard() -> None:
    states = TaskStates.of(parse_task_file(CHAIR))
    table = states.table
    screws = sorted(states.during("Screw seat"), key=len)
    shown = [screws[0]]  # seat placed, no screw yet
    region = learn_region(table, shown, level=0.05)
    assert set(shown) <= region.states and len(region.states) > 1
    hazard = next(s for s in region.states if s not in shown)
    safer = learn_region(table, shown, level=0.05, hazardous=[hazard])
    assert hazard not in safer.states and hazard in safer.excluded
    assert safer.states < region.states


@given(st.integers(1, 6), st.floats(0.01, 2.0), st.integers(0, 2**16))
def test_region_invariants(marked_count: int, level: float, seed: int) -> None:
    rng = np.random.default_rng(seed)
    values = rng.random((12, 4)) < 0.5
    names = [f"s{i}" for i in range(12)]
    table = TruthTable(names, ["p", "q", "r", "t"], values)
    picks = list(rng.choice(12, size=marked_count + 2, replace=False))
    marked = [names[i] for i in picks[:marked_count]]
    hazard = [names[i] for i in picks[marked_count:]]
    region = learn_region(table, marked, hazardous=hazard, level=level)
    assert set(marked) <= region.states
    assert not set(hazard) & region.states
    if level <= 1.0:
        assert learn_region(table, marked, level=level * 0.5).states >= learn_region(table, marked, level=level).states


def test_bad_input() -> None:
    table = TruthTable.from_sets(["a", "b"], {"p": {"a"}})
    with pytest.raises(ValueError, match="mark at least one"):
        learn_region(table, [])
    with pytest.raises(ValueError, match="both marked and hazardous"):
        learn_region(table, ["a"], hazardous=["a"])
    with pytest.raises(ValueError, match="> 0"):
        learn_region(table, ["a"], bandwidths=[0.0])
    with pytest.raises(KeyError):
        learn_region(table, ["z"])


FRAME = [
    "get_left_frame", "place_left_frame", "peg_left_front", "peg_left_rear", "get_right_frame", "place_right_frame",
    "peg_right_front", "peg_right_rear", "get_front_support", "attach_front_support", "get_back_support",
    "attach_back_support",
]


def test_a_recorded_behavior_gets_the_regions_it_was_shown() -> None:
    chair = TaskStates.of(parse_task_file(CHAIR))
    key = next(b for b in chair.spec.behaviors if b.name == "hand-hex-key")
    hazard = chair.state_after([*FRAME, "insert_bolt_rl"])
    recorder = BehaviorRecorder(chair, key, level=0.1, bandwidths=(1.0,), hazardous=[hazard])
    starts = [[*FRAME, bolt] for bolt in ("insert_bolt_fl", "insert_bolt_fr", "insert_bolt_rr")]
    learned = recorder.fit(starts, stops=[[*FRAME, "insert_bolt_fl", "tighten_nut_fl"]]).behavior_
    within = scope(chair, key)
    assert set(recorder.starts_) <= initiation_states(chair, learned)
    assert initiation_states(chair, learned) == recorder.initiation_.states & within
    assert len(initiation_states(chair, learned)) > len(recorder.starts_)  # it generalised
    assert hazard not in initiation_states(chair, learned) and hazard in chair.region(learned.termination)
    assert recorder.termination_ is not None
    assert chair.region(learned.termination) & within == (recorder.termination_.states | {hazard}) & within
    assert learned.subtasks == key.subtasks and learned.name == key.name
    unsafe = BehaviorRecorder(chair, key, level=0.1, bandwidths=(1.0,))
    assert hazard in initiation_states(chair, unsafe.fit(recorder.starts_).behavior_)  # the hazard kept it out
    untouched = BehaviorRecorder(chair, key).fit([[*FRAME, "insert_bolt_fl"]])
    assert untouched.behavior_.termination == key.termination and untouched.termination_ is None


def test_recording_refuses_what_it_cannot_learn() -> None:
    chair = TaskStates.of(parse_task_file(CHAIR))
    key = chair.spec.behaviors[0]
    with pytest.raises(LearningError, match="record at least one state"):
        BehaviorRecorder(chair, key).fit([])
    with pytest.raises(ValueError, match="not a way the task can begin"):
        BehaviorRecorder(chair, key).fit([["get_seat"]])
    start = chair.state_after(FRAME)
    with pytest.raises(LearningError, match="hazardous"):
        BehaviorRecorder(chair, key, hazardous=[start]).fit([start])
    # two states no predicate tells apart: one shown, the other hazardous
    twins = TaskStates.of(parse_task_string(
        "name: t\nstructure: {chain: [{clique: [a, b], name: Pick one}, c], name: All}\n"
        "behaviors: [{name: beep, text: beep, category: enhancing awareness, subtasks: [All]}]\n", "yaml"
    ))
    twin = BehaviorRecorder(twins, twins.spec.behaviors[0], hazardous=[twins.state_after(["b"])])
    with pytest.raises(LearningError, match="cannot tell"):
        twin.fit([["a"]])
