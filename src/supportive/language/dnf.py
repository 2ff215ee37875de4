"""State regions as DNF formulas over grounded predicates (§3.3.4.3).

A *truth table* lists a task's states and, for each, which grounded predicates (atoms such as
``attached(seat, frame)`` or ``done(Attach front frame)``) hold. A literal is an atom or its negation; a
conjunction of literals holds in the states where all of them do; a DNF formula is a disjunction of
conjunctions and denotes the union of its clauses' state sets:

    S = ⋃_{c ∈ C} ⋂_{l ∈ c} R(l)

Everything is a boolean mask over the table's states (numpy), so evaluating a formula on thousands of states
is a few vector operations. The formula types themselves live in :mod:`supportive.tasks.formula` (task files
hold formulas) and are re-exported here.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable, Mapping, Sequence
from functools import cached_property

import numpy as np

from supportive.errors import LanguageError
from supportive.tasks.formula import DNF, Conjunction, Literal

__all__ = ["DNF", "Conjunction", "Literal", "TruthTable", "simplify"]


class TruthTable:
    """Which atoms hold in which states.

    Args:
        states: The states (any hashable values), in a fixed order.
        atoms: The grounded atoms, in a fixed order.
        values: Boolean matrix, ``values[i, j]`` = atom ``j`` holds in state ``i``.

    Raises:
        LanguageError: for a shape mismatch or repeated states or atoms.

    >>> table = TruthTable.from_sets(["s0", "s1", "s2"], {"p": {"s1", "s2"}, "q": {"s2"}})
    >>> sorted(table.states_of(DNF.of(["p", Literal("q", False)])))
    ['s1']
    >>> sorted(table.states_of(DNF.of(["q"], [Literal("p", False)])))
    ['s0', 's2']
    """

    def __init__(self, states: Sequence[Hashable], atoms: Sequence[str], values: np.ndarray) -> None:
        matrix = np.asarray(values, dtype=bool)
        if matrix.shape != (len(states), len(atoms)):
            raise LanguageError(f"values has shape {matrix.shape}, expected {(len(states), len(atoms))}")
        if len(set(states)) != len(states) or len(set(atoms)) != len(atoms):
            raise LanguageError("states and atoms must not repeat")
        self.states: tuple[Hashable, ...] = tuple(states)
        self.atoms: tuple[str, ...] = tuple(atoms)
        self.values = matrix

    @classmethod
    def from_sets(cls, states: Sequence[Hashable], holds: Mapping[str, Iterable[Hashable]]) -> TruthTable:
        """A table from, for each atom, the states where it holds (states not listed make it false)."""
        index = {state: i for i, state in enumerate(states)}
        values = np.zeros((len(states), len(holds)), dtype=bool)
        for j, where in enumerate(holds.values()):
            for state in where:
                if state not in index:
                    raise LanguageError(f"atom {list(holds)[j]!r} holds in an unknown state {state!r}")
                values[index[state], j] = True
        return cls(states, list(holds), values)

    @cached_property
    def atom_index(self) -> dict[str, int]:
        """Column of each atom."""
        return {atom: j for j, atom in enumerate(self.atoms)}

    @cached_property
    def state_index(self) -> dict[Hashable, int]:
        """Row of each state."""
        return {state: i for i, state in enumerate(self.states)}

    def literal_mask(self, literal: Literal) -> np.ndarray:
        """R(literal) as a mask over the states.

        Raises:
            KeyError: for an atom the table does not know.
        """
        column = self.values[:, self.atom_index[literal.atom]]
        return column if literal.positive else ~column

    def conjunction_mask(self, conjunction: Conjunction) -> np.ndarray:
        """R(conjunction): the states where every literal holds."""
        mask = np.ones(len(self.states), dtype=bool)
        for literal in conjunction.literals:
            mask &= self.literal_mask(literal)
        return mask

    def mask(self, formula: DNF) -> np.ndarray:
        """R(formula): the union of its clauses' state sets."""
        mask = np.zeros(len(self.states), dtype=bool)
        for clause in formula.clauses:
            mask |= self.conjunction_mask(clause)
        return mask

    def states_of(self, formula: DNF) -> frozenset[Hashable]:
        """The states the formula denotes."""
        return frozenset(s for s, keep in zip(self.states, self.mask(formula), strict=True) if keep)

    def mask_of(self, states: Iterable[Hashable]) -> np.ndarray:
        """A mask of the given states.

        Raises:
            KeyError: for a state the table does not know.
        """
        mask = np.zeros(len(self.states), dtype=bool)
        for state in states:
            mask[self.state_index[state]] = True
        return mask


def simplify(
    formula: DNF, table: TruthTable, within: Iterable[Hashable], *, fixed: frozenset[Literal] = frozenset()
) -> DNF:
    """A shorter formula that denotes the same states as ``formula`` among ``within`` (outside them: don't care).

    Clauses that hold in no state of ``within`` go; then each literal not in ``fixed`` is dropped from its clause
    while the clause still holds only where the formula does (within ``within``); then each clause the others
    already cover goes. Nothing is searched, so the result is short, not shortest (for that, see
    :func:`~supportive.language.cover.minimal_cover`); a formula that holds everywhere in ``within`` becomes
    ``true`` and one that holds nowhere ``false``.

    Args:
        formula: Every atom must be in the table.
        table: The states.
        within: The states that count.
        fixed: Literals never dropped (say, the words a person used), unless their whole clause goes.

    Raises:
        KeyError: for an atom or a state the table does not know.

    >>> table = TruthTable.from_sets(["s0", "s1", "s2"], {"p": {"s1", "s2"}, "q": {"s2"}})
    >>> str(simplify(DNF.of(["p", "q"], ["p", Literal("q", False)]), table, ["s0", "s1", "s2"]))
    'p'
    >>> str(simplify(DNF.of(["q", "p"]), table, ["s2"])), str(simplify(DNF.of(["q"]), table, ["s0", "s1"]))
    ('true', 'false')
    """
    inside = table.mask_of(within)
    clauses = [clause for clause in formula.clauses if (table.conjunction_mask(clause) & inside).any()]
    region = table.mask(DNF(tuple(clauses))) & inside
    outside = inside & ~region
    shortened: list[Conjunction] = []
    for clause in clauses:
        literals = set(clause.literals)
        for literal in sorted(clause.literals - fixed):
            fewer = Conjunction(frozenset(literals - {literal}))
            if not (table.conjunction_mask(fewer) & outside).any():
                literals.discard(literal)
        shortened.append(Conjunction(frozenset(literals)))
    kept = list(dict.fromkeys(shortened))
    for clause in sorted(kept, key=len, reverse=True):
        others = [c for c in kept if c != clause]
        if not (table.conjunction_mask(clause) & inside & ~table.mask(DNF(tuple(others)))).any():
            kept = others
    if any(not clause.literals for clause in kept):
        return DNF.true()
    return DNF(tuple(kept))
