"""How a preference changes a supportive behavior's subtasks and regions (§3.3.4.3).

"When I am {X}, I want you to {Y}" means: do Y during X. Let ``D`` be the states where the person is at one of
the named subtasks (``active(X) or ready(X)``, what "when I am X" refers to, :meth:`TaskStates.during`), ``C``
the start condition the person gave (``true`` when none) and ``Z`` the stop condition. Then Y joins X and,
within D only, follows the person's words, its conditions elsewhere staying as they were:

    initiation'  = (initiation ∧ ¬D) ∨ (D ∧ C)
    termination' = (termination ∧ ¬D) ∨ (D ∧ Z)

so a preference without a condition guarantees that Y may start whenever X is under way. Without a stop
condition the termination is kept where Y already belonged and, in a subtask Y joins, Y stops when that
subtask is done (``termination' = termination ∧ ¬D_new``): the old stop condition was about other subtasks. Without a named
subtask ("give me screws when the seat is not attached") the conditions replace the old ones. "Don't {Y} when
I am {X} [when C]" takes those states away: ``initiation' = initiation ∧ ¬(D ∧ C)``, and a named subtask Y
belonged to is dropped from its subtasks when no condition narrows the request and another subtask remains.
A behavior tied to no subtask already belongs to every state; it stays so.

The results are formulas in the task file's DNF, shortened with :func:`~supportive.language.dnf.simplify`
over the behavior's states (those of its subtasks; elsewhere the formula does not matter): literals the rule
added are dropped where they change nothing there, the person's and the file's own are kept, and a formula
that still denotes the same states there is left as it was written.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from supportive.errors import LanguageError
from supportive.language.dnf import simplify
from supportive.language.explain import scope
from supportive.language.states import TaskStates
from supportive.tasks.behaviors import SupportiveBehavior
from supportive.tasks.formula import DNF, parse_formula

__all__ = ["during", "prefer", "refuse"]


def during(subtasks: Sequence[str]) -> DNF:
    """The formula of the states where a person is at any of ``subtasks``: ``active(X) or ready(X)`` each.

    >>> str(during(["Screw seat"]))
    'active(Screw seat) or ready(Screw seat)'
    """
    return DNF.of(*([f"{predicate}({subtask})"] for subtask in subtasks for predicate in ("active", "ready")))


def _shortened(states: TaskStates, behavior: SupportiveBehavior, formula: DNF, old: str, words: DNF) -> str:
    """``formula`` simplified over the behavior's states, keeping the literals of ``words``; the ``old``
    text itself when it denotes the same states there."""
    within = scope(states, behavior)
    simplified = simplify(states.grounded(formula), states.table, within, fixed=words.literals())
    if states.region(old) & within == states.region(simplified) & within:
        return old
    return str(simplified)


def prefer(
    states: TaskStates,
    behavior: SupportiveBehavior,
    subtasks: Sequence[str],
    start: DNF | None = None,
    stop: DNF | None = None,
) -> SupportiveBehavior:
    """The behavior after "When I am {subtasks}, I want you to {behavior} [when start] [until stop]".

    Args:
        states: The task's states.
        behavior: The behavior as it is.
        subtasks: The named subtasks (none: the conditions replace the behavior's).
        start: Where, within the subtasks, it may start (None: anywhere).
        stop: Where, within the subtasks, it stops (None: as before).

    Raises:
        UnknownNameError: for a subtask the task does not have.
    """
    for subtask in subtasks:
        states.during(subtask)
    if not subtasks:
        return replace(
            behavior,
            initiation=behavior.initiation if start is None else str(start),
            termination=behavior.termination if stop is None else str(stop),
        )
    joined = tuple(dict.fromkeys((*behavior.subtasks, *subtasks))) if behavior.subtasks else ()
    updated = replace(behavior, subtasks=joined)
    inside = during(subtasks)
    condition = DNF.true() if start is None else start
    old_start = parse_formula(behavior.initiation)
    initiation = _shortened(
        states, updated, old_start & ~inside | inside & condition, behavior.initiation, old_start | condition
    )
    old_stop = parse_formula(behavior.termination)
    if stop is not None:
        new_stop = old_stop & ~inside | inside & stop
    else:  # in a subtask it joins, it stops when that subtask is done (its old stop was about other subtasks)
        new_stop = old_stop & ~during([s for s in joined if s not in behavior.subtasks])
    words = old_stop if stop is None else old_stop | stop
    termination = _shortened(states, updated, new_stop, behavior.termination, words)
    return replace(updated, initiation=initiation, termination=termination)


def refuse(
    states: TaskStates, behavior: SupportiveBehavior, subtasks: Sequence[str], start: DNF | None = None
) -> SupportiveBehavior:
    """The behavior after "Don't {behavior} when I am {subtasks} [when start]".

    Args:
        states: The task's states.
        behavior: The behavior as it is.
        subtasks: The named subtasks (none: wherever ``start`` holds).
        start: Narrows the request to the states where it holds (None: all of the subtasks).

    Raises:
        UnknownNameError: for a subtask the task does not have.
        LanguageError: with neither subtasks nor a condition (nothing says when not to).
    """
    for subtask in subtasks:
        states.during(subtask)
    if not subtasks and start is None:
        raise LanguageError("say when not to: name a subtask or a condition")
    # not (D and C) = not D or not C: negating the short parts keeps the formula small
    allowed = (~during(subtasks) if subtasks else DNF(())) | (~start if start is not None else DNF(()))
    remaining = tuple(s for s in behavior.subtasks if s not in subtasks)
    if start is None and remaining and len(remaining) < len(behavior.subtasks):
        behavior = replace(behavior, subtasks=remaining)
    old_start = parse_formula(behavior.initiation)
    initiation = _shortened(states, behavior, old_start & allowed, behavior.initiation, old_start)
    return replace(behavior, initiation=initiation)
