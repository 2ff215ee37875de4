"""Which reading of the demonstrations to keep: the one that best predicts demonstrations it did not see.

Readings of the same demonstrations (:class:`~supportive.learning.learner.HTNLearner`), each learned from the
demonstrations with their slips undone (a step out of order or forgotten put back where the ``general`` hierarchy
admits it, a repeated or unknown one taken out; the slips are found once, on all the demonstrations,
:mod:`~supportive.learning.general.noise`: the held-out demonstrations are scored as what their people meant
to do, which is what a reading predicts):

* ``general``: chains and cliques the evidence supports, a partial order where no tree fits;
* ``strict``: the thesis's reading, only what was seen in full;
* ``partial order``: no subtasks, the steps in the orders the evidence establishes;
* ``general`` and ``partial order`` with **consistent orders**: every order two or more demonstrations keep
  without exception counts as established (``order_support=2``), not only those unlikely by chance. People
  with habits keep orders that are free, but a task also has orders too few demonstrations show to rule out
  chance; which of the two explains the demonstrations better is for them to say.

They are scored by K-fold cross-validation: learned from the other folds, each held-out demonstration's
log-likelihood when every execution the reading admits is equally likely (``-log`` of how many action sequences
it admits, the instances of a repeated subtask counted once; no frequency is fitted, so no reading is
favoured for its parameters). A held-out demonstration the reading does
not admit is explained as noise, as the slip model reads it: each step out of place costs ``slip_rate`` times
the place it landed among the demonstration's, on top of the probability of the execution it came from. The
steps out of place are those a greedy cover takes out so that no order the reading requires is reversed and
no subtask interleaved (an upper bound on the fewest): one when moving one step makes the demonstration
admitted, else at least two. So a reading too tight to
generalise pays for every demonstration it refuses, and one too loose for every one it admits. The first of
:data:`CANDIDATES` (the default first) whose mean held-out log-likelihood per demonstration is within one
standard error of the best mean is kept — the one-standard-error rule (Hastie, Tibshirani and Friedman, *The
Elements of Statistical Learning*, §7.10), the error being that of the mean of the paired differences over the
held-out demonstrations: another reading must predict them better by more than chance — unless, learned from
all the demonstrations, it admits exactly the executions the ``general`` reading admits: then the same
distribution is kept with its subtasks (:func:`same_executions`).

No comparison is run (``general`` is kept) with fewer than ``min_demonstrations`` demonstrations, when every
reading admits the same executions, or when the demonstrations show every execution the ``general`` reading
admits (none can then predict a held-out demonstration better: the others admit the same or more).
"""

from __future__ import annotations

import itertools
import math
import statistics
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from supportive.learning.general.evidence import BoolMatrix
from supportive.learning.pair_orders import required_orders
from supportive.tasks.executions import Progress
from supportive.tasks.htn import HTN, ActionNode, CliqueNode, Leaf, Node, shape, to_leaves

__all__ = [
    "CANDIDATES",
    "CONSISTENT",
    "READINGS",
    "Selection",
    "held_out_log_likelihoods",
    "same_executions",
    "select_reading",
]

READINGS = ("general", "strict", "partial order")
"""The readings one can ask for by name (``mode``), the default first."""

CONSISTENT = " (consistent orders)"
"""Suffix of a reading that takes every order two or more demonstrations keep without exception as
established (``order_support=2``), however likely by chance."""

CANDIDATES = ("general", f"general{CONSISTENT}", "strict", "partial order", f"partial order{CONSISTENT}")
"""The readings ``auto`` chooses between, the default first."""

Fitter = Callable[[str, Sequence[int]], HTN]
"""Learns one reading (by name) from the demonstrations of the given indices."""


