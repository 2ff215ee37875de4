"""What a world must provide for supportive-behavior planning (§3.2.3, §3.2.5): a small Protocol.

The planner in this package never looks inside a world's states or operators. A world says which operators
exist and what they do: whether an agent may apply one in a state (symbolic preconditions and geometric
predicates computed on demand), the state it leads to, how long it takes that agent (its motion duration),
which objects and space it ties up, and which predicates it adds and deletes (so that the prohibited predicate
prototypes P can be checked). It also proposes hypothetical environments — single-object changes — and the
support agent's plan to make each one (§3.2.5.1).

States must be hashable and picklable; operators must be hashable, picklable and carry a ``name`` (the
operator prototype, e.g. ``"pick"``), which the support agent's capabilities C_s are checked against.
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Sequence
from dataclasses import dataclass, field
from typing import Protocol, TypeVar

import numpy as np

__all__ = [
    "LEAD",
    "SUPPORT",
    "Effects",
    "LeadSearch",
    "Operator",
    "Predicate",
    "SupportWorld",
]

LEAD = "lead"
"""The name of the lead agent, the one that works towards the goal."""
SUPPORT = "support"
"""The name of the support agent a_s, the one that may only help."""

Predicate = tuple[str, ...]
"""A ground predicate: its name then its arguments, e.g. ``("on_board", "wire3-1")``."""


@dataclass(frozen=True)
class Effects:
    """What an operator changes: the predicates it makes true and those it makes false."""

    add: frozenset[Predicate] = field(default_factory=frozenset)
    delete: frozenset[Predicate] = field(default_factory=frozenset)

    @property
    def touched(self) -> frozenset[Predicate]:
        """Every predicate the operator adds or deletes."""
        return self.add | self.delete


StateT_contra = TypeVar("StateT_contra", contravariant=True)


class LeadSearch(Protocol[StateT_contra]):
    """The lead's search complexity in a state: the effort its planner spends there to find its next plan
    (search nodes, say). §3.2.5: a solution to Σ "reduces the expected duration … or reduces the expected
    search complexity required for agents in A to find solutions"; a support agent that knows the lead's
    planner heuristic can model it."""

    def __call__(self, state: StateT_contra, limit: float = math.inf) -> float:
        """The lead's search effort in ``state`` (>= 0) when it is at most ``limit``; otherwise any value
        above ``limit`` (the search may stop as soon as it knows)."""
        ...


class Operator(Protocol):
    """A parameterised operator: anything hashable with the name of its prototype."""

    @property
    def name(self) -> str:
        """The operator prototype (``"pick"``, ``"place"``, …)."""
        ...

    def __hash__(self) -> int: ...


StateT = TypeVar("StateT", bound=Hashable)
OperatorT = TypeVar("OperatorT", bound=Operator)
MoveT = TypeVar("MoveT", bound=Hashable)


class SupportWorld(Protocol[StateT, OperatorT, MoveT]):
    """A world the support planner can reason about (T's operators and geometry, a_s's abilities).

    Type parameters: the world's states, its operators, and its hypothetical changes ("moves": an object and
    the pose it could be moved to).
    """

    @property
    def initial_state(self) -> StateT:
        """s_0, the state the task starts in (plan weights are computed there)."""
        ...

    @property
    def support_capabilities(self) -> frozenset[str]:
        """C_s: the operator prototypes the support agent may use."""
        ...

    @property
    def prohibited(self) -> tuple[str, ...]:
        """P: predicate prototypes the support agent must never add or delete, e.g. ``"on_board(*)"``."""
        ...

    def objects(self, state: StateT) -> tuple[str, ...]:
        """The objects of the world, by name."""
        ...

    def holds(self, state: StateT, predicate: Predicate) -> bool:
        """Whether a predicate holds in a state; geometric ones (reachable, clear, …) computed on demand."""
        ...

    def preconditions_hold(self, state: StateT, operator: OperatorT, agent: str) -> bool:
        """Whether ``agent`` may apply ``operator`` in ``state``."""
        ...

    def apply(self, state: StateT, operator: OperatorT, agent: str) -> StateT:
        """The state after ``agent`` applies ``operator`` (its preconditions hold)."""
        ...

    def duration(self, state: StateT, operator: OperatorT, agent: str) -> float:
        """Seconds ``agent`` takes to execute ``operator`` from ``state`` (its motion model)."""
        ...

    def resources(self, state: StateT, operator: OperatorT, agent: str) -> frozenset[Hashable]:
        """The objects and regions of space ``operator`` ties up while ``agent`` executes it."""
        ...

    def effects(self, state: StateT, operator: OperatorT, agent: str) -> Effects:
        """The predicates ``operator`` adds and deletes when ``agent`` applies it in ``state``."""
        ...

    def remaining_plan(self, state: StateT, plan: Sequence[OperatorT]) -> tuple[OperatorT, ...] | None:
        """The steps of a lead plan still to do in ``state``; None when the state contradicts the plan
        (the lead has done something the plan does not do)."""
        ...

    def sample_moves(self, state: StateT, rng: np.random.Generator, count: int) -> list[MoveT]:
        """``count`` hypothetical single-object changes: an object and a new pose for it (§3.2.5.1)."""
        ...

    def support_plan(self, state: StateT, move: MoveT) -> tuple[OperatorT, ...] | None:
        """The support agent's operators that make ``move`` happen, or None when it cannot."""
        ...

    def describe(self, operator: OperatorT) -> str:
        """An operator in a few words, for people."""
        ...
