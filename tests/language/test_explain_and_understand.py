"""Algorithm 7 and its inverse: explanations read back give the region back; preferences change behaviors."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from supportive.errors import UnderstandingError
from supportive.io import parse_task_file, parse_task_string
from supportive.language.explain import (
    explain_behavior,
    explain_subtask,
    initiation_states,
    verbalize,
)
from supportive.language.grammar import Preference, parse_utterance
from supportive.language.states import TaskStates
from supportive.language.understand import ConditionReader, Understanding, Understood, guess_category
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
            assert clause.subtask is not None
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
    known = understanding.apply(_preference(
        "When I am screwing the seat, I want you to give me screws until the seat is attached to the left frame"
    ))
    assert not known.created and known.behavior.name == "give-screws"
    assert known.behavior.termination == "attached(seat, left_frame)"
    assert known.confident and known.behavior.subtasks == ("Screw seat",)
    new = understanding.apply(_preference("While I tighten the bolts, please shine a light on the bolt"))
    assert new.created and new.behavior.category is BehaviorCategory.ENHANCING_AWARENESS
    assert new.behavior.text == "shine a light on the bolt" and new.behavior.subtasks[0].startswith("Fasten")
    with pytest.raises(UnderstandingError, match="condition in the task's words"):
        understanding.apply(_preference("When I am screwing the seat, give me screws until the moon is blue"))


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
    texts = [explain_subtask(chair, s).text for s in ("Screw seat", "Attach seat", "Fasten nuts and bolts", "Build frame")]
    texts += [explain_behavior(chair, b).text for b in chair.spec.behaviors]
    for text in texts:
        assert not [name for name in names if name in text.lower()], text
    assert "when you are not screwing seat, until you are screwing seat" in explain_subtask(chair, "Screw seat").text


LIGHTS = """\
name: lights
actions:
  - {id: a, effects: ["p"]}
  - {id: b, effects: ["q"]}
  - {id: c, effects: ["r"]}
predicates:
  - {name: p, text: "the p light is on"}
  - {name: q, text: "the q light is on"}
  - {name: r, text: "the r light is on"}
structure: {clique: [a, b, c], name: Switch lights}
behaviors:
  - {name: beep, text: beep, category: enhancing awareness, subtasks: [Switch lights], initiation: "p and q"}
  - {name: blink, text: blink, category: enhancing awareness, subtasks: [Switch lights],
     initiation: "p and not r", termination: "q and r and not p"}
"""


def test_what_the_predicates_cannot_say_is_admitted_in_a_sentence() -> None:
    """With one literal per term, "p and q" cannot be said at all and "p and not r" only imprecisely."""
    lights = TaskStates.of(parse_task_string(LIGHTS, "yaml"))
    beep = explain_behavior(lights, "beep", max_literals=1)
    assert beep.text == (
        "While you are switching lights, I will beep in one situation I have no words for, until you have "
        "finished switching lights."
    )
    blink = explain_behavior(lights, "blink", max_literals=1)
    (clause,) = blink.clauses
    assert clause.start is not None and not clause.start.exact and clause.start_words == "the p light is on"
    assert clause.stop_words == ""
    assert blink.text == (
        "While you are switching lights, I will blink when the p light is on, until a situation I have no words "
        "for. (That description of when I start covers all 2 relevant states and 1 irrelevant one.)"
    )
    assert "<" not in explain_subtask(lights, "Switch lights", max_literals=1).text
    exact = explain_behavior(lights, "blink").text  # three literals are enough
    assert "when the p light is on and the r light is not on, until the q light is on" in exact
    assert "description" not in exact


def test_a_behavior_tied_to_no_subtask_is_explained_over_the_whole_task(chair: TaskStates) -> None:
    understanding = Understanding(chair)
    glue = understanding.apply(_preference("when the seat is not placed, give me glue")).behavior
    assert glue.subtasks == () and glue.initiation == "not placed(seat)"
    answer = explain_behavior(chair, glue)
    (clause,) = answer.clauses
    assert clause.subtask is None and len(initiation_states(chair, glue)) > 1
    assert answer.text.startswith("Whatever you are doing, I will give you glue when the seat is not in place")
    assert "never" not in answer.text
    assert chair.region(ConditionReader(chair).read(clause.start_words)) == initiation_states(chair, glue)
    nowhere = explain_behavior(chair, replace(glue, initiation="false"))
    assert nowhere.text == "I will never give you glue: it starts in no state of the task." and not nowhere.clauses


def _said(chair: TaskStates, text: str, subtasks: tuple[str, ...] | None = None) -> Understood:
    return Understanding(chair).apply(_preference(text), subtasks=subtasks)


def _preference(text: str) -> Preference:
    utterance = parse_utterance(text)
    assert isinstance(utterance, Preference), utterance
    return utterance


def test_a_preference_without_a_condition_lets_the_behavior_start_throughout_the_subtask(chair: TaskStates) -> None:
    """The issue's headline: "When I am attaching the front frame, I want you to give me screws"."""
    understood = _said(chair, "When I am attaching the front frame, I want you to give me screws", ("Build frame",))
    screws = understood.behavior
    assert screws.subtasks == ("Screw seat", "Build frame")
    assert chair.during("Build frame") <= initiation_states(chair, screws)
    before = next(b for b in chair.spec.behaviors if b.name == "give-screws")
    seat = chair.during("Screw seat")
    assert initiation_states(chair, screws) & seat == initiation_states(chair, before) & seat
    assert understood.acknowledgement == "OK. I will now also give you screws while you are building frame."
    assert "While you are building frame, I will give you screws at any point" in explain_behavior(chair, screws).text


