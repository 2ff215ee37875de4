"""Transfer, what the other tasks give: their Q-functions (condition b) and their CC-HTNs' macros (condition c).

**Source Q-functions.** The Q-function an explorer has learned on a task it fully comprehends is, once every
novelty is spent, the fixed point of the task SMDP without novelty rewards; it is computed here exactly, by
one backward pass of value iteration over the task's (acyclic) state space, instead of by running an explorer
on every other task (the same numbers, deterministically and fast): ``Q(s, o)`` = the discounted rewards of
performing option ``o`` from ``s`` (:data:`~.explore.FAIL` for the failing primitive,
:data:`~.explore.STEP` for each valid one; no novelty or completion bonus is left to earn) plus ``γ^k V(s')``, with ``V`` = max over options and 0 at
the complete state; a failing first action leaves ``s`` unchanged, ``Q = FAIL + γ V(s)``.

**Aggregation (flat Q-function transfer).** States of different tasks are compared by one feature: the last
action performed (``START`` at the empty state). For each other task, the mean of ``Q(s, o)`` over its
(state, possible last action) pairs with that feature; then the mean over the other tasks having the
feature. A target state starts with the aggregate of the last action the agent performed when it first
reached it; features no other task has start at 0.

**Macro actions.** Each other task's CC-HTN is learned with :class:`~supportive.learning.HTNLearner` from
*all* its valid orderings (at most 96 per task; this recovers the ground truth), and
:func:`~supportive.learning.macros.macro_library` collects their chains and cliques (each subtask once, at
least two actions). Condition (c) adds those :meth:`~supportive.learning.macros.MacroAction.applicable` to
the target (every action of the macro is one of the target's) to the agent's dictionary, and the other
tasks' Q-functions are computed with the same dictionary, so macros get transferred initial values too. A
macro performs any admissible order of its subtask (one drawn uniformly each time; at most 24 per macro
here) or, in the ``fixed-order`` reading, always the one order ``MacroAction.actions``
(:func:`macro_option`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import cache

from supportive.errors import ExperimentError
from supportive.examples.food import load_transfer, transfer_names
from supportive.experiments.transfer.explore import (
    FAIL,
    GAMMA,
    START,
    STEP,
    Option,
    TaskModel,
)
from supportive.learning.learner import HTNLearner
from supportive.learning.macros import MacroAction, macro_library
from supportive.tasks.htn import HTN, iter_orderings

PRIOR_SCALE = 0.001
"""Transferred advantages are multiplied by this: they order the options a state has not tried yet (about 0
for what succeeded after the same last action elsewhere, about −0.001 for what failed) without ranking them
below known, exhausted options (whose step costs make them −0.01 or less)."""

__all__ = [
    "PRIOR_SCALE",
    "aggregate",
    "dictionary",
    "macro_option",
    "macros_for",
    "source_q",
    "task_model",
    "transfer_initial",
]


@cache
def task_model(name: str) -> TaskModel:
    """The state space of the transfer task ``name`` (cached per process)."""
    spec = load_transfer(name)
    if spec.structure is None:
        raise ExperimentError(f"transfer task {name} has no structure")
    return TaskModel.from_structure(name, spec.structure)


@cache
def dictionary() -> tuple[str, ...]:
    """The shared primitive actions of all transfer tasks, sorted (39)."""
    return tuple(sorted({a for name in transfer_names() for a in load_transfer(name).action_ids()}))


@cache
def learned_htn(name: str) -> HTN:
    """The CC-HTN learned from every valid ordering of task ``name`` (cached per process)."""
    spec = load_transfer(name)
    assert spec.structure is not None
    orderings = [[a for a, _ in leaves] for leaves in iter_orderings(spec.structure)]
    return HTNLearner(mode="strict").fit(orderings).htn_


@cache
def macros_for(target: str) -> tuple[MacroAction, ...]:
    """Macro actions of the other tasks' CC-HTNs applicable to ``target``, in library order."""
    library = macro_library(learned_htn(n) for n in transfer_names() if n != target)
    available = set(task_model(target).actions)
    return tuple(m for m in library if m.applicable(available))


