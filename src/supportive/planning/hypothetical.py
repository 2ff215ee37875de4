"""Hypothetical environments (§3.2.5.1): Ξ = {ξ = (π, d, s)}.

Single-object changes are sampled from the world (an object and a new location and/or pose), the support
agent's plan to make each is asked of the world, and the plan is checked here, whatever the world: every
operator must be one of a_s's capabilities C_s, must not add or delete a predicate matching the prohibited
prototypes P, and must have its preconditions hold when its turn comes. What survives is kept with the plan's
duration (the support agent's motion model), the objects and space it ties up, and the state it leads to;
the rest are discarded and counted by reason.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Hashable
from dataclasses import dataclass, field
from typing import Generic, TypeVar

import numpy as np

from supportive.planning.problem import SupportProblem
from supportive.planning.prototypes import matching
from supportive.planning.world import Operator

__all__ = ["DISCARD_REASONS", "Hypothetical", "HypotheticalSet", "hypothetical_environments"]

StateT = TypeVar("StateT", bound=Hashable)
OperatorT = TypeVar("OperatorT", bound=Operator)
MoveT = TypeVar("MoveT", bound=Hashable)

DISCARD_REASONS = ("unreachable", "incapable", "prohibited", "precondition", "duplicate")
"""Why a sampled change is discarded: the world has no plan for it, the plan uses an operator outside C_s,
an effect matches P, a precondition fails along the plan, or the change was sampled before."""

_ATTEMPTS_PER_ENVIRONMENT = 4


@dataclass(frozen=True)
class Hypothetical(Generic[StateT, OperatorT, MoveT]):
    """ξ = (π, d, s): a support plan, its estimated duration and the environment it produces.

    Attributes:
        plan: π, the support agent's operators.
        duration: d, seconds the support agent needs to execute them.
        state: s, the state after them.
        resources: The objects and space the plan ties up (what the lead must wait for, Algorithm 5).
        move: The sampled change the plan makes (world-specific), None for the empty plan.
    """

    plan: tuple[OperatorT, ...]
    duration: float
    state: StateT
    resources: frozenset[Hashable] = field(default_factory=frozenset)
    move: MoveT | None = None

    @classmethod
    def idle(cls, state: StateT) -> Hypothetical[StateT, OperatorT, MoveT]:
        """The empty support plan: do nothing, the environment stays ``state``."""
        return cls((), 0.0, state)


@dataclass(frozen=True)
class HypotheticalSet(Generic[StateT, OperatorT, MoveT]):
    """The attainable hypothetical environments Ξ, and how many sampled changes were discarded, by reason."""

    environments: tuple[Hypothetical[StateT, OperatorT, MoveT], ...]
    discarded: dict[str, int]
    sampled: int


def hypothetical_environments(
    problem: SupportProblem[StateT, OperatorT, MoveT],
    count: int,
    seed: int | np.random.Generator | None = None,
) -> HypotheticalSet[StateT, OperatorT, MoveT]:
    """Sample up to ``count`` attainable hypothetical environments at s_c (§3.2.5.1).

    Changes are drawn from the world in rounds until ``count`` are attainable or
    ``4 * count`` have been drawn; the result depends only on the seed.

    Args:
        problem: Σ; its ``state`` is s_c.
        count: How many environments to keep (at most).
        seed: Seeds the sampling of changes.

    Returns:
        Ξ in the order sampled, with the discard counts.
    """
    rng = np.random.default_rng(seed)
    world = problem.world
    kept: list[Hypothetical[StateT, OperatorT, MoveT]] = []
    seen: set[MoveT] = set()
    discarded: Counter[str] = Counter()
    sampled = 0
    while len(kept) < count and sampled < _ATTEMPTS_PER_ENVIRONMENT * count:
        batch = world.sample_moves(problem.state, rng, count - len(kept))
        if not batch:
            break
        for move in batch:
            sampled += 1
            if move in seen:
                discarded["duplicate"] += 1
                continue
            seen.add(move)
            verdict = _attain(problem, move)
            if isinstance(verdict, str):
                discarded[verdict] += 1
            else:
                kept.append(verdict)
    return HypotheticalSet(tuple(kept), {r: discarded[r] for r in DISCARD_REASONS if discarded[r]}, sampled)


def _attain(
    problem: SupportProblem[StateT, OperatorT, MoveT], move: MoveT
) -> Hypothetical[StateT, OperatorT, MoveT] | str:
    """The environment ``move`` leads to, or the reason it is discarded."""
    world = problem.world
    agent = problem.support_agent
    plan = world.support_plan(problem.state, move)
    if plan is None or not plan:
        return "unreachable"
    if any(op.name not in problem.capabilities for op in plan):
        return "incapable"
    state = problem.state
    seconds = 0.0
    used: set[Hashable] = set()
    for op in plan:
        if not world.preconditions_hold(state, op, agent):
            return "precondition"
        if matching(world.effects(state, op, agent), problem.prohibited):
            return "prohibited"
        seconds += world.duration(state, op, agent)
        used |= world.resources(state, op, agent)
        state = world.apply(state, op, agent)
    return Hypothetical(tuple(plan), seconds, state, frozenset(used), move)
