"""Algorithm 5: estimating how long a lead plan takes in a hypothetical environment.

The lead executes its plan step by step in the environment ξ.s the support plan produces. A step whose
objects or space the support plan also uses must first wait for the support plan to finish (the time left
of ξ.d); every step then takes its own execution time, weighted by the decay γ(i), and the support plan's
remaining time shrinks by what the step took. A step whose preconditions fail makes the plan impossible:
the estimate is the nullification penalty, a value greater than the worst known plan's duration.

Two readings of the thesis's listing are corrected here (docs/support.md says why):

* the listing indents lines 11–14 under the "shared objects" test, so a step that shares nothing with the
  support plan would take no time and never change the state; every step takes its time and is applied;
* the listing starts from s_c, where the support plan has not acted, so no support plan could ever help;
  the plan is executed in ξ.s (for the empty support plan ξ.s is s_c) and the waiting models that ξ.s is
  reached only after ξ.d.

Steps the lead has already done in s_c are skipped (``world.remaining_plan``); a state the plan contradicts
gets the penalty too. A decision taken while the lead is in the middle of a step (the state counts that step
done) gives the seconds the lead still needs for it as ``lead_busy``: the support plan runs on meanwhile.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Sequence
from dataclasses import dataclass
from typing import TypeVar

from supportive.errors import PlanningError
from supportive.planning.hypothetical import Hypothetical
from supportive.planning.world import LEAD, Operator, SupportWorld

__all__ = ["Decay", "GeometricDecay", "estimate_duration", "no_decay"]

StateT = TypeVar("StateT", bound=Hashable)
OperatorT = TypeVar("OperatorT", bound=Operator)
MoveT = TypeVar("MoveT", bound=Hashable)

Decay = Callable[[int], float]
"""γ: Z+ → [0, 1], the weight of the i-th step (1-based) of a plan."""


def no_decay(step: int) -> float:
    """γ(i) = 1: every step counts fully (the thesis's f(x) = 1)."""
    return 1.0


@dataclass(frozen=True)
class GeometricDecay:
    """γ(i) = rate^(i−1): near-term effects of a support plan count more than distant ones.

    >>> GeometricDecay(0.5)(3)
    0.25
    """

    rate: float

    def __post_init__(self) -> None:
        if not 0.0 < self.rate <= 1.0:
            raise PlanningError(f"decay rate must be in (0, 1], got {self.rate}")

    def __call__(self, step: int) -> float:
        """The weight of step ``step`` (1-based)."""
        return float(self.rate ** (step - 1))


def estimate_duration(
    world: SupportWorld[StateT, OperatorT, MoveT],
    plan: Sequence[OperatorT],
    support: Hypothetical[StateT, OperatorT, MoveT],
    penalty: float,
    decay: Decay = no_decay,
    lead: str = LEAD,
    lead_busy: float = 0.0,
) -> float:
    """Algorithm 5: the estimated execution duration of lead plan ``plan`` given support plan ``support``.

    Args:
        world: The world (operators, preconditions, motion durations, resources).
        plan: π, a lead plan (from s_0; steps already done in the support's start state are skipped).
        support: ξ; ``Hypothetical.idle(s_c)`` for no support.
        penalty: PLAN_NULLIFICATION_PENALTY, returned when a step's preconditions fail.
        decay: γ, the weight of each step by its position among the steps still to do.
        lead: The lead agent's name.
        lead_busy: Seconds the lead still needs for the step it is in the middle of, before the plan's next
            step can start (0 between steps); the support plan runs on meanwhile, so that much less of it is
            left to wait for. The estimate counts from the end of that step.

    Returns:
        Seconds (weighted by γ), or ``penalty``.
    """
    state = support.state
    steps = world.remaining_plan(state, plan)
    if steps is None:
        return penalty
    elapsed = 0.0
    left = max(0.0, support.duration - lead_busy)
    shared = support.resources
    for i, op in enumerate(steps, start=1):
        if not world.preconditions_hold(state, op, lead):
            return penalty
        step_time = 0.0
        if left > 0.0 and not shared.isdisjoint(world.resources(state, op, lead)):
            step_time = left  # must wait for the support plan to finish
        step_time += world.duration(state, op, lead)
        elapsed += step_time * decay(i)
        left = max(0.0, left - step_time)
        state = world.apply(state, op, lead)
    return elapsed