@cache
def source_q(name: str, options: tuple[Option, ...]) -> dict[int, list[float]]:
    """The converged Q-function of task ``name`` for the dictionary ``options`` (no novelty), per state.

    An option with several sequences (a macro performing any admissible order) is worth the mean over its
    sequences, drawn uniformly; a sequence whose first action fails leaves the state unchanged
    (``FAIL + γ V(s)``), so ``V(s)`` is found as the fixed point of ``V = max_o Q(s, o)`` (a contraction;
    with one sequence per option it is reached at once, from the best option that always progresses)."""
    model = task_model(name)
    value: dict[int, float] = {model.full: 0.0}
    q: dict[int, list[float]] = {}
    for state in sorted(model.allowed, key=lambda s: -s.bit_count()):
        if state == model.full:
            continue
        parts: list[tuple[float, int, int]] = []  # per option: sum over progressing sequences, count, failing
        for option in options:
            total, fails = 0.0, 0
            for sequence in option:
                worth = _sequence_value(model, state, sequence, value)
                if worth is None:
                    fails += 1
                else:
                    total += worth
            parts.append((total, len(option) - fails, fails))
        best = max(total / count for total, count, fails in parts if count and not fails)
        mixed = [part for part in parts if part[1] and part[2]]
        for _ in range(200):
            stay = FAIL + GAMMA * best
            new = max([best, *((total + fails * stay) / (count + fails) for total, count, fails in mixed)])
            if abs(new - best) <= 1e-13:
                break
            best = new
        value[state] = best
        stay = FAIL + GAMMA * best
        q[state] = [(total + fails * stay) / (count + fails) for total, count, fails in parts]
    return q


def _sequence_value(
    model: TaskModel, state: int, sequence: tuple[str, ...], value: dict[int, float]
) -> float | None:
    """Discounted rewards of performing ``sequence`` from ``state`` plus the value where it stops; None when
    its first action fails (the state does not change)."""
    reward, discount, current = 0.0, 1.0, state
    for action in sequence:
        bit = model.allowed[current].get(action)
        if bit is None:
            reward += discount * FAIL
            discount *= GAMMA
            break
        current |= bit
        reward += discount * STEP
        discount *= GAMMA
        if current == model.full:
            break
    return None if current == state else reward + discount * value[current]


def _lasts(model: TaskModel) -> dict[int, list[str]]:
    lasts: dict[int, list[str]] = {0: [START]}
    for state in sorted(model.allowed):
        for action, bit in model.allowed[state].items():
            lasts.setdefault(state | bit, []).append(action)
    return lasts


def aggregate(
    sources: Sequence[str], options: tuple[Option, ...], how: str = "max", scale: float = 1.0
) -> dict[str, list[float]]:
    """Feature (last action) -> one initial value per option: the advantage ``Q(s, o) − V(s)`` of the
    sources' (state, last action) pairs with that feature, aggregated by ``how``: ``"max"`` (the best the
    option did after that action in any other task) or ``"mean"`` (per source, then over the sources)."""
    if how not in ("max", "mean"):
        raise ExperimentError(f"aggregate: how must be 'max' or 'mean', not {how!r}")
    width = len(options)
    best: dict[str, list[float]] = {}
    totals: dict[str, list[float]] = {}
    tasks: dict[str, int] = {}
    for name in sources:
        model = task_model(name)
        q = source_q(name, options)
        sums: dict[str, list[float]] = {}
        counts: dict[str, int] = {}
        for state, lasts in _lasts(model).items():
            if state == model.full:
                continue
            row = q[state]
            top = max(row)
            advantage = [v - top for v in row]
            for last in lasts:
                if how == "max":
                    acc = best.setdefault(last, [-math.inf] * width)
                    for i, v in enumerate(advantage):
                        if v > acc[i]:
                            acc[i] = v
                    continue
                acc = sums.setdefault(last, [0.0] * width)
                for i, v in enumerate(advantage):
                    acc[i] += v
                counts[last] = counts.get(last, 0) + 1
        for last, acc in sums.items():
            total = totals.setdefault(last, [0.0] * width)
            for i, v in enumerate(acc):
                total[i] += v / counts[last]
            tasks[last] = tasks.get(last, 0) + 1
    if how == "max":
        return {last: [round(scale * v, 12) for v in row] for last, row in sorted(best.items())}
    return {
        last: [round(scale * v / tasks[last], 12) for v in total] for last, total in sorted(totals.items())
    }


@cache
def transfer_initial(
    target: str, with_macros: bool, how: str = "max", scale: float = PRIOR_SCALE, order: str = "any"
) -> tuple[tuple[Option, ...], dict[str, list[float]]]:
    """The dictionary and the initial Q values for ``target`` (leave-one-out over the transfer tasks):
    condition (b) without macros, (c) with them; ``order`` says what a macro performs (:func:`macro_option`).
    """
    options: tuple[Option, ...] = tuple(((a,),) for a in dictionary())
    if with_macros:
        options += tuple(dict.fromkeys(macro_option(m, order) for m in macros_for(target)))
    sources = [n for n in transfer_names() if n != target]
    return options, aggregate(sources, options, how, scale)


def macro_option(macro: MacroAction, order: str) -> Option:
    """A macro as a dictionary entry: ``"any"``, every admissible order of its subtask (a clique's children
    in any order, one drawn each time it is used); ``"fixed"``, always the one order ``macro.actions``.

    Raises:
        ExperimentError: for another ``order``.
    """
    if order == "fixed":
        return (macro.actions,)
    if order == "any":
        return tuple(macro.sequences())
    raise ExperimentError(f"macro order must be 'any' or 'fixed', not {order!r}")
