"""The utterance grammar: preferences, the two questions of Algorithm 7, conditions, and what a failure says."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import SupportiveError, UnderstandingError
from supportive.language.grammar import (
    ExplainBehavior,
    ExplainSubtask,
    Preference,
    normalise_text,
    parse_condition,
    parse_utterance,
)

HELD_OUT = Path(__file__).parents[1] / "data" / "chair-utterances.yaml"


def pref(
    subtasks: tuple[str, ...], behaviors: tuple[str, ...], start: str | None = None, stop: str | None = None
) -> Preference:
    return Preference(subtasks, behaviors, start, stop)


SEAT_SCREWS = pref(("attaching the seat",), ("give me screws",))
ATTACH_SCREWS = pref(("attach the seat",), ("give me screws",))


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        # the thesis's template and its everyday variants
        ("When I am attaching the seat, I want you to give me screws", SEAT_SCREWS),
        ("When I'm attaching the seat, I want you to give me screws.", SEAT_SCREWS),
        ("When I’m attaching the seat, I’d like you to give me screws", SEAT_SCREWS),
        ("when im attaching the seat i want you to give me screws", SEAT_SCREWS),
        ("WHEN I AM ATTACHING THE SEAT, I WANT YOU TO GIVE ME SCREWS!!!", SEAT_SCREWS),
        ("  when i am attaching the seat , i want you to give me screws .  ", SEAT_SCREWS),
        ("while I'm attaching the seat, please give me screws", SEAT_SCREWS),
        ("please give me screws when I'm attaching the seat", SEAT_SCREWS),
        ("if I am attaching the seat could you give me screws", SEAT_SCREWS),
        ("when I'm attaching the seat I'd like you to give me screws", SEAT_SCREWS),
        ("whenever I attach the seat, give me screws", ATTACH_SCREWS),
        ("each time I attach the seat, give me screws", ATTACH_SCREWS),
        ("give me screws while I attach the seat", ATTACH_SCREWS),
        ("Would you please give me screws while I attach the seat?", ATTACH_SCREWS),
        ("Can you give me screws when I'm attaching the seat?", SEAT_SCREWS),
        ("give me screws while I'm attaching the seat, thanks", SEAT_SCREWS),
        ("when we are attaching the seat, give me screws", SEAT_SCREWS),
        ("when you see me attaching the seat, give me screws", SEAT_SCREWS),
        ("while attaching the seat, give me screws", SEAT_SCREWS),
        ("when I'm attaching the seat then give me screws", SEAT_SCREWS),
        ("when i am attaching the seat give me screws", SEAT_SCREWS),
        ("When I am attaching the seat, you should give me screws", SEAT_SCREWS),
        ("When I am attaching the seat, make sure to give me screws", SEAT_SCREWS),
        ("When I am attaching the seat, I need you to give me screws", SEAT_SCREWS),
        ("it would be great if you could give me screws when I'm attaching the seat", SEAT_SCREWS),
        ("during the seat attachment, give me screws", pref(("the seat attachment",), ("give me screws",))),
        # vocatives and fillers
        ("Robot, when I am attaching the seat, give me screws.", SEAT_SCREWS),
        ("When I’m attaching the seat, robot, give me screws!", SEAT_SCREWS),
        ("okay robot, when I'm attaching the seat, give me screws", SEAT_SCREWS),
        ("um, when I'm attaching the seat, give me screws", SEAT_SCREWS),
        ("please give me screws when I'm attaching the seat, robot", SEAT_SCREWS),
        ("When I'm attaching the seat, robot, could you, please, give me screws", SEAT_SCREWS),
    ],
)
def test_preference_phrasings(text: str, expected: Preference) -> None:
    assert parse_utterance(text) == expected


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        # the thesis's conjunction example
        (
            "When I am attaching the front frame or securing the side boards, I want you to give me screws and "
            "hold the rear frame steady.",
            pref(
                ("attaching the front frame", "securing the side boards"),
                ("give me screws", "hold the rear frame steady"),
            ),
        ),
        (
            "when I am attaching the seat and/or screwing it down, give me screws",
            pref(("attaching the seat", "screwing it down"), ("give me screws",)),
        ),
        (
            "When I am attaching the seat, give me screws, hold the frame and pass me the hex key",
            pref(("attaching the seat",), ("give me screws", "hold the frame", "pass me the hex key")),
        ),
        (
            "When I am putting the pegs in, hand me pegs and then hold the frame",
            pref(("putting the pegs in",), ("hand me pegs", "hold the frame")),
        ),
        # a determiner after "or" borrows the verb of the conjunct before
        (
            "When I'm tightening the rear left bolt or the rear right bolt, hold the back rail",
            pref(
                ("tightening the rear left bolt", "tightening the rear right bolt"), ("hold the back rail",)
            ),
        ),
        (
            "When I am putting pegs in the left frame or the right frame, hand me pegs",
            pref(("putting pegs in the left frame", "putting pegs in the right frame"), ("hand me pegs",)),
        ),
        (
            "when I am attaching screws or the seat, hold it",
            pref(("attaching screws", "attaching the seat"), ("hold it",)),
        ),
        # "and"/"or" not followed by a verb stay inside the phrase
        (
            "When I am fastening the nuts and bolts, pass me the hex key",
            pref(("fastening the nuts and bolts",), ("pass me the hex key",)),
        ),
        (
            "When I am attaching the front and back rails, hold the frame",
            pref(("attaching the front and back rails",), ("hold the frame",)),
        ),
        (
            "When I am attaching the seat, give me screws and nuts",
            pref(("attaching the seat",), ("give me screws and nuts",)),
        ),
        (
            "When I'm attaching the seat, I want you to hold the front and back rails steady",
            pref(("attaching the seat",), ("hold the front and back rails steady",)),
        ),
    ],
)
def test_conjunctions(text: str, expected: Preference) -> None:
    assert parse_utterance(text) == expected


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        (
            "when I am attaching the seat, give me screws until the seat is attached",
            pref(("attaching the seat",), ("give me screws",), stop="the seat is attached"),
        ),
        (
            "When I am attaching the seat, give me screws but stop when the seat is attached",
            pref(("attaching the seat",), ("give me screws",), stop="the seat is attached"),
        ),
        (
            "give me screws until the seat is attached when I am attaching the seat",
            pref(("attaching the seat",), ("give me screws",), stop="the seat is attached"),
        ),
        (
            "When I am attaching the seat, give me screws when the seat is placed until it is attached",
            pref(
                ("attaching the seat",),
                ("give me screws",),
                start="the seat is placed",
                stop="it is attached",
            ),
        ),
        (
            "give me screws when I am attaching the seat as long as the seat isn't attached",
            pref(("attaching the seat",), ("give me screws",), start="the seat is not attached"),
        ),
        # conditions alone, with predicate templates
        (
            "give me screws when the seat is not attached",
            pref((), ("give me screws",), start="the seat is not attached"),
        ),
        (
            "give me screws only when the seat is not attached",
            pref((), ("give me screws",), start="the seat is not attached"),
        ),
        (
            "give me screws as long as the seat is not attached",
            pref((), ("give me screws",), start="the seat is not attached"),
        ),
        (
            "give me screws until the front frame is attached to the left support",
            pref((), ("give me screws",), stop="the front frame is attached to the left support"),
        ),
        (
            "when the seat is placed, give me screws",
            pref((), ("give me screws",), start="the seat is placed"),
        ),
        ("as long as the seat is loose, hold it", pref((), ("hold it",), start="the seat is loose")),
    ],
)
def test_conditions_in_preferences(text: str, expected: Preference) -> None:
    assert parse_utterance(text) == expected


@pytest.mark.parametrize(
    ("text", "phrase"),
    [
        ("How will you help me attach the front frame?", "attach the front frame"),
        ("how can you help when I am attaching the seat", "attaching the seat"),
        ("what will you do while I attach the seat?", "attach the seat"),
        ("what do you do when I'm attaching the seat", "attaching the seat"),
        ("how are you going to help me with the seat", "the seat"),
        ("what can you do for me while I attach the seat", "attach the seat"),
        ("tell me how you will help me attach the seat", "attach the seat"),
        ("can you tell me how you will help me with the seat", "the seat"),
        ("How do you help during the seat attachment?", "the seat attachment"),
        ("what will you do to help me attach the seat", "attach the seat"),
        (
            "Robot, how will you help me attach the front rail or the back rail?",
            "attach the front rail or the back rail",
        ),
    ],
)
def test_explain_subtask(text: str, phrase: str) -> None:
    assert parse_utterance(text) == ExplainSubtask(phrase)


@pytest.mark.parametrize(
    ("text", "phrase"),
    [
        ("When will you hold the rear frame steady?", "hold the rear frame steady"),
        ("when do you give me screws?", "give me screws"),
        ("under what conditions will you give me screws", "give me screws"),
        ("in which situations do you give me screws", "give me screws"),
        ("at what point will you give me screws?", "give me screws"),
        ("when are you going to hold the rear frame steady", "hold the rear frame steady"),
        ("can you tell me when you will give me screws", "give me screws"),
        ("when would you give me screws", "give me screws"),
    ],
)
def test_explain_behavior(text: str, phrase: str) -> None:
    assert parse_utterance(text) == ExplainBehavior(phrase)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            "When I am attaching the seat",
            "I understood 'When I am attaching the seat' but not what you want me to do; "
            "say: When I am …, I want you to …",
        ),
        (
            "When I'm attaching the seat, I want you to",
            "I understood 'When I'm attaching the seat, I want you to' but not what you want me to do; "
            "say: When I am …, I want you to …",
        ),
        (
            "When I am",
            "I understood 'When I am' but not what you are doing; say: When I am …, I want you to …",
        ),
        (
            "how will you help me?",
            "I understood 'how will you help me' but not which part of the task you mean; say: How will you help me …?",
        ),
        (
            "When will you",
            "I understood 'When will you' but not which of my behaviors you mean; say: When will you …?",
        ),
        (
            "give me screws",
            "I understood 'give me screws' but not when you want it; say: When I am …, I want you to …",
        ),
        (
            "Please give me screws when",
            "I understood 'Please give me screws' but not when you want it; say: When I am …, I want you to …",
        ),
    ],
)
def test_failures_say_what_was_understood(text: str, message: str) -> None:
    with pytest.raises(UnderstandingError) as caught:
        parse_utterance(text)
    assert str(caught.value) == message
    assert isinstance(caught.value, SupportiveError)
    assert caught.value.text == text


@pytest.mark.parametrize("text", ["", "?!", "blah blah", "the seat is placed"])
def test_failures_with_nothing_understood_list_the_forms(text: str) -> None:
    with pytest.raises(
        UnderstandingError, match=r"I did not understand .*; say one of: 'When I am …, I want you to …'"
    ) as caught:
        parse_utterance(text)
    assert caught.value.understood is None


@pytest.mark.parametrize(
    ("text", "dnf"),
    [
        ("the seat is placed", [[("the seat is placed", True)]]),
        ("the seat is not placed", [[("the seat is placed", False)]]),
        ("the seat isn't placed", [[("the seat is placed", False)]]),
        ("the seat is not yet attached", [[("the seat is attached", False)]]),
        ("there are no screws left", [[("there are screws left", False)]]),
        (
            "the seat is not attached and the front rail is present or the seat is placed",
            [
                [("the seat is attached", False), ("the front rail is present", True)],
                [("the seat is placed", True)],
            ],
        ),
        (
            "the seat is attached or the rail is attached and the frame is not standing",
            [
                [("the seat is attached", True)],
                [("the rail is attached", True), ("the frame is standing", False)],
            ],
        ),
        ("the seat placed and the rail attached", [[("the seat placed", True), ("the rail attached", True)]]),
        # a conjunct that is no clause stays in the literal
        (
            "the front rail is attached to the left and right frames",
            [[("the front rail is attached to the left and right frames", True)]],
        ),
        (
            "The seat is placed, or the rail is present.",
            [[("the seat is placed", True)], [("the rail is present", True)]],
        ),
    ],
)
def test_parse_condition(text: str, dnf: list[list[tuple[str, bool]]]) -> None:
    assert parse_condition(text) == dnf


def test_parse_condition_of_a_preference() -> None:
    preference = parse_utterance(
        "When I'm attaching the seat, give me screws until the seat isn't loose or the rail is on"
    )
    assert isinstance(preference, Preference)
    assert preference.stop is not None
    assert parse_condition(preference.stop) == [[("the seat is loose", False)], [("the rail is on", True)]]


def test_parse_condition_rejects_nothing() -> None:
    with pytest.raises(UnderstandingError):
        parse_condition(" , ")


def test_normalise_text() -> None:
    assert normalise_text("I’m sure it's the robot's; isn't it?") == "i am sure it is the robot , is not it"
    assert normalise_text("Don't wanna — gimme the hex-key") == "do not want to , give me the hex key"


def _held_out() -> list[dict[str, Any]]:
    data = yaml.safe_load(HELD_OUT.read_text(encoding="utf-8"))
    return list(data["utterances"])


@pytest.mark.parametrize("item", _held_out(), ids=lambda item: str(item["text"])[:50])
def test_held_out_utterances_parse(item: dict[str, Any]) -> None:
    result = parse_utterance(item["text"])
    if item["kind"] == "preference":
        assert isinstance(result, Preference)
        assert len(result.subtask_phrases) == len(item["subtasks"])
        assert list(result.behavior_phrases) == item["behaviors"]
        assert result.start == item.get("start")
        assert result.stop == item.get("stop")
    elif item["kind"] == "explain_subtask":
        assert isinstance(result, ExplainSubtask)
    else:
        assert result == ExplainBehavior(item["behavior"])


def test_phrases_are_normalised() -> None:
    for item in _held_out():
        result = parse_utterance(item["text"])
        phrases = (
            result.subtask_phrases + result.behavior_phrases
            if isinstance(result, Preference)
            else (result.subtask_phrase if isinstance(result, ExplainSubtask) else result.behavior_phrase,)
        )
        for phrase in phrases:
            assert phrase == phrase.strip().lower()
            assert re.fullmatch(r"[a-z0-9 ]+", phrase), phrase


VOCABULARY = (
    "when i am while you want to give me screws hold the seat and or not until please how will help "
    "what do under conditions robot , is attached front rail"
)
WORDS = st.sampled_from(VOCABULARY.split())
CONDITION_WORDS = "the seat rail is not no and or attached placed , front"


@given(st.lists(WORDS, max_size=12).map(" ".join))
def test_any_text_is_understood_or_refused_politely(text: str) -> None:
    try:
        result = parse_utterance(text)
    except UnderstandingError as error:
        assert str(error).startswith("I ")
    else:
        assert isinstance(result, Preference | ExplainSubtask | ExplainBehavior)


@given(st.lists(st.sampled_from(CONDITION_WORDS.split()), min_size=1, max_size=10))
def test_condition_keeps_every_content_word(words: list[str]) -> None:
    text = " ".join(words)
    content = [w for w in words if w not in {",", "not", "no", "and", "or"}]
    if not content:
        return
    dnf = parse_condition(text)
    kept = [w for clause in dnf for phrase, _ in clause for w in phrase.split() if w not in {"and", "or"}]
    assert kept == content


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("Don't give me screws when I'm fastening the bolts", (("fastening the bolts",), ("give me screws",))),
        ("do not give me screws while I attach the seat", (("attach the seat",), ("give me screws",))),
        ("Never hold the seat when I am screwing it", (("screwing it",), ("hold the seat",))),
        ("Stop giving me screws when I am fastening the bolts", (("fastening the bolts",), ("giving me screws",))),
        ("When I am fastening the bolts, please don't give me screws", (("fastening the bolts",), ("give me screws",))),
        ("When I'm fastening the bolts, I don't want you to give me screws", (("fastening the bolts",), ("give me screws",))),
        ("when I'm fastening the bolts don't give me screws", (("fastening the bolts",), ("give me screws",))),
        ("when I am fastening the bolts you should not give me screws", (("fastening the bolts",), ("give me screws",))),
        ("When I am fastening the bolts, I want you to stop giving me screws", (("fastening the bolts",), ("giving me screws",))),
    ],
)
def test_negative_preferences(text: str, expected: tuple[tuple[str, ...], tuple[str, ...]]) -> None:
    result = parse_utterance(text)
    assert result == Preference(*expected, negative=True)


def test_negation_outside_the_request_is_no_negative_preference() -> None:
    conditioned = parse_utterance("I don't want you to hand me the hex key when the seat is not placed")
    assert conditioned == Preference((), ("hand me the hex key",), "the seat is not placed", negative=True)
    stop = parse_utterance("give me screws but stop when the seat is attached")
    assert stop == pref((), ("give me screws",), stop="the seat is attached")
    positive = parse_utterance("When I'm not fastening the bolts, give me screws")
    assert isinstance(positive, Preference) and not positive.negative
