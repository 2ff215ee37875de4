from __future__ import annotations

from pathlib import Path

import pytest

from supportive.errors import TaskFileError
from supportive.io import parse_task_file, parse_task_string
from supportive.io.taskfile import dump_task
from supportive.tasks.behaviors import BehaviorCategory

CHAIR = Path(__file__).parents[2] / "examples" / "ikea-chair.yaml"

BASE = """\
name: t
actions:
  - {id: get, effects: ["holding(part)"]}
  - {id: put, effects: ["not holding(part)", "placed(part)"]}
predicates:
  - {name: holding, params: [x], text: "you hold the ?x"}
  - {name: placed, params: [x], text: "the ?x is in place"}
structure: {chain: [get, put], name: Move part}
"""


def test_chair_behaviors_load_and_round_trip(tmp_path: Path) -> None:
    spec = parse_task_file(CHAIR)
    names = [b.name for b in spec.behaviors]
    assert names[0] == "give-screws" and len(names) == 5
    give = spec.behaviors[0]
    assert give.category is BehaviorCategory.MATERIALS_RETRIEVAL and give.subtasks == ("Screw seat",)
    assert {p.name for p in spec.predicates} == {"holding", "placed", "attached", "bolted"}
    assert "placed(seat)" in next(a for a in spec.actions if a.id == "place_seat").effects
    again = parse_task_string(dump_task(spec, "yaml"), "yaml")
    assert again == spec
    assert parse_task_string(dump_task(spec, "json"), "json") == spec


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        ("behaviors:\n  - {name: b, text: help, category: cheering}\n", "category"),
        ("behaviors:\n  - {name: b, text: help, category: materials retrieval, subtasks: [Fly]}\n",
         "'Fly' is not a named subtask"),
        ("behaviors:\n  - {name: b, text: help, category: materials retrieval, initiation: 'holding(part'}\n",
         "cannot read the formula"),
        ("behaviors:\n  - {name: b, text: help, category: materials retrieval, initiation: 'flying(part)'}\n",
         "predicate 'flying' is not declared"),
        ("behaviors:\n  - {name: b, text: help, category: materials retrieval, termination: 'placed(a, b)'}\n",
         "placed takes 1 arguments"),
        ("behaviors:\n  - {name: b, text: help, category: materials retrieval, termination: 'done(Nothing)'}\n",
         "done() takes one named subtask"),
        ("behaviors:\n  - {name: b, text: x, category: enhancing awareness}\n"
         "  - {name: b, text: y, category: enhancing awareness}\n", "declared twice"),
    ],
)
def test_behavior_errors_name_the_place(extra: str, words: str) -> None:
    with pytest.raises(TaskFileError) as caught:
        parse_task_string(BASE + extra, "yaml", path="t.yaml")
    assert words in str(caught.value) and str(caught.value).startswith("t.yaml:")


def test_effect_and_predicate_errors() -> None:
    with pytest.raises(TaskFileError, match="an effect is one atom"):
        parse_task_string(BASE.replace('"placed(part)"', '"placed(part) or holding(part)"'), "yaml")
    with pytest.raises(TaskFileError, match="derived from the structure"):
        parse_task_string(
            BASE.replace("predicates:\n", "predicates:\n  - {name: done, params: [x], text: '?x is done'}\n"), "yaml"
        )


TYPED = """\
name: t
objects:
  part: [seat, rail]
  corner: [front_left]
actions:
  - {id: get, effects: ["holding(seat)"]}
  - {id: put, effects: ["not holding(seat)", "attached(seat, rail)"]}
predicates:
  - {name: holding, params: [x: part], text: "you hold the ?x"}
  - {name: attached, params: [x: part, y], text: "the ?x is attached to the ?y", negative: "the ?x is loose on the ?y"}
structure: {chain: [get, put], name: Move part}
"""


def test_typed_predicates_load_and_round_trip() -> None:
    spec = parse_task_string(TYPED, "yaml")
    holding, attached = spec.predicates
    assert holding.params == ("x",) and holding.types == ("part",)
    assert attached.params == ("x", "y") and attached.types == ("part", None)
    assert dict(spec.objects) == {"part": ("seat", "rail"), "corner": ("front_left",)}
    assert parse_task_string(dump_task(spec, "yaml"), "yaml") == spec
    assert parse_task_string(dump_task(spec, "json"), "json") == spec
    chair = parse_task_file(CHAIR)
    assert {p.name: p.types for p in chair.predicates}["attached"] == ("part", "part")
    untyped = parse_task_string(BASE, "yaml")  # no types, no objects: as before
    assert untyped.objects == () and all(p.types == () for p in untyped.predicates)


@pytest.mark.parametrize(
    ("old", "new", "place", "words"),
    [
        ('"holding(seat)"', '"holding(front_left)"', "actions[0].effects[0]",
         "holding(front_left): ?x of holding is a part (seat, rail), got 'front_left'"),
        ('"attached(seat, rail)"', '"attached(seat, table)"', "actions[1].effects[1]",
         "attached(seat, table): 'table' is not declared in 'objects'"),
        ("[x: part]", "[x: tool]", "predicates[0].params[0]", "type 'tool' is not declared in 'objects'"),
        ('"you hold the ?x"', '"you hold the ?thing"', "predicates[0].text",
         "template 'you hold the ?thing' uses ?thing, which is not a parameter (parameters of holding: ?x)"),
        ('"the ?x is loose on the ?y"', '"the ?x is loose"', "predicates[1].negative",
         "template 'the ?x is loose' does not say ?y (parameters of attached: ?x, ?y)"),
        ("[x: part]", "[{x: part, y: part}]", "predicates[0].params", "a typed parameter is one 'name: type' pair"),
        ("[x: part, y]", "[x: part, x]", "predicates[1].params", "names a parameter twice"),
    ],
)
def test_typed_predicate_errors_name_the_place(old: str, new: str, place: str, words: str) -> None:
    assert old in TYPED
    with pytest.raises(TaskFileError) as caught:
        parse_task_string(TYPED.replace(old, new, 1), "yaml", path="t.yaml")
    message = str(caught.value)
    assert f": {place}: " in message and words in message and message.startswith("t.yaml:"), message


def test_types_without_declared_objects_are_not_checked() -> None:
    without_objects = TYPED.replace("objects:\n  part: [seat, rail]\n  corner: [front_left]\n", "")
    spec = parse_task_string(without_objects.replace('"holding(seat)"', '"holding(anything)"'), "yaml")
    assert spec.objects == () and spec.predicates[0].types == ("part",)
