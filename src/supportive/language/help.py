"""The help a robot offers when it notices a mistake, in its own words (§3.1's taxonomy of supportive behaviors).

Each kind of mistake (:class:`~supportive.inference.mistakes.StepVerdict`) maps to a behaviour the robot can
carry out and a sentence it says:

* a skipped step (``missing``) → *enhancing awareness*: a reminder of the step, which comes before the one
  just done;
* a step done before what it needs (``out-of-order`` with prerequisites) → *materials retrieval*: bring what
  the missing prerequisite needs, so it can be done now;
* a step that breaks into a subtask under way (``out-of-order``, nothing missing) → *enhancing awareness*:
  point out where the person is;
* a step done again (``repeated``) or not of the task (``unknown-step``) → *enhancing awareness*: say so;
* and, whichever the kind, when a step that cannot be undone may come next while something it needs is not
  done → *task progression guidance*: a warning before it (:func:`warning_for`).

Steps are named by their text in the task file ("place the red block"), as what the person does ("placing
the red block", :func:`~supportive.language.wording.gerund`); a sentence names at most :data:`NAMED` of them
and counts the rest.

>>> texts = {"sugar": "add sugar", "pour": "pour the water"}
>>> from supportive.inference.mistakes import StepVerdict
>>> help_for(StepVerdict(3, "pour", 0.98, True, "missing", (), ("sugar",)), texts).say
'You skipped adding sugar: it comes before pouring the water. I will remind you.'
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass

from supportive.inference.mistakes import StepVerdict
from supportive.language.wording import gerund
from supportive.tasks.behaviors import BehaviorCategory

__all__ = ["Help", "help_for", "mistake_record", "warning_for"]


@dataclass(frozen=True)
class Help:
    """What the robot offers: a behaviour of the taxonomy, what it does (a verb phrase it can say) and the
    sentence it says."""

    category: BehaviorCategory
    behavior: str
    say: str

    def as_dict(self) -> dict[str, str]:
        """Plain-data form (the ``help`` of a mistake in ``infer``'s JSON lines and on the board)."""
        return {"category": self.category.value, "behavior": self.behavior, "say": self.say}


def help_for(verdict: StepVerdict, texts: Mapping[str, str]) -> Help | None:
    """The help for a mistake (None when the verdict is not one). ``texts`` maps action ids to their text
    (an id stands for itself when it has none)."""
    if not verdict.mistake or verdict.kind is None:
        return None
    doing = _doing(verdict.action, texts)
    if verdict.kind == "missing":
        skipped = _listing([_doing(a, texts) for a in verdict.skipped])
        if verdict.action == "<end>":
            return Help(
                BehaviorCategory.ENHANCING_AWARENESS,
                f"remind you of {skipped}",
                f"The task is done but you skipped {skipped}. I can remind you how it goes.",
            )
        return Help(
            BehaviorCategory.ENHANCING_AWARENESS,
            f"remind you of {skipped}",
            f"You skipped {skipped}: it comes before {doing}. I will remind you.",
        )
    if verdict.kind == "out-of-order" and verdict.prerequisites:
        needed = _listing([_doing(a, texts) for a in verdict.prerequisites])
        return Help(
            BehaviorCategory.MATERIALS_RETRIEVAL,
            f"bring what {needed} needs",
            f"{_capital(doing)} needs {needed} first. I can bring you what {needed} needs.",
        )
    if verdict.kind == "out-of-order":
        return Help(
            BehaviorCategory.ENHANCING_AWARENESS,
            "show you where you are in the task",
            f"{_capital(doing)} breaks into what you were in the middle of. I can show you where you are.",
        )
    if verdict.kind == "repeated":
        return Help(
            BehaviorCategory.ENHANCING_AWARENESS,
            f"tell you {doing} is done",
            f"You have already finished {doing}; once is enough.",
        )
    return Help(
        BehaviorCategory.ENHANCING_AWARENESS,
        f"tell you {verdict.action!r} is not part of the task",
        f"{_capital(doing)} is not part of this task as I learned it.",
    )


def mistake_record(verdict: StepVerdict, texts: Mapping[str, str]) -> dict[str, object]:
    """A verdict as plain data with the help it calls for (``help``: the behaviour's category, what the robot
    does and ``say``, the sentence), as ``infer`` prints it in its ``mistake`` field and the belief bag
    writes it."""
    record = verdict.as_dict()
    offered = help_for(verdict, texts)
    if offered is not None:
        record["help"] = offered.as_dict()
    return record


def warning_for(
    undone: Sequence[str], likely_next: Collection[str], irreversible: Collection[str], texts: Mapping[str, str]
) -> Help | None:
    """A warning before a step that cannot be undone: when one of the ``irreversible`` actions may come next
    (``likely_next``) while steps it needs (``undone``) are not done. None when there is nothing to warn of."""
    ahead = [a for a in likely_next if a in irreversible]
    if not ahead or not undone:
        return None
    step = _doing(ahead[0], texts)
    needed = _listing([_doing(a, texts) for a in undone])
    return Help(
        BehaviorCategory.TASK_PROGRESSION_GUIDANCE,
        f"hold back {step} until {needed} is done",
        f"Before {step}: {needed} is not done yet, and {step} cannot be undone.",
    )


def _doing(action: str, texts: Mapping[str, str]) -> str:
    """An action as what a person does ("place the red block" → "placing the red block")."""
    return gerund(texts.get(action) or action.replace("_", " "))


NAMED = 3
"""The most steps a sentence names; more are counted ("a, b, c and 4 more steps"): a robot that reads out
twenty steps is not heard."""


def _listing(items: Sequence[str]) -> str:
    """``a``, ``a and b``, ``a, b and c``; past :data:`NAMED` items, the first ones and how many more."""
    if len(items) <= 1:
        return "".join(items)
    if len(items) > NAMED:
        rest = len(items) - NAMED
        return f"{', '.join(items[:NAMED])} and {rest} more step{'s' if rest > 1 else ''}"
    return f"{', '.join(items[:-1])} and {items[-1]}"


def _capital(text: str) -> str:
    return text[:1].upper() + text[1:]
