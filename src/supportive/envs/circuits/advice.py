"""What the support agent would do in a circuit scenario, and why, in words (``supportive support``).

:func:`advise` makes one decision at the scenario's table: the supportive actions chosen, the seconds they
take, the lead's expected saving, the known plans they favour most (with their estimated durations before and
after), and how many hypothetical environments were sampled, kept and discarded. :func:`simulate` runs the
lead alone and with the support agent and compares makespans and the lead's planning effort
(:class:`SupportSimulation`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, Literal

from supportive.envs.circuits.leads import GreedyCircuitLead
from supportive.envs.circuits.plans import CircuitPlan
from supportive.envs.circuits.scenario import CircuitScenario
from supportive.envs.tabletop.leads import PlanFollowingLead
from supportive.envs.tabletop.operators import Install
from supportive.envs.tabletop.team import TeamResult, run_team
from supportive.planning.problem import SupportProblem
from supportive.planning.selection import SupportDecision
from supportive.seeding import Seed

__all__ = ["FavouredPlan", "SupportAdvice", "SupportSimulation", "advise", "describe_plan", "simulate"]

LeadKind = Literal["plans", "greedy"]


def describe_plan(plan: CircuitPlan) -> str:
    """A plan's pieces in build order: ``battery, battery, led, switch (4 pieces)``."""
    kinds = [op.kind for op in plan if isinstance(op, Install)]
    return f"{', '.join(kinds)} ({len(kinds)} pieces)"


@dataclass(frozen=True)
class FavouredPlan:
    """A known plan the chosen action shortens, with its estimated durations (seconds)."""

    index: int
    text: str
    before: float
    after: float


@dataclass(frozen=True)
class SupportAdvice:
    """One decision of the support agent, in words and numbers."""

    scenario: str
    scheme: str
    actions: tuple[str, ...]
    support_seconds: float
    expected_saving: float
    favoured: tuple[FavouredPlan, ...]
    plans: int
    environments: int
    discarded: dict[str, int] = field(default_factory=dict)

    def lines(self) -> list[str]:
        """The advice as sentences, one per line."""
        out = [
            f"{self.scenario}: {self.plans} known plans, {self.scheme} weights; "
            f"{self.environments} hypothetical environments kept"
            + (
                f" ({', '.join(f'{n} {why}' for why, n in self.discarded.items())} discarded)"
                if self.discarded
                else ""
            )
        ]
        if not self.actions:
            out.append("The support agent does nothing: no sampled change shortens the lead's likely plans.")
            return out
        out.append(f"Supportive action ({self.support_seconds:.1f} s): " + "; then ".join(self.actions) + ".")
        out.append(
            f"Expected saving for the lead: {self.expected_saving:.2f} s (weighted over the known plans)."
        )
        for plan in self.favoured:
            out.append(f"  favours plan {plan.index}: {plan.text}: {plan.before:.1f} s -> {plan.after:.1f} s")
        return out

    def as_dict(self) -> dict[str, Any]:
        """Plain JSON data."""
        return {
            "scenario": self.scenario,
            "scheme": self.scheme,
            "actions": list(self.actions),
            "support_seconds": round(self.support_seconds, 3),
            "expected_saving": round(self.expected_saving, 3),
            "favoured": [
                {"plan": p.index, "pieces": p.text, "before": round(p.before, 3), "after": round(p.after, 3)}
                for p in self.favoured
            ],
            "plans": self.plans,
            "environments": self.environments,
            "discarded": dict(self.discarded),
        }


def advise(
    scenario: CircuitScenario,
    plans: Sequence[CircuitPlan],
    *,
    seed: Seed = 0,
    workers: int = 1,
    favoured: int = 3,
) -> tuple[SupportAdvice, SupportDecision[Any, Any, Any]]:
    """The support agent's decision at the scenario's table, and the advice that says it.

    Raises:
        SearchLimitError: when the decision would make more duration estimates than the scenario's
            ``estimate_limit`` (checked before any is made).
    """
    scenario.check_decision(plans)
    world = scenario.world
    problem = SupportProblem.of(world, plans)
    with scenario.planner(workers=workers).fit(problem) as planner:
        decision = planner.decide(problem, seed)
    chosen = decision.chosen
    advice = SupportAdvice(
        scenario.name,
        scenario.scheme.value,
        tuple(world.describe(op) for op in chosen.plan),
        chosen.duration,
        decision.expected_saving,
        tuple(
            FavouredPlan(i, describe_plan(plans[i]), decision.idle_durations[i], decision.chosen_durations[i])
            for i in decision.favoured(favoured)
        ),
        len(plans),
        len(decision.candidates.environments),
        dict(decision.candidates.discarded),
    )
    return advice, decision


@dataclass(frozen=True)
class SupportSimulation:
    """The lead alone and with the support agent on one table.

    Attributes:
        lead: Which lead ran (``plans`` or ``greedy``).
        alone: The lead's run alone.
        supported: Its run with the support agent.
    """

    lead: str
    alone: TeamResult[Any]
    supported: TeamResult[Any]

    @property
    def gain_percent(self) -> float:
        """How much faster the supported lead finished, in percent of its makespan alone (0 when that is 0)."""
        alone = self.alone.makespan
        return 100.0 * (1.0 - self.supported.makespan / alone) if alone else 0.0

    def line(self) -> str:
        """The comparison as one sentence."""
        alone, helped = self.alone, self.supported
        return (
            f"Simulated ({self.lead} lead): alone {alone.makespan:.1f} s, with support {helped.makespan:.1f} s "
            f"({self.gain_percent:+.1f} % faster, {helped.support_actions} supportive actions); lead search nodes "
            f"{alone.lead_nodes} -> {helped.lead_nodes}"
        )

    def as_dict(self) -> dict[str, Any]:
        """Plain JSON data."""
        alone, helped = self.alone, self.supported
        return {
            "lead": self.lead,
            "alone": {"makespan": alone.makespan, "completed": alone.completed, "lead_nodes": alone.lead_nodes},
            "supported": {
                "makespan": helped.makespan,
                "completed": helped.completed,
                "lead_nodes": helped.lead_nodes,
                "support_actions": helped.support_actions,
                "conflicts": dict(helped.conflicts),
            },
        }


def simulate(
    scenario: CircuitScenario,
    plans: Sequence[CircuitPlan],
    lead: LeadKind = "plans",
    *,
    seed: Seed = 0,
    workers: int = 1,
) -> SupportSimulation:
    """The lead alone, then with the support agent: the thesis's makespan comparison on one table.

    Args:
        scenario: The scenario.
        plans: Π_T (the plan-following lead knows all of it).
        lead: ``plans`` (follows the quickest known plan) or ``greedy`` (plans online with the proximity
            heuristic).
        seed: Seeds the support agent's sampling.
        workers: Local processes scoring candidates.

    Raises:
        SearchLimitError: when each decision would make more duration estimates than the scenario's
            ``estimate_limit`` (checked before the runs).
    """
    scenario.check_decision(plans)
    world = scenario.world
    known = tuple(plans)

    def policy() -> Any:
        return GreedyCircuitLead() if lead == "greedy" else PlanFollowingLead(known)

    alone = run_team(world, policy())
    with scenario.planner(workers=workers).fit(SupportProblem.of(world, known)) as planner:
        helped = run_team(world, policy(), planner, known, seed=seed, record=True)
    return SupportSimulation(lead, alone, helped)
