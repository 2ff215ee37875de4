"""Explaining a supportive-behavior policy in words (§3.3.4.3, Algorithm 7).

Two requests: about a subtask ("How will you help me attach the seat?") — every behavior that may start
during it, with when it starts and when it stops — and about a behavior ("When will you give me screws?") —
every subtask it belongs to, with the same two conditions. Each condition is the behavior's initiation (or
termination) region intersected with the subtask's states, described by the smallest DNF over the task's
predicates (:func:`~supportive.language.cover.minimal_cover`; states outside the subtask are "don't care":
the sentence is about the subtask) and spoken with the predicates' templates. When no formula covers a region
exactly the robot says so, and how precise its best description is; when the predicates cannot describe it
at all it says "I have no words for …".
"""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass

from supportive.language.cover import Cover, NoCoverError, describe_precision, minimal_cover
from supportive.language.states import TaskStates
from supportive.tasks.behaviors import SupportiveBehavior
from supportive.tasks.formula import DNF, Literal

__all__ = [
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

    >>> from supportive.io import parse_task_file
    >>> from supportive.tasks.formula import parse_formula
    >>> chair = TaskStates.of(parse_task_file("examples/ikea-chair.yaml"))
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


@dataclass(frozen=True)
class PolicyClause:
    """One behavior within one subtask: when it starts and when it stops, as covers and words.

    ``activity`` is the subtask as the sentence says it (:meth:`TaskStates.activity`).
    """

    behavior: SupportiveBehavior
    subtask: str
    activity: str
    start: Cover | None
    stop: Cover | None
    start_words: str
    stop_words: str

    def sentence(self, *, about: str) -> str:
        """The clause as the robot says it: ``about`` is "subtask" (the behavior leads) or "behavior"."""
        when = "at any point" if self.start_words == "at any point" else f"when {self.start_words}"
        if about == "subtask":
            return f"{self.behavior.text} {when}, until {self.stop_words}"
        return f"While you are {self.activity}, I will {self.behavior.text} {when}, until {self.stop_words}"

    def caveats(self) -> list[str]:
        """What the robot admits about its description's precision."""
        out = []
        for label, cover in (("when I start", self.start), ("when I stop", self.stop)):
            if cover is not None and not cover.exact:
                out.append(f"(That description of {label} {describe_precision(cover)}.)")
        return out


@dataclass(frozen=True)
class Explanation:
    """An answer: the sentence to say and the clauses behind it."""

    text: str
    clauses: tuple[PolicyClause, ...]


def _describe(
    states: TaskStates, region: frozenset[Hashable], within: frozenset[Hashable], max_literals: int
) -> tuple[Cover | None, str]:
    target = region & within
    if not target:
        return None, "never"
    if target == within:
        return None, "at any point"
    try:
        cover = minimal_cover(
            states.table, target, irrelevant=within - target, max_literals=max_literals, full_coverage=True
        )
    except NoCoverError:
        cover = minimal_cover(
            states.table, target, irrelevant=within - target, max_literals=max_literals, full_coverage=False
        )
        if not cover.covered & target:
            return cover, f"<I have no words for these {len(target)} states>"
    return cover, verbalize(cover.formula, states)


def scope(states: TaskStates, behavior: SupportiveBehavior) -> frozenset[Hashable]:
    """The states a behavior belongs to: those during any of its subtasks (every state when it names none)."""
    if not behavior.subtasks:
        return frozenset(states.states)
    return frozenset().union(*(states.during(s) for s in behavior.subtasks if s in states.subtasks))


def initiation_states(states: TaskStates, behavior: SupportiveBehavior) -> frozenset[Hashable]:
    """Where the behavior may start: its initiation formula's states within its subtasks."""
    return states.region(behavior.initiation) & scope(states, behavior)


def _clause(states: TaskStates, behavior: SupportiveBehavior, subtask: str, max_literals: int) -> PolicyClause:
    during = states.during(subtask)
    start, start_words = _describe(states, initiation_states(states, behavior), during, max_literals)
    stop, stop_words = _describe(states, states.region(behavior.termination), during, max_literals)
    if stop_words == "never":
        stop_words = states.say(Literal(f"done({subtask})"))
    elif stop_words == "at any point":
        stop_words = "you tell me to stop"
    return PolicyClause(behavior, subtask, states.activity(subtask), start, stop, start_words, stop_words)


def _starts_in(states: TaskStates, behavior: SupportiveBehavior, subtask: str) -> bool:
    return bool(initiation_states(states, behavior) & states.during(subtask))


def explain_subtask(states: TaskStates, subtask: str, *, max_literals: int = 3) -> Explanation:
    """Answer "How will you help me {subtask}?" (Algorithm 7, lines 5–10).

    Raises:
        KeyError: for an unknown subtask.

    >>> from supportive.io import parse_task_file
    >>> chair = TaskStates.of(parse_task_file("examples/ikea-chair.yaml"))
    >>> print(explain_subtask(chair, "Fasten nuts and bolts").text)  # doctest: +NORMALIZE_WHITESPACE
    When you are fastening nuts and bolts, I can hand you the hex key at any point, until you have finished
    fastening nuts and bolts; and I can point out the next bolt to fasten when you are fastening nuts and bolts,
    until you have finished fastening nuts and bolts.
    """
    states.during(subtask)  # raises KeyError for an unknown name
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
        KeyError: for a behavior name the task does not have.
    """
    if isinstance(behavior, str):
        found = {b.name: b for b in states.spec.behaviors}.get(behavior)
        if found is None:
            raise KeyError(f"no behavior named {behavior!r}")
        behavior = found
    subtasks = [s for s in behavior.subtasks if s in states.subtasks and _starts_in(states, behavior, s)]
    if not subtasks:
        return Explanation(f"I will never {behavior.text}: no subtask lets it start.", ())
    clauses = tuple(_clause(states, behavior, s, max_literals) for s in subtasks)
    caveats = [line for c in clauses for line in c.caveats()]
    return Explanation(" ".join([*(c.sentence(about="behavior") + "." for c in clauses), *caveats]), clauses)
