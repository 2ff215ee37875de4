"""How the robot names a subtask in a sentence: as what the person is doing (§3.3.4.3).

A subtask's name is an imperative ("Screw seat", "Mount front support") or, in some task files, a noun phrase
("Yellow tower", "Row 2", "Middle blocks"). Every sentence speaks of a subtask the same way, as an *activity*:
the gerund of an imperative ("screwing seat") and "working on …" for anything else ("working on yellow
tower") — never "yellowing tower". Whether a name's first word is a verb is decided with a closed list of verbs
common in task names (:data:`SUBTASK_VERBS`) and, per task, the verbs its actions' texts begin with.
"""

from __future__ import annotations

from collections.abc import Iterable

__all__ = ["EVERYDAY_VERBS", "SUBTASK_VERBS", "activity", "gerund"]

_EVERYDAY = """give hand pass bring fetch get grab take hold keep steady stabilize stabilise lift raise lower
    move put place lay push pull press turn rotate flip tighten loosen unscrew fasten attach detach mount insert
    remove fit align clamp secure prepare assemble build add pick stand open close clean tidy clear show tell
    remind warn watch check wait stop start help point shine read count sort stay come go let make do find
    offer provide drive thread carry apply fix finish begin continue repeat"""
_TASK_NAME_VERBS = """screw bolt nail glue drill saw sand paint varnish wire solder connect plug install load
    unload pack unpack wrap label stack join tie lock unlock cover set arrange mark measure weigh cut chop slice
    dice peel grate mince crush mash cook boil bake fry grill roast toast heat melt simmer steam brew stir mix
    beat whisk blend knead roll fold pour drain rinse wash dry fill empty spread butter dress season flavour
    flavor garnish top marinate scramble serve plate sweep wipe scrub water plant dig sew shape trim switch"""

EVERYDAY_VERBS: tuple[str, ...] = tuple(_EVERYDAY.split())
"""Everyday verbs of requests and tasks; the utterance grammar's closed list of verbs
(:data:`~supportive.language.grammar.GRAMMAR`)."""

SUBTASK_VERBS: frozenset[str] = frozenset(EVERYDAY_VERBS) | frozenset(_TASK_NAME_VERBS.split())
"""Verbs a subtask's name may begin with (lower case)."""

_VOWELS = set("aeiou")


def gerund(phrase: str) -> str:
    """An imperative as what a person is doing: "Screw seat" → "screwing seat" (only the verb changes case).

    >>> [gerund(x) for x in ("Screw seat", "Prepare left frame", "Chop carrots", "Add pegs", "Open lid", "Tie up")]
    ['screwing seat', 'preparing left frame', 'chopping carrots', 'adding pegs', 'opening lid', 'tying up']
    >>> gerund("Make French toast")
    'making French toast'
    """
    verb, _, rest = phrase.strip().partition(" ")
    verb = verb.lower()
    if verb.endswith("ing"):
        word = verb
    elif verb.endswith("ie"):
        word = verb[:-2] + "ying"
    elif verb.endswith("e") and not verb.endswith("ee") and len(verb) > 2:
        word = verb[:-1] + "ing"
    elif (
        len(verb) >= 3 and sum(c in _VOWELS for c in verb) == 1 and verb[-1] not in _VOWELS | set("wxy")
        and verb[-2] in _VOWELS and verb[-3] not in _VOWELS
    ):
        word = verb + verb[-1] + "ing"
    else:
        word = verb + "ing"
    return f"{word} {rest.strip()}".strip()


def _sentence_case(name: str) -> str:
    """A name as it reads inside a sentence: a capitalised first word loses its capital ("Yellow tower" →
    "yellow tower"); an acronym or a single letter keeps it ("BLT sandwich", "V structure")."""
    first, _, rest = name.strip().partition(" ")
    if len(first) > 1 and first[0].isupper() and first[1:] == first[1:].lower():
        first = first.lower()
    return f"{first} {rest.strip()}".strip()


def activity(subtask: str, verbs: Iterable[str] = ()) -> str:
    """A subtask named as what a person is doing at it, for "you are …", "you have finished …".

    Args:
        subtask: The subtask's name.
        verbs: More words (lower case) to take as verbs, besides :data:`SUBTASK_VERBS` — for a task, the verbs
            its actions' texts begin with.

    >>> activity("Screw seat"), activity("Fasten nuts and bolts"), activity("Yellow tower"), activity("Row 2")
    ('screwing seat', 'fastening nuts and bolts', 'working on yellow tower', 'working on row 2')
    >>> activity("Whole frame"), activity("Seat rail"), activity("Seat rail", verbs={"seat"})
    ('working on whole frame', 'working on seat rail', 'seating rail')
    """
    first = subtask.strip().partition(" ")[0].lower()
    if first.endswith("ing") or first in SUBTASK_VERBS or first in set(verbs):
        return gerund(subtask)
    return f"working on {_sentence_case(subtask)}"