@dataclass(frozen=True)
class Selection:
    """Which reading was kept and why.

    Attributes:
        chosen: The reading kept.
        reason: ``"held-out likelihood"`` (saying, when another reading scored best, by how much and the
            standard error it was within, and, when the reading kept is not ``general``, its mean held-out
            log-likelihood minus ``general``'s and that difference's standard error), ``"the readings
            agree"``, ``"every execution was demonstrated"`` or ``"too few
            demonstrations"``.
        scores: Mean held-out log-likelihood per demonstration (nats) of each reading, when compared.
        admitted: Held-out demonstrations each reading admitted, when compared.
        folds: Folds of the cross-validation (0 when none was run).
    """

    chosen: str
    reason: str
    scores: dict[str, float] = field(default_factory=dict)
    admitted: dict[str, int] = field(default_factory=dict)
    folds: int = 0

    def as_dict(self) -> dict[str, object]:
        """Plain-data form (``"selection"`` in ``learn --format json``)."""
        return {
            "chosen": self.chosen,
            "reason": self.reason,
            "held_out_log_likelihood": {k: round(v, 4) for k, v in self.scores.items()},
            "held_out_admitted": dict(self.admitted),
            "folds": self.folds,
        }

    def describe(self) -> str:
        """One line for a terminal."""
        if not self.scores:
            return f"reading: {self.chosen} ({self.reason})"
        scores = ", ".join(f"{name} {value:.2f}" for name, value in self.scores.items())
        why = self.reason.removeprefix("held-out likelihood").removeprefix(" ")
        return (
            f"reading: {self.chosen} (held-out log-likelihood per demonstration, {self.folds} folds: {scores})"
            + (f" {why}" if why else "")
        )


def held_out_log_likelihoods(
    htn: HTN, held_out: Sequence[Sequence[str]], slip_rate: float
) -> list[tuple[float, bool]]:
    """For each held-out demonstration, its log-likelihood under ``htn`` and whether ``htn`` admits it (see
    the module docstring for how a refused one is explained)."""
    uniform = _log_symmetry(htn) - math.log(max(htn.count_orderings(), 1))
    required: BoolMatrix | None = None  # the orders ``htn`` requires, found once for all it refuses
    out = []
    for actions in held_out:
        if htn.admits(actions):
            out.append((uniform, True))
            continue
        if required is None:
            required = required_orders(htn)[1]
        moved = _moves_needed(htn, actions, required)
        out.append((uniform + moved * (math.log(slip_rate) - math.log(max(len(actions), 1))), False))
    return out


def _moves_needed(htn: HTN, actions: Sequence[str], required: BoolMatrix) -> int:
    """How many steps of ``actions`` were done out of place, for a demonstration ``htn`` refuses: the steps a
    greedy cover takes out so that no order ``htn`` requires is reversed and no subtask is interleaved (an
    upper bound on the fewest), and at least one; exactly one when moving a single step — the cover's, or
    any when the cover is empty — makes it admitted, else at least two."""
    steps = list(actions)
    cover = _cover(htn, steps, required)
    tried = cover if len(cover) == 1 else range(len(steps)) if not cover else ()
    if next(htn.executions.single_moves(steps, tried), None) is not None:
        return 1
    return max(len(cover), 2)


def _cover(htn: HTN, steps: Sequence[str], required: BoolMatrix) -> list[int]:
    """Positions a greedy cover takes out of ``steps`` so that no order ``htn`` requires is reversed
    (``required[i, j]``: ``htn.leaves[i]`` comes before ``htn.leaves[j]`` in every execution performing both)
    and no subtask is interleaved (a step the reading lacks conflicts with every other)."""
    leaves = to_leaves(steps)
    index = {leaf: i for i, leaf in enumerate(htn.leaves)}
    conflicts: dict[int, set[int]] = {p: set() for p in range(len(leaves))}
    for p, q in itertools.combinations(range(len(leaves)), 2):  # p done before q: reversed when q must precede
        first, second = index.get(leaves[p]), index.get(leaves[q])
        if first is None or second is None or required[second, first]:
            conflicts[p].add(q)
            conflicts[q].add(p)
    for node_leaves in _module_leaves(htn):  # a step inside a subtask's span that is not of it
        inside = [p for p, leaf in enumerate(leaves) if leaf in node_leaves]
        for p in range(inside[0] + 1, inside[-1]) if len(inside) > 1 else ():
            if leaves[p] not in node_leaves:
                for q in inside:
                    conflicts[p].add(q)
                    conflicts[q].add(p)
    taken: list[int] = []
    while any(conflicts.values()):
        worst = max(conflicts, key=lambda p: (len(conflicts[p]), -p))
        for other in conflicts.pop(worst):
            conflicts[other].discard(worst)
        taken.append(worst)
    return taken


