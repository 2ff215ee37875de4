"""The supportive-behavior TAMP problem Σ = (T, Π_T, a_s, C_s, s_c, P) of §3.2.5.

T — the lead agents, their operators and capabilities, s_0 and the goal — is the world; Π_T is a set of lead
plans that solve it; a_s, C_s and P say who supports and what it may and may not do; s_c is the state now.
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from dataclasses import dataclass, replace
from typing import Any, Generic, TypeVar

from supportive.errors import PlanningError
from supportive.planning.prototypes import Prototype
from supportive.planning.world import LEAD, SUPPORT, Operator, SupportWorld

__all__ = ["SupportProblem"]

StateT = TypeVar("StateT", bound=Hashable)
OperatorT = TypeVar("OperatorT", bound=Operator)
MoveT = TypeVar("MoveT", bound=Hashable)


@dataclass(frozen=True)
class SupportProblem(Generic[StateT, OperatorT, MoveT]):
    """Σ = (T, Π_T, a_s, C_s, s_c, P).

    Attributes:
        world: T, the TAMP problem: operators, geometry, motion models, s_0 (``world.initial_state``).
        plans: Π_T, the known lead plans (each a sequence of lead operators from s_0 to the goal).
        state: s_c, the current state.
        support_agent: a_s, the support agent's name.
        lead_agent: The lead agent whose plans Π_T are.
        capabilities: C_s, the operator prototypes a_s may use.
        prohibited: P, the predicate prototypes a_s must never add or delete.
        lead_busy: Seconds the lead still needs for the step it is in the middle of (s_c counts that step
            done); 0 between steps (see :func:`~supportive.planning.duration.estimate_duration`).
    """

    world: SupportWorld[StateT, OperatorT, MoveT]
    plans: tuple[tuple[OperatorT, ...], ...]
    state: StateT
    support_agent: str = SUPPORT
    lead_agent: str = LEAD
    capabilities: frozenset[str] = frozenset()
    prohibited: tuple[Prototype, ...] = ()
    lead_busy: float = 0.0

    @classmethod
    def of(
        cls,
        world: SupportWorld[StateT, OperatorT, MoveT],
        plans: Sequence[Sequence[OperatorT]],
        state: StateT | None = None,
        *,
        capabilities: frozenset[str] | None = None,
        prohibited: Sequence[str | Prototype] | None = None,
        **agents: Any,
    ) -> SupportProblem[StateT, OperatorT, MoveT]:
        """The problem for ``world`` and its plans, at ``state`` (default s_0), with C_s and P from the world
        unless given.

        Raises:
            PlanningError: when there is no plan, or a plan is empty.
        """
        known = tuple(tuple(plan) for plan in plans)
        if not known:
            raise PlanningError("Π_T is empty: the support planner needs at least one known lead plan")
        if any(not plan for plan in known):
            raise PlanningError("Π_T holds an empty plan: every known plan must have at least one step")
        texts = world.prohibited if prohibited is None else prohibited
        return cls(
            world,
            known,
            world.initial_state if state is None else state,
            capabilities=world.support_capabilities if capabilities is None else frozenset(capabilities),
            prohibited=tuple(p if isinstance(p, Prototype) else Prototype.parse(p) for p in texts),
            **agents,
        )

    def at(self, state: StateT, lead_busy: float = 0.0) -> SupportProblem[StateT, OperatorT, MoveT]:
        """The same problem with s_c = ``state`` (and the lead busy for ``lead_busy`` more seconds)."""
        return replace(self, state=state, lead_busy=lead_busy)
