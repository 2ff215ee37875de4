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