def _log_symmetry(htn: HTN) -> float:
    """``log`` of how many leaf sequences of ``htn`` make one action sequence: the instances of a repeated
    subtask (siblings of one shape in a clique, the legs of a table) swap without changing what is done
    (``m!`` for ``m`` of them; exact when every instance is performed)."""
    total = 0.0
    stack: list[Node] = list(htn.roots)
    while stack:
        node = stack.pop()
        if isinstance(node, ActionNode):
            continue
        if isinstance(node, CliqueNode):
            classes = Counter(repr(shape(child)) for child in node.children)
            total += sum(math.lgamma(m + 1) for m in classes.values())
        stack.extend(node.children)
    return total


def _module_leaves(htn: HTN) -> list[frozenset[Leaf]]:
    """The leaves of every chain and clique below the roots (each performed without interruption)."""
    out: list[frozenset[Leaf]] = []
    stack: list[Node] = list(htn.roots)
    while stack:
        node = stack.pop()
        if isinstance(node, ActionNode):
            continue
        out.append(frozenset(node.leaves))
        stack.extend(node.children)
    return out


def select_reading(
    actions: Sequence[Sequence[str]],
    fit: Fitter,
    general: HTN,
    *,
    folds: int,
    min_demonstrations: int,
    slip_rate: float,
) -> Selection:
    """Choose a reading among those of ``full`` (see the module docstring).

    Args:
        actions: The demonstrations with their slips undone, as action ids; each one ``general`` admits (the
            slips were undone where it admits them), so as many distinct ones as it has executions are all of
            them.
        fit: Learns a reading from some of them (by index); called for each reading with every index, then
            for each fold.
        general: The ``general`` reading learned from all of them.
        folds: At most this many folds (leave one out when there are fewer demonstrations).
        min_demonstrations: Compare only from this many demonstrations on.
        slip_rate: The probability of a refused demonstration as noise (see the module docstring).
    """
    if len(actions) < min_demonstrations:
        return Selection(READINGS[0], "too few demonstrations")
    if general.count_orderings() <= len({tuple(a) for a in actions}):
        return Selection(READINGS[0], "every execution was demonstrated")
    everything = list(range(len(actions)))
    full = {name: general if name == READINGS[0] else fit(name, everything) for name in CANDIDATES}
    if len({(*htn.canonical(), htn.count_orderings()) for htn in full.values()}) == 1:
        return Selection(READINGS[0], "the readings agree")
    k = min(folds, len(actions))
    values: dict[str, list[float]] = {name: [] for name in full}  # each held-out demonstration's, fold by fold
    admitted = dict.fromkeys(full, 0)
    for fold in range(k):
        train = [i for i in range(len(actions)) if i % k != fold]
        held = [i for i in range(len(actions)) if i % k == fold]
        scored: dict[tuple[object, object], list[tuple[float, bool]]] = {}  # readings learning one hierarchy
        for name in full:
            htn = fit(name, train)
            key = (htn.roots, htn.top_level)
            if key not in scored:
                scored[key] = held_out_log_likelihoods(htn, [actions[i] for i in held], slip_rate)
            for value, ok in scored[key]:
                values[name].append(value)
                admitted[name] += ok
    scores = {name: sum(held) / len(actions) for name, held in values.items()}
    best = max(full, key=lambda name: (scores[name], -CANDIDATES.index(name)))
    chosen = next(name for name in full if _within_one_error(values[name], values[best]))
    notes = []
    if chosen != best:
        gap, error = _gap(values[chosen], values[best])
        notes.append(f"{best} best by {gap:.3f} nats, within one standard error, {error:.3f}")
    kept_instead = chosen != READINGS[0] and not same_executions(full[chosen], general)
    if kept_instead:
        gain, error = _gap(values[READINGS[0]], values[chosen])
        notes.append(f"{chosen} against {READINGS[0]}: {gain:+.3f} nats, standard error {error:.3f}")
    reason = "held-out likelihood" + (f" ({'; '.join(notes)})" if notes else "")
    if chosen != READINGS[0] and not kept_instead:
        reason += f"; {chosen} admits the same executions as {READINGS[0]}"
        return Selection(READINGS[0], reason, scores, admitted, k)
    return Selection(chosen, reason, scores, admitted, k)