def test_a_condition_applies_within_the_named_subtasks_only(chair: TaskStates) -> None:
    understood = _said(
        chair, "When I am fastening the bolts, give me screws when the front left bolt is tight until the seat is placed",
        ("Fasten nuts and bolts",),
    )
    screws = understood.behavior
    before = next(b for b in chair.spec.behaviors if b.name == "give-screws")
    seat, bolts = chair.during("Screw seat"), chair.during("Fasten nuts and bolts")
    assert initiation_states(chair, screws) & seat == initiation_states(chair, before) & seat
    assert chair.region(screws.termination) & seat == chair.region(before.termination) & seat
    assert initiation_states(chair, screws) & bolts == chair.region("bolted(front_left)") & bolts
    assert chair.region(screws.termination) & bolts == chair.region("placed(seat)") & bolts
    # named no subtask: the condition replaces the behavior's everywhere
    replaced = _said(chair, "Give me screws when the seat is not in place").behavior
    assert replaced.initiation == "not placed(seat)" and replaced.subtasks == ("Screw seat",)
    # a condition that never holds in the subtask is said so
    never = _said(chair, "When I am fastening the bolts, give me screws when the seat is attached to the left frame",
                  ("Fasten nuts and bolts",))
    assert "never holds while you are fastening nuts and bolts" in never.acknowledgement


def test_a_negative_preference_takes_the_states_away(chair: TaskStates) -> None:
    frames = _said(chair, "Don't hold the side frames steady when I'm mounting the front support",
                   ("Mount front support",))
    assert frames.negative and frames.behavior.subtasks == ("Mount back support",)
    assert not initiation_states(chair, frames.behavior) & chair.during("Mount front support")
    assert frames.acknowledgement == "OK. I will no longer hold the side frames steady while you are mounting front support."
    key = _said(chair, "Never hand me the hex key while I fasten the front left bolt", ("Fasten front left bolt",))
    assert key.behavior.subtasks == ("Fasten nuts and bolts",)  # a part of its subtask: those states go
    left = chair.during("Fasten front left bolt")
    assert not initiation_states(chair, key.behavior) & left
    assert key.before is not None
    assert initiation_states(chair, key.behavior) == initiation_states(chair, key.before) - left
    narrowed = _said(chair, "Don't hand me the hex key when I'm fastening the bolts if the front left bolt is tight",
                     ("Fasten nuts and bolts",))
    bolts = chair.during("Fasten nuts and bolts")
    assert narrowed.behavior.subtasks == ("Fasten nuts and bolts",)  # a condition narrows it: the subtask stays
    assert initiation_states(chair, narrowed.behavior) == bolts - chair.region("bolted(front_left)")
    nothing = _said(chair, "Don't give me screws when I'm fastening the bolts", ("Fasten nuts and bolts",))
    assert nothing.behavior == nothing.before and nothing.acknowledgement.endswith("anyway; I changed nothing.")
    with pytest.raises(UnderstandingError, match="behaviors I have"):
        _said(chair, "Don't juggle when I'm fastening the bolts")


def test_a_stop_that_holds_throughout_is_said_as_stopping_at_once() -> None:
    lights = TaskStates.of(parse_task_string(LIGHTS, "yaml"))
    stuck = replace(lights.spec.behaviors[0], initiation="true", termination="not r")
    text = explain_behavior(lights, stuck).text
    assert text.startswith("While you are switching lights, I will beep at any point, until the r light is not on")
    instant = explain_behavior(lights, replace(stuck, termination="true")).text
    assert instant == "While you are switching lights, I will beep at any point, but stop at once: I stop wherever I start."


def test_the_statement_made_when_confident_keeps_the_negation(chair: TaskStates) -> None:
    said = _said(chair, "Don't hold the side frames steady when I'm mounting the front support", ("Mount front support",))
    assert said.confirmation == "OK: when you are mounting front support, I will not hold the side frames steady."
