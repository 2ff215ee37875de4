"""A tiny world on a line, for checking the support planner by hand.

Objects lie at positions on a line; the goal is at 0 (only the lead puts things there) and the lead reaches
no further than ``reach``. The lead's operator ``Fetch(i)`` walks from its hand to the object and back to 0
(one unit per second); the support agent picks an object up and puts it down elsewhere (``speed`` units per
second). With ``cell`` set, objects also tie up the cell of the line they lie in.
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Sequence
from dataclasses import dataclass, replace

import numpy as np
import pytest

from supportive.planning.world import LEAD, Effects, Predicate


@dataclass(frozen=True)
class Fetch:
    item: int
    name: str = "fetch"


@dataclass(frozen=True)
class Pick:
    item: int
    name: str = "pick"


@dataclass(frozen=True)
class Put:
    item: int
    x: float
    name: str = "place"


LineOp = Fetch | Pick | Put


@dataclass(frozen=True)
class LineState:
    positions: tuple[float | None, ...]  # None: at the goal
    held: int | None
    lead_hand: float
    support_hand: float


@dataclass(frozen=True)
class LineMove:
    item: int
    x: float


class LineWorld:
    """The line world (see the module docstring)."""

    def __init__(
        self,
        names: Sequence[str],
        positions: Sequence[float],
        *,
        support_hand: float = 10.0,
        support_speed: float = 1.0,
        reach: float = 15.0,
        length: int = 20,
        cell: float | None = None,
        prohibited: tuple[str, ...] = ("in_goal(*)",),
    ) -> None:
        self.names = tuple(names)
        self._initial = LineState(tuple(positions), None, 0.0, support_hand)
        self.support_speed = support_speed
        self.reach = reach
        self.length = length
        self.cell = cell
        self._prohibited = prohibited

    @property
    def initial_state(self) -> LineState:
        return self._initial

    @property
    def support_capabilities(self) -> frozenset[str]:
        return frozenset({"pick", "place"})

    @property
    def prohibited(self) -> tuple[str, ...]:
        return self._prohibited

    def objects(self, state: LineState) -> tuple[str, ...]:
        return self.names

    def holds(self, state: LineState, predicate: Predicate) -> bool:
        name, item = predicate[0], self.names.index(predicate[-1])
        if name == "in_goal":
            return state.positions[item] is None
        if name == "reachable":
            x = state.positions[item]
            return x is not None and x <= self.reach
        raise ValueError(predicate)

    def _cells(self, x: float) -> frozenset[Hashable]:
        return frozenset() if self.cell is None else frozenset({("cell", math.floor(x / self.cell))})

    def preconditions_hold(self, state: LineState, op: LineOp, agent: str) -> bool:
        x = state.positions[op.item]
        if isinstance(op, Fetch):
            return agent == LEAD and x is not None and state.held != op.item and x <= self.reach
        if isinstance(op, Pick):
            return state.held is None
        return state.held == op.item and 1 <= op.x <= self.length

    def apply(self, state: LineState, op: LineOp, agent: str) -> LineState:
        positions = list(state.positions)
        if isinstance(op, Fetch):
            positions[op.item] = None
            return replace(state, positions=tuple(positions), lead_hand=0.0)
        if isinstance(op, Pick):
            x = state.positions[op.item]
            return replace(state, held=op.item, support_hand=0.0 if x is None else x)
        positions[op.item] = op.x
        return replace(state, positions=tuple(positions), held=None, support_hand=op.x)

    def duration(self, state: LineState, op: LineOp, agent: str) -> float:
        if isinstance(op, Fetch):
            x = state.positions[op.item]
            assert x is not None
            return abs(state.lead_hand - x) + x
        if isinstance(op, Pick):
            x = state.positions[op.item]
            return abs(state.support_hand - (0.0 if x is None else x)) / self.support_speed
        return abs(state.support_hand - op.x) / self.support_speed

    def resources(self, state: LineState, op: LineOp, agent: str) -> frozenset[Hashable]:
        if isinstance(op, Put):
            return frozenset({op.item}) | self._cells(op.x)
        x = state.positions[op.item]
        return frozenset({op.item}) | (frozenset() if x is None else self._cells(x))

    def effects(self, state: LineState, op: LineOp, agent: str) -> Effects:
        name = self.names[op.item]
        x = state.positions[op.item]
        where: Predicate = ("in_goal", name) if x is None else ("at", name, str(x))
        if isinstance(op, Fetch):
            return Effects(frozenset({("in_goal", name)}), frozenset({where}))
        if isinstance(op, Pick):
            return Effects(frozenset({("holding", agent, name)}), frozenset({where}))
        return Effects(frozenset({("at", name, str(op.x))}), frozenset({("holding", agent, name)}))

    def remaining_plan(self, state: LineState, plan: Sequence[LineOp]) -> tuple[LineOp, ...] | None:
        fetched = {op.item for op in plan}
        if any(x is None and i not in fetched for i, x in enumerate(state.positions)):
            return None
        return tuple(op for op in plan if state.positions[op.item] is not None)

    def sample_moves(self, state: LineState, rng: np.random.Generator, count: int) -> list[LineMove]:
        """Every (object, whole position) pair, in a random order, the first ``count``."""
        moves = [LineMove(i, float(x)) for i in range(len(self.names)) for x in range(1, self.length + 1)]
        order = rng.permutation(len(moves))
        return [moves[i] for i in order[:count]]

    def support_plan(self, state: LineState, move: LineMove) -> tuple[LineOp, ...] | None:
        if state.positions[move.item] == move.x:
            return None
        return (Pick(move.item), Put(move.item, move.x))

    def describe(self, op: LineOp) -> str:
        return f"{op.name} {self.names[op.item]}"

    def plans(self) -> tuple[tuple[LineOp, ...], ...]:
        """One plan per object: fetch it alone."""
        return tuple((Fetch(i),) for i in range(len(self.names)))


@pytest.fixture(scope="session")
def line_world_type() -> type[LineWorld]:
    """The LineWorld class."""
    return LineWorld