def _gap(candidate: Sequence[float], best: Sequence[float]) -> tuple[float, float]:
    """How much better ``best`` predicted the held-out demonstrations than ``candidate`` (the mean of their
    differences, demonstration by demonstration, in nats) and the standard error of that mean (0 for one)."""
    differences = [b - c for b, c in zip(best, candidate, strict=True)]
    if len(differences) < 2:
        return statistics.fmean(differences), 0.0
    return statistics.fmean(differences), statistics.stdev(differences) / math.sqrt(len(differences))


def _within_one_error(candidate: Sequence[float], best: Sequence[float]) -> bool:
    """Whether ``candidate``'s mean held-out log-likelihood is within one standard error of ``best``'s (the
    one-standard-error rule, on the paired differences). Exactly one error away counts as within, rounding
    apart: that is every case in which a single held-out demonstration tells the two apart (``d`` once among
    ``n``: mean and standard error are both ``d / n``), which the last bit of a sum must not decide."""
    gap, error = _gap(candidate, best)
    return gap <= error or math.isclose(gap, error)


def same_executions(first: HTN, second: HTN, *, limit: int = 20_000) -> bool:
    """True when ``first`` and ``second`` admit exactly the same leaf sequences: their execution machines
    explored together, each as the set of states a prefix may lead to, until a prefix one may extend or end
    and the other not (False), or ``limit`` pairs of state sets (False: not shown equal).

    >>> from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, TopLevel
    >>> a, b = ActionNode("a"), ActionNode("b")
    >>> clique = HTN("t", (CliqueNode((a, b)),))
    >>> free = HTN("t", (a, b), TopLevel((0,), (3,), ((0, 0, 1), (0, 1, 2), (1, 1, 3), (2, 0, 3))))
    >>> same_executions(clique, free), same_executions(clique, HTN("t", (ChainNode((a, b)),)))
    (True, False)
    """
    machines = (first.executions, second.executions)
    start = (frozenset(machines[0].initial()), frozenset(machines[1].initial()))
    seen = {start}
    stack = [start]
    while stack:
        states = stack.pop()
        if len({any(m.can_finish(s) for s in group) for m, group in zip(machines, states, strict=True)}) > 1:
            return False
        nexts: list[dict[Leaf, set[Progress]]] = [{}, {}]
        for side, (machine, group) in enumerate(zip(machines, states, strict=True)):
            for state in group:
                for leaf, after in machine.moves(state).items():
                    nexts[side].setdefault(machine.leaves[leaf], set()).add(after)
        if nexts[0].keys() != nexts[1].keys():
            return False
        for label, reached in nexts[0].items():
            pair = (frozenset(reached), frozenset(nexts[1][label]))
            if pair not in seen:
                if len(seen) >= limit:
                    return False
                seen.add(pair)
                stack.append(pair)
    return True
