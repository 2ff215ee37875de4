"""Explaining a supportive-behavior policy in words (§3.3.4.3, Algorithm 7).

Two requests: about a subtask ("How will you help me attach the seat?") — every behavior that may start
during it, with when it starts and when it stops — and about a behavior ("When will you give me screws?") —
every subtask it belongs to (the whole task for a behavior tied to none), with the same two conditions.
Each condition is the behavior's initiation (or termination) region intersected with the subtask's states,
described by the smallest DNF over the task's predicates (:func:`~supportive.language.cover.minimal_cover`; states outside the subtask are "don't care":
the sentence is about the subtask) and spoken with the predicates' templates. When no formula covers a region
exactly the robot says so, and how precise its best description is; when the predicates cannot describe it
at all it says in how many situations it would, but has no words for them.
"""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass

from supportive.errors import NoCoverError, UnknownNameError
from supportive.language.cover import Cover, describe_precision, minimal_cover
from supportive.language.states import TaskStates
from supportive.tasks.behaviors import SupportiveBehavior
from supportive.tasks.formula import DNF, Literal

__all__ = [
    "ANY_POINT",
    "Explanation",
    "PolicyClause",
    "explain_behavior",
    "explain_subtask",
    "initiation_states",
    "scope",
    "verbalize",
]


def verbalize(formula: DNF, states: TaskStates) -> str:
    """A formula in words: literals joined by "and", clauses by "or"; ``true`` is "at any point", ``false``
    "never".

    >>> from supportive.examples import load
    >>> from supportive.tasks.formula import parse_formula
    >>> chair = TaskStates.of(load("ikea-chair"))
    >>> verbalize(parse_formula("placed(seat) and not attached(seat, left_frame)"), chair)
    'the seat is in place and the seat is not attached to the left frame'
    """
    if not formula.clauses:
        return "never"
    spoken = []
    for clause in formula.clauses:
        if not clause.literals:
            return "at any point"
        parts = [states.say(literal) for literal in sorted(clause.literals, key=lambda lit: (not lit.positive, lit.atom))]
        spoken.append(" and ".join(parts))
    return ", or ".join(spoken) if len(spoken) > 1 and any(" and " in s for s in spoken) else " or ".join(spoken)


ANY_POINT = "at any point"
"""The words for a region that is all of the states the sentence is about."""


@dataclass(frozen=True)
class PolicyClause:
    """One behavior within one subtask (or, for a behavior tied to none, the whole task): when it starts and when
    it stops, as covers and words.

    ``subtask`` is None for the whole task; ``activity`` is the subtask as the sentence says it
    (:meth:`TaskStates.activity`). ``start_words`` and ``stop_words`` are the conditions in words, or
    :data:`ANY_POINT` (for the stop: it stops as soon as it starts), or empty when the predicates cannot describe the region at all (the sentence then
    says how many situations it has no words for).
    """

    behavior: SupportiveBehavior
    subtask: str | None
    activity: str
    start: Cover | None
    stop: Cover | None
    start_words: str
    stop_words: str

    def sentence(self, *, about: str) -> str:
        """The clause as the robot says it: ``about`` is "subtask" (the behavior leads) or "behavior"."""
        if self.start_words == ANY_POINT:
            when = ANY_POINT
        elif self.start_words:
            when = f"when {self.start_words}"
        else:
            count = _described(self.start)
            when = f"in {'one situation' if count == 1 else f'{count} situations'} I have no words for"
        if self.stop_words == ANY_POINT:
            until = "but stop at once: I stop wherever I start"
        elif self.stop_words:
            until = f"until {self.stop_words}"
        else:
            count = _described(self.stop)
            until = f"until {'a situation' if count == 1 else f'one of {count} situations'} I have no words for"
        if about == "subtask":
            return f"{self.behavior.text} {when}, {until}"
        lead = "Whatever you are doing" if self.subtask is None else f"While you are {self.activity}"
        return f"{lead}, I will {self.behavior.text} {when}, {until}"

    def caveats(self) -> list[str]:
        """What the robot admits about its description's precision (nothing for what it has no words for)."""
        out = []
        for label, cover, words in (("when I start", self.start, self.start_words), ("when I stop", self.stop, self.stop_words)):
            if cover is not None and not cover.exact and words:
                out.append(f"(That description of {label} {describe_precision(cover)}.)")
        return out


def _described(cover: Cover | None) -> int:
    """How many states a cover was asked to describe."""
    return 0 if cover is None else len(cover.target)


@dataclass(frozen=True)
class Explanation:
    """An answer: the sentence to say and the clauses behind it."""

    text: str
    clauses: tuple[PolicyClause, ...]


