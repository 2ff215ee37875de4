"""State regions as DNF formulas over grounded predicates (§3.3.4.3).

A *truth table* lists a task's states and, for each, which grounded predicates (atoms such as
``attached(seat, frame)`` or ``done(Attach front frame)``) hold. A literal is an atom or its negation; a
conjunction of literals holds in the states where all of them do; a DNF formula is a disjunction of
conjunctions and denotes the union of its clauses' state sets:

    S = ⋃_{c ∈ C} ⋂_{l ∈ c} R(l)

Everything is a boolean mask over the table's states (numpy), so evaluating a formula on thousands of states
is a few vector operations.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

__all__ = ["DNF", "Conjunction", "Literal", "TruthTable"]


@dataclass(frozen=True, order=True)
class Literal:
    """A grounded atom (``attached(seat, frame)``) or its negation."""

    atom: str
    positive: bool = True

    def negated(self) -> Literal:
        """The opposite literal."""
        return Literal(self.atom, not self.positive)

    def __str__(self) -> str:
        return self.atom if self.positive else f"not {self.atom}"


@dataclass(frozen=True)
class Conjunction:
    """Literals that must all hold (the empty conjunction holds everywhere)."""

    literals: frozenset[Literal]

    @classmethod
    def of(cls, *literals: Literal | str) -> Conjunction:
        """A conjunction of literals; a plain string is a positive literal."""
        return cls(frozenset(Literal(x) if isinstance(x, str) else x for x in literals))

    @property
    def consistent(self) -> bool:
        """False when it holds an atom both ways (it then denotes no state)."""
        return not any(lit.negated() in self.literals for lit in self.literals)

    def __len__(self) -> int:
        return len(self.literals)

    def __str__(self) -> str:
        return " and ".join(str(lit) for lit in sorted(self.literals)) or "always"


@dataclass(frozen=True)
class DNF:
    """A disjunction of conjunctions (no clause: denotes no state)."""

    clauses: tuple[Conjunction, ...]

    @classmethod
    def of(cls, *clauses: Conjunction | Iterable[Literal | str]) -> DNF:
        """A DNF from conjunctions or iterables of literals."""
        return cls(tuple(c if isinstance(c, Conjunction) else Conjunction.of(*c) for c in clauses))

    @property
    def size(self) -> int:
        """Total number of literals: how long it takes to say."""
        return sum(len(c) for c in self.clauses)

    def atoms(self) -> frozenset[str]:
        """Every atom the formula mentions."""
        return frozenset(lit.atom for clause in self.clauses for lit in clause.literals)

    def __str__(self) -> str:
        return " or ".join(f"({c})" if len(self.clauses) > 1 and len(c) > 1 else str(c) for c in self.clauses) or "never"


class TruthTable:
    """Which atoms hold in which states.

    Args:
        states: The states (any hashable values), in a fixed order.
        atoms: The grounded atoms, in a fixed order.
        values: Boolean matrix, ``values[i, j]`` = atom ``j`` holds in state ``i``.

    Raises:
        ValueError: for a shape mismatch or repeated states or atoms.

    >>> table = TruthTable.from_sets(["s0", "s1", "s2"], {"p": {"s1", "s2"}, "q": {"s2"}})
    >>> sorted(table.states_of(DNF.of(["p", Literal("q", False)])))
    ['s1']
    >>> sorted(table.states_of(DNF.of(["q"], [Literal("p", False)])))
    ['s0', 's2']
    """

    def __init__(self, states: Sequence[Hashable], atoms: Sequence[str], values: np.ndarray) -> None:
        matrix = np.asarray(values, dtype=bool)
        if matrix.shape != (len(states), len(atoms)):
            raise ValueError(f"values has shape {matrix.shape}, expected {(len(states), len(atoms))}")
        if len(set(states)) != len(states) or len(set(atoms)) != len(atoms):
            raise ValueError("states and atoms must not repeat")
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
                    raise ValueError(f"atom {list(holds)[j]!r} holds in an unknown state {state!r}")
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
