"""A task's states and the predicates that hold in them: the space supportive behaviors are described over.

A state is what has been done so far: the set of the structure's leaves (action, performance) performed, for
every valid prefix of every valid ordering (breadth-first from nothing done, :func:`allowed_next`). In each
state hold:

* ``done(S)`` for every named subtask S whose actions are all done, ``active(S)`` for every one begun but not
  finished, ``ready(S)`` for every one not begun that may begin next
  (:data:`~supportive.tasks.behaviors.DERIVED_PREDICATES`);
* the task's own atoms, from the actions' ``effects``: an atom an action makes true holds once that action is
  done, unless an action done makes it false again (``not …`` effects win: in the tasks this is meant for —
  pick a part up, put it down — the undoing action always comes later).

The result is a :class:`~supportive.language.dnf.TruthTable` over every atom the task can mention, so any
formula of its predicates denotes a set of states.
"""

from __future__ import annotations

from collections import Counter, deque
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from supportive.errors import LanguageError, LearningError, UnknownNameError
from supportive.language.dnf import TruthTable
from supportive.language.wording import activity
from supportive.tasks.behaviors import DERIVED_PREDICATES, PredicateSpec
from supportive.tasks.formula import DNF, Conjunction, Literal, parse_formula, split_atom
from supportive.tasks.htn import ChainNode, CliqueNode, Leaf, Node, allowed_next, internal_nodes
from supportive.tasks.spec import TaskSpec

__all__ = ["MAX_STATES", "State", "TaskStates"]

State = frozenset[Leaf]
"""A task state: the leaves performed so far."""

MAX_STATES = 200_000
"""Refuse to enumerate more states than this (a task that large needs a factored state space)."""


