"""Algorithm 7 and its inverse: explanations read back give the region back; preferences change behaviors."""

from __future__ import annotations

from pathlib import Path

import pytest

from supportive.io import parse_task_file, parse_task_string
from supportive.language.explain import (
    explain_behavior,
    explain_subtask,
    initiation_states,
    verbalize,
)
from supportive.language.grammar import UnderstandingError, parse_utterance
from supportive.language.states import TaskStates
from supportive.language.understand import ConditionReader, Understanding, guess_category
from supportive.language.wording import activity, gerund
from supportive.tasks.behaviors import BehaviorCategory
from supportive.tasks.formula import parse_formula

CHAIR = Path(__file__).parents[2] / "examples" / "ikea-chair.yaml"


@pytest.fixture(scope="module")
def chair() -> TaskStates:
    return TaskStates.of(parse_task_file(CHAIR))


def test_every_exact_explanation_reads_back_to_its_region(chair: TaskStates) -> None:
    reader = ConditionReader(chair)
    checked = 0
    for behavior in chair.spec.behaviors:
        for clause in explain_behavior(chair, behavior).clauses:
            during = chair.during(clause.subtask)
            for cover, words, region in (
                (clause.start, clause.start_words, initiation_states(chair, behavior)),
                (clause.stop, clause.stop_words, chair.region(behavior.termination)),
            ):
                if cover is None or not cover.exact:
                    continue
                back = chair.region(reader.read(words)) & during
                assert back == region & during, (behavior.name, clause.subtask, words)
                checked += 1
    assert checked >= 4


def test_verbalized_formulas_read_back(chair: TaskStates) -> None:
    reader = ConditionReader(chair)
    for text in (
        "placed(seat) and not attached(seat, left_frame)",
        "holding(front_rail) or holding(back_rail)",
        "done(Mount supports)",
        "attached(seat, left_frame) and attached(seat, right_frame) or bolted(rear_left)",
    ):
        formula = parse_formula(text)
        assert reader.read(verbalize(formula, chair)) == formula


def test_explain_subtask_and_behavior_sentences(chair: TaskStates) -> None:
    text = explain_subtask(chair, "Screw seat").text
    assert text.startswith("When you are screwing seat, I can give you screws")
    assert "hold the seat in place" in text
    answer = explain_behavior(chair, "hold-frames").text
    assert answer.count("While you are") == 2 and "mounting front support" in answer
    assert explain_subtask(chair, "Prepare left frame").text.endswith("I have no supportive behavior to offer.")
    with pytest.raises(KeyError):
        explain_subtask(chair, "Paint chair")
    with pytest.raises(KeyError):
        explain_behavior(chair, "dance")


def test_the_thesis_example_shape(chair: TaskStates) -> None:
    """The give-screws start region is the thesis's two-clause shape: placed and not attached (left or right)."""
    clause = explain_behavior(chair, "give-screws").clauses[0]
    assert clause.subtask == "Screw seat" and clause.stop_words == "you have finished screwing seat"


def test_preferences_update_or_create_behaviors(chair: TaskStates) -> None:
    understanding = Understanding(chair)
    known = understanding.apply(parse_utterance(
        "When I am screwing the seat, I want you to give me screws until the seat is attached to the left frame"
    ))
    assert not known.created and known.behavior.name == "give-screws"
    assert known.behavior.termination == "attached(seat, left_frame)"
    assert known.confident and known.behavior.subtasks == ("Screw seat",)
    new = understanding.apply(parse_utterance("While I tighten the bolts, please shine a light on the bolt"))
    assert new.created and new.behavior.category is BehaviorCategory.ENHANCING_AWARENESS
    assert new.behavior.text == "shine a light on the bolt" and new.behavior.subtasks[0].startswith("Fasten")
    with pytest.raises(UnderstandingError, match="condition in the task's words"):
        understanding.apply(parse_utterance("When I am screwing the seat, give me screws until the moon is blue"))


def test_small_helpers() -> None:
    assert gerund("Tighten nut") == "tightening nut" and gerund("Put seat") == "putting seat"
    assert guess_category("carry the table with me") is BehaviorCategory.COLLABORATIVE_OBJECT_MANIPULATION
    assert guess_category("point at the next bolt") is BehaviorCategory.TASK_PROGRESSION_GUIDANCE


NOUN_NAMED = """\
name: frame
actions:
  - {id: left, text: "stand the left side up"}
  - {id: right, text: "stand the right side up"}
  - {id: rail, text: "seat the rail on the pegs"}
  - {id: cap, text: "put the cap on"}
structure:
  chain:
    - {clique: [left, right], name: Whole frame}
    - {chain: [rail, cap], name: Seat rail}
behaviors:
  - {name: steady, text: hold the frame steady, category: materials stabilization, subtasks: [Whole frame],
     initiation: "not active(Whole frame)"}
"""


def test_subtasks_named_by_a_noun_are_worked_on_not_gerundised() -> None:
    states = TaskStates.of(parse_task_string(NOUN_NAMED, "yaml"))
    text = explain_subtask(states, "Whole frame").text
    assert text.startswith("When you are working on whole frame, I can hold the frame steady when you are not ")
    assert "wholing" not in text and "you are not working on whole frame" in text
    assert states.activity("Whole frame") == "working on whole frame"
    assert activity("Seat rail") == "working on seat rail"
    assert states.activity("Seat rail") == "seating rail"  # the task's own texts begin with "seat"
    assert gerund("Make French toast") == "making French toast" and activity("V structure") == "working on V structure"


def test_every_sentence_names_a_subtask_the_same_way(chair: TaskStates) -> None:
    """A subtask is always said as an activity ("screwing seat"), never by its bare name ("screw seat")."""
    names = [name.lower() for name in chair.subtasks]
    texts = [explain_subtask(chair, s).text for s in chair.subtasks]
    texts += [explain_behavior(chair, b).text for b in chair.spec.behaviors]
    for text in texts:
        assert not [name for name in names if name in text.lower()], text
    assert "when you are not screwing seat, until you are screwing seat" in explain_subtask(chair, "Screw seat").text
