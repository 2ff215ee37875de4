"""Supportive behaviors and the predicates that describe when they run (§3.1, §3.3): model only.

A task file may declare typed, parameterised *predicates* with a language template, give actions *effects*
(the atoms they make true, or false with ``not``), and list *supportive behaviors*: a name, what the robot
says it does, a category of the taxonomy of §3.1, the subtasks (named CC-HTN nodes) it belongs to, and its
initiation and termination regions as formulas (:mod:`supportive.tasks.formula`).
"""

from __future__ import annotations

import enum
import re
from dataclasses import dataclass

from supportive.errors import TaskModelError

__all__ = ["DERIVED_PREDICATES", "BehaviorCategory", "PredicateSpec", "SupportiveBehavior", "placeholders"]

DERIVED_PREDICATES: dict[str, PredicateSpec] = {}
"""Predicates every task with a structure has, over its named subtasks: ``done(S)`` (all of S is done),
``active(S)`` (S is under way: begun, not finished) and ``ready(S)`` (S not begun, but it may begin next).
Their ``?subtask`` is spoken as an activity ("screwing seat", :func:`supportive.language.wording.activity`),
so every sentence names a subtask the same way. Filled in below."""


class BehaviorCategory(enum.Enum):
    """The taxonomy of supportive behaviors (§3.1)."""

    MATERIALS_STABILIZATION = "materials stabilization"
    MATERIALS_RETRIEVAL = "materials retrieval"
    COLLABORATIVE_OBJECT_MANIPULATION = "collaborative object manipulation"
    ENHANCING_AWARENESS = "enhancing awareness"
    TASK_PROGRESSION_GUIDANCE = "task progression guidance"


@dataclass(frozen=True)
class PredicateSpec:
    """A predicate such as ``attached(?x, ?y)`` with its language template.

    Attributes:
        name: The predicate's name.
        params: Parameter names, without the ``?``.
        text: How to say it holds, with ``?param`` placeholders (``"?x is attached to ?y"``).
        negative: How to say it does not hold (default: ``text`` with "not" after its first is/are/has, or
            "it is not the case that …").
        types: The type of each parameter (None: untyped), or empty when none is typed; a task that declares
            its objects by type only accepts objects of a parameter's type as its argument.
    """

    name: str
    params: tuple[str, ...]
    text: str
    negative: str | None = None
    types: tuple[str | None, ...] = ()

    def say(self, args: tuple[str, ...], positive: bool = True) -> str:
        """The template filled in with ``args`` (underscores read as spaces).

        Raises:
            TaskModelError: for the wrong number of arguments.

        >>> p = PredicateSpec("attached", ("x", "y"), "?x is attached to ?y")
        >>> p.say(("front_rail", "left_frame")), p.say(("seat", "left_frame"), positive=False)
        ('front rail is attached to left frame', 'seat is not attached to left frame')
        """
        if len(args) != len(self.params):
            raise TaskModelError(f"{self.name} takes {len(self.params)} arguments, got {len(args)}")
        template = self.text if positive else (self.negative or _negate(self.text))
        values = {param: arg.replace("_", " ") for param, arg in zip(self.params, args, strict=True)}
        return _PLACEHOLDER.sub(lambda m: values.get(m.group(1), m.group(0)), template)


_PLACEHOLDER = re.compile(r"\?([A-Za-z_][A-Za-z0-9_]*)")


def placeholders(template: str) -> list[str]:
    """The ``?name`` placeholders a predicate's template uses, in order.

    >>> placeholders("?y holds the ?x_end of ?y")
    ['y', 'x_end', 'y']
    """
    return _PLACEHOLDER.findall(template)


def _negate(text: str) -> str:
    words = text.split()
    for i, word in enumerate(words):
        if word in ("is", "are", "has", "have", "was", "were", "can"):
            return " ".join([*words[: i + 1], "not", *words[i + 1 :]])
    return f"it is not the case that {text}"


@dataclass(frozen=True)
class SupportiveBehavior:
    """A supportive behavior a person can ask for and the robot can explain.

    Attributes:
        name: Identifier (``give-screws``).
        text: What the robot does, as a verb phrase it can say (``"give you screws"``).
        category: Its place in the taxonomy of §3.1.
        subtasks: Names of the CC-HTN nodes it is tied to.
        initiation: Formula of the states where it may start (``"true"``: whenever its subtask runs).
        termination: Formula of the states where it stops.
    """

    name: str
    text: str
    category: BehaviorCategory
    subtasks: tuple[str, ...] = ()
    initiation: str = "true"
    termination: str = "false"


DERIVED_PREDICATES.update(
    {
        "done": PredicateSpec(
            "done", ("subtask",), "you have finished ?subtask", "you have not finished ?subtask"
        ),
        "active": PredicateSpec("active", ("subtask",), "you are ?subtask", "you are not ?subtask"),
        "ready": PredicateSpec("ready", ("subtask",), "you can start ?subtask", "you cannot start ?subtask yet"),
    }
)