def _describe(
    states: TaskStates, region: frozenset[Hashable], within: frozenset[Hashable], max_literals: int
) -> tuple[Cover | None, str]:
    """The smallest description of ``region`` within ``within``: "never", :data:`ANY_POINT`, a condition in
    words, or "" (with the cover) when no conjunction the predicates allow covers any of it."""
    target = region & within
    if not target:
        return None, "never"
    if target == within:
        return None, ANY_POINT
    try:
        cover = minimal_cover(
            states.table, target, irrelevant=within - target, max_literals=max_literals, full_coverage=True
        )
    except NoCoverError:
        cover = minimal_cover(
            states.table, target, irrelevant=within - target, max_literals=max_literals, full_coverage=False
        )
        if not cover.covered & target:
            return cover, ""
    return cover, verbalize(cover.formula, states)


def scope(states: TaskStates, behavior: SupportiveBehavior) -> frozenset[Hashable]:
    """The states a behavior belongs to: those during any of its subtasks (every state when it names none)."""
    if not behavior.subtasks:
        return frozenset(states.states)
    return frozenset().union(*(states.during(s) for s in behavior.subtasks if s in states.subtasks))


def initiation_states(states: TaskStates, behavior: SupportiveBehavior) -> frozenset[Hashable]:
    """Where the behavior may start: its initiation formula's states within its subtasks."""
    return states.region(behavior.initiation) & scope(states, behavior)


def _clause(
    states: TaskStates, behavior: SupportiveBehavior, subtask: str | None, max_literals: int
) -> PolicyClause:
    """The clause of a behavior within a subtask, or within the whole task when ``subtask`` is None."""
    within = frozenset(states.states) if subtask is None else states.during(subtask)
    start, start_words = _describe(states, initiation_states(states, behavior), within, max_literals)
    stop, stop_words = _describe(states, states.region(behavior.termination), within, max_literals)
    if stop_words == "never":
        stop_words = "you have finished the task" if subtask is None else states.say(Literal(f"done({subtask})"))
    activity = "" if subtask is None else states.activity(subtask)
    return PolicyClause(behavior, subtask, activity, start, stop, start_words, stop_words)


def _starts_in(states: TaskStates, behavior: SupportiveBehavior, subtask: str) -> bool:
    return bool(initiation_states(states, behavior) & states.during(subtask))


def explain_subtask(states: TaskStates, subtask: str, *, max_literals: int = 3) -> Explanation:
    """Answer "How will you help me {subtask}?" (Algorithm 7, lines 5–10).

    Raises:
        UnknownNameError: for an unknown subtask.

    >>> from supportive.examples import load
    >>> chair = TaskStates.of(load("ikea-chair"))
    >>> print(explain_subtask(chair, "Fasten nuts and bolts").text)  # doctest: +NORMALIZE_WHITESPACE
    When you are fastening nuts and bolts, I can hand you the hex key at any point, until you have finished
    fastening nuts and bolts; and I can point out the next bolt to fasten when you are fastening nuts and bolts,
    until you have finished fastening nuts and bolts.
    """
    states.during(subtask)  # raises UnknownNameError for an unknown name
    behaviors = [b for b in states.spec.behaviors if _starts_in(states, b, subtask)]
    if not behaviors:
        return Explanation(f"When you are {states.activity(subtask)}, I have no supportive behavior to offer.", ())
    clauses = tuple(_clause(states, b, subtask, max_literals) for b in behaviors)
    said = "; and I can ".join(c.sentence(about="subtask") for c in clauses)
    caveats = [line for c in clauses for line in c.caveats()]
    return Explanation(" ".join([f"When you are {states.activity(subtask)}, I can {said}.", *caveats]), clauses)


def explain_behavior(states: TaskStates, behavior: str | SupportiveBehavior, *, max_literals: int = 3) -> Explanation:
    """Answer "When will you {behavior}?" (Algorithm 7, lines 11–15).

    Raises:
        UnknownNameError: for a behavior name the task does not have.
    """
    if isinstance(behavior, str):
        found = {b.name: b for b in states.spec.behaviors}.get(behavior)
        if found is None:
            raise UnknownNameError(f"no behavior named {behavior!r}")
        behavior = found
    if not behavior.subtasks:  # tied to no subtask: it belongs to every state (see `scope`)
        if not initiation_states(states, behavior):
            return Explanation(f"I will never {behavior.text}: it starts in no state of the task.", ())
        clauses: tuple[PolicyClause, ...] = (_clause(states, behavior, None, max_literals),)
    else:
        subtasks = [s for s in behavior.subtasks if s in states.subtasks and _starts_in(states, behavior, s)]
        if not subtasks:
            return Explanation(f"I will never {behavior.text}: no subtask lets it start.", ())
        clauses = tuple(_clause(states, behavior, s, max_literals) for s in subtasks)
    caveats = [line for c in clauses for line in c.caveats()]
    return Explanation(" ".join([*(c.sentence(about="behavior") + "." for c in clauses), *caveats]), clauses)