@dataclass(frozen=True)
class TaskStates:
    """Every state of a task and the atoms that hold in each.

    Build with :meth:`of`.

    Attributes:
        spec: The task.
        structure: Its structure (the ground truth, or a learned hierarchy's single root).
        states: Every reachable state, in breadth-first order (the empty state first).
        table: The truth table of every atom over the states.
    """

    spec: TaskSpec
    structure: Node
    states: tuple[State, ...]
    table: TruthTable

    @classmethod
    def of(cls, spec: TaskSpec, structure: Node | None = None) -> TaskStates:
        """Enumerate the states of ``spec`` (under ``structure``, default: the spec's own).

        Raises:
            LearningError: when there is no structure, or more than :data:`MAX_STATES` states.

        >>> from supportive.examples import load
        >>> states = TaskStates.of(load("knife-carrots-celery"))
        >>> len(states.states), states.table.atoms[:2]
        (5, ('done(Prepare salad vegetables)', 'active(Prepare salad vegetables)'))
        """
        root = structure if structure is not None else spec.structure
        if root is None:
            raise LearningError(f"task {spec.name!r} has no structure to enumerate states from")
        states = _enumerate(root)
        subtasks = [n for n in internal_nodes(root) if n.name]
        atoms: dict[str, list[bool]] = {}
        for node in subtasks:
            leaves = frozenset(node.leaves)
            atoms[f"done({node.name})"] = [leaves <= s for s in states]
            atoms[f"active({node.name})"] = [bool(leaves & s) and not leaves <= s for s in states]
            atoms[f"ready({node.name})"] = [not leaves & s and bool(leaves & allowed_next(root, s)) for s in states]
        effects = {a.id: [parse_formula(e).clauses[0] for e in a.effects] for a in spec.actions}
        declared = {lit.atom for clauses in effects.values() for clause in clauses for lit in clause.literals}
        for name in sorted(declared):
            atoms[name] = [_holds(name, state, effects) for state in states]
        values = np.zeros((len(states), len(atoms)), dtype=bool)
        for j, column in enumerate(atoms.values()):
            values[:, j] = column
        return cls(spec, root, states, TruthTable(states, list(atoms), values))

    @cached_property
    def subtasks(self) -> dict[str, ChainNode | CliqueNode]:
        """The named subtasks by name."""
        return {n.name: n for n in internal_nodes(self.structure) if n.name}

    @cached_property
    def predicates(self) -> dict[str, PredicateSpec]:
        """The task's predicates and the derived ``done``/``active``, by name."""
        return {**DERIVED_PREDICATES, **{p.name: p for p in self.spec.predicates}}

    def during(self, subtask: str) -> frozenset[State]:
        """The states in which a person is at ``subtask``: about to begin it (``ready``) or under way
        (``active``) — what "when I am {subtask}" refers to.

        Raises:
            UnknownNameError: for an unknown subtask name.
        """
        if subtask not in self.subtasks:
            raise UnknownNameError(f"no subtask named {subtask!r} (known: {', '.join(sorted(self.subtasks))})")
        return self.table.states_of(DNF.of([f"active({subtask})"], [f"ready({subtask})"]))  # type: ignore[return-value]

    def grounded(self, formula: DNF | str) -> DNF:
        """The formula (or its text) over the table's atoms only: an atom the task never makes true holds
        nowhere, so a clause needing one goes and ``not`` of one is dropped from its clause."""
        parsed = parse_formula(formula) if isinstance(formula, str) else formula
        known = set(self.table.atoms)
        kept = []
        for clause in parsed.clauses:
            if all(lit.atom in known or not lit.positive for lit in clause.literals):
                kept.append(Conjunction(frozenset(lit for lit in clause.literals if lit.atom in known)))
        return DNF(tuple(kept))

    def region(self, formula: DNF | str) -> frozenset[State]:
        """The states a formula (or its text) denotes; an atom the task never makes true holds nowhere."""
        return self.table.states_of(self.grounded(formula))  # type: ignore[return-value]

    @cached_property
    def verbs(self) -> frozenset[str]:
        """The words the task's action texts begin with: verbs of this task, whatever the general list says."""
        return frozenset(a.text.split()[0].lower() for a in self.spec.actions if a.text and a.text.split())

    def activity(self, subtask: str) -> str:
        """A subtask as what the person is doing at it ("screwing seat", "working on yellow tower")."""
        return activity(subtask, self.verbs)

    def state_after(self, actions: Sequence[str]) -> State:
        """The state once ``actions`` (ids, in the order performed) are done; a repeated action is its next
        performance.

        Raises:
            LanguageError: when the actions are no valid beginning of the task.
        """
        counts: Counter[str] = Counter()
        leaves = set()
        for action in actions:
            counts[action] += 1
            leaves.add((action, counts[action]))
        state = frozenset(leaves)
        if state not in self.table.state_index:
            raise LanguageError(f"{', '.join(actions) or 'nothing'}: not a way the task can begin")
        return state

    def say(self, literal: Literal) -> str:
        """A literal in words, with its predicate's template (a subtask said as an activity).

        Raises:
            KeyError: for an atom of an unknown predicate.
        """
        name, args = split_atom(literal.atom)
        if name in DERIVED_PREDICATES:
            args = tuple(self.activity(a) for a in args)
        return self.predicates[name].say(args, literal.positive)


def _enumerate(root: Node) -> tuple[State, ...]:
    start: State = frozenset()
    seen = {start}
    order = [start]
    queue = deque([start])
    while queue:
        state = queue.popleft()
        for leaf in sorted(allowed_next(root, state)):
            following = state | {leaf}
            if following not in seen:
                if len(seen) >= MAX_STATES:
                    raise LearningError(f"the task has more than {MAX_STATES} states; describe it more coarsely")
                seen.add(following)
                order.append(following)
                queue.append(following)
    return tuple(order)


def _holds(atom: str, state: State, effects: dict[str, list[Conjunction]]) -> bool:
    done = {action for action, _ in state}
    made, unmade = False, False
    for action in done:
        for clause in effects.get(action, ()):
            for literal in clause.literals:
                if literal.atom == atom:
                    made |= literal.positive
                    unmade |= not literal.positive
    return made and not unmade

