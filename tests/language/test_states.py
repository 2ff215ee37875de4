from __future__ import annotations

from pathlib import Path

import pytest

from supportive.errors import LearningError
from supportive.io import parse_task_file, parse_task_string
from supportive.language.states import TaskStates
from supportive.tasks.formula import Literal

CHAIR = Path(__file__).parents[2] / "examples" / "ikea-chair.yaml"

SMALL = """\
name: move
actions:
  - {id: get, effects: ["holding(part)"]}
  - {id: put, effects: ["not holding(part)", "placed(part)"]}
  - {id: wave}
predicates:
  - {name: holding, params: [x], text: "you hold the ?x"}
  - {name: placed, params: [x], text: "the ?x is in place"}
structure:
  clique:
    - {chain: [get, put], name: Move part}
    - wave
"""


def test_states_and_atoms_by_hand() -> None:
    states = TaskStates.of(parse_task_string(SMALL, "yaml"))
    get, put, wave = ("get", 1), ("put", 1), ("wave", 1)
    # a clique child is never interleaved: "wave" comes before "get" or after "put", not between
    assert set(states.states) == {
        frozenset(), frozenset({get}), frozenset({wave}), frozenset({get, put}), frozenset({wave, get}),
        frozenset({get, put, wave}),
    }
    assert states.region("holding(part)") == {frozenset({get}), frozenset({wave, get})}
    assert states.region("placed(part) and not holding(part)") == {frozenset({get, put}), frozenset({get, put, wave})}
    assert states.region("done(Move part)") == states.region("placed(part)")
    assert states.during("Move part") == {frozenset(), frozenset({get}), frozenset({wave}), frozenset({wave, get})}
    assert states.region("flying(part)") == frozenset()
    assert states.region("not flying(part)") == set(states.states)
    assert states.region("true") == set(states.states) and states.region("false") == frozenset()
    assert states.say(Literal("holding(part)", False)) == "it is not the case that you hold the part"
    with pytest.raises(KeyError, match="no subtask named 'Fly'"):
        states.during("Fly")


def test_chair_regions() -> None:
    states = TaskStates.of(parse_task_file(CHAIR))
    assert len(states.states) == 79
    screws = states.during("Screw seat")
    assert len(screws) == 3 and all(("place_seat", 1) in s for s in screws)
    give = states.region("placed(seat) and not attached(seat, left_frame) or placed(seat) and not attached(seat, right_frame)")
    assert screws <= give
    assert states.say(Literal("attached(seat, left_frame)")) == "the seat is attached to the left frame"
    assert states.say(Literal("done(Attach seat)", False)) == "you have not finished attaching seat"


def test_no_structure() -> None:
    with pytest.raises(LearningError, match="no structure"):
        TaskStates.of(parse_task_string("name: t\ndemonstrations: [{steps: [a]}]\n", "yaml"))
