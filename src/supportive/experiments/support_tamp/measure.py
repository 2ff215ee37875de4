"""Running the support-TAMP experiment: one trial = one random table of the thesis-size circuit task, every
scenario and speed pairing run with the lead alone and with the support agent.

* ``unpredictable`` (scenario 1): the lead knows a random subset of Π_T (each plan with probability ½, at
  least one) and follows the quickest valid plan of it; the support agent uses conservative weights.
* ``heuristic`` (scenario 2): the lead plans online with the greedy proximity heuristic; the support agent
  uses aggressive weights.

Lead and support agent are each fast (100 %) or slow (33 %). The same table, the same known subset and the
same seeds are used with and without support (common random numbers).
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from typing import Any

from supportive.envs.circuits.leads import GreedyCircuitLead
from supportive.envs.circuits.scenario import thesis_scenario
from supportive.envs.tabletop.leads import PlanFollowingLead
from supportive.envs.tabletop.team import LeadPolicy, TeamResult, run_team
from supportive.experiments.trials import Trial, spawn_trials
from supportive.planning.problem import SupportProblem

__all__ = ["ENVIRONMENTS", "PAIRINGS", "SCENARIOS", "SLOW", "make_trials", "run_trial"]

SLOW = 1 / 3
"""The thesis's slow agent: 33 % of full speed."""

PAIRINGS: dict[str, tuple[float, float]] = {
    "slow lead, fast support": (SLOW, 1.0),
    "fast lead, fast support": (1.0, 1.0),
    "slow lead, slow support": (SLOW, SLOW),
    "fast lead, slow support": (1.0, SLOW),
}
"""Lead and support speeds: a more, equally or less rapidly moving helper."""

SCENARIOS: dict[str, str] = {"unpredictable": "conservative", "heuristic": "aggressive"}
"""The thesis's two scenarios and the weighting scheme the support agent uses in each."""

ENVIRONMENTS = 200
"""Hypothetical environments per support decision."""


def make_trials(trials: int, seed: int) -> Sequence[Trial]:
    """``trials`` random tables, each trial with its own seed."""
    return spawn_trials(seed, [{"environments": ENVIRONMENTS} for _ in range(trials)])


def _lead(kind: str, known: Sequence[Any]) -> LeadPolicy[Any, Any]:
    return GreedyCircuitLead() if kind == "heuristic" else PlanFollowingLead(known)


def _outcome(result: TeamResult[Any]) -> dict[str, Any]:
    return {
        "makespan": result.makespan,
        "completed": result.completed,
        "lead_steps": result.lead_steps,
        "lead_nodes": result.lead_nodes,
        "lead_plans": result.lead_plans,
        "support_actions": result.support_actions,
        "support_decisions": result.support_decisions,
        "conflicts": dict(sorted(result.conflicts.items())),
    }


def run_trial(trial: Trial) -> dict[str, Any]:
    """Every scenario and pairing on one random table, alone and supported."""
    rng = trial.rng()
    layout_seed = int(rng.integers(2**31))
    environments = int(trial.params.get("environments", ENVIRONMENTS))
    base = thesis_scenario(layout_seed, environments=environments)
    plans = base.plans()
    subset = [plan for plan in plans if rng.random() < 0.5] or [plans[int(rng.integers(len(plans)))]]
    support_seed = int(rng.integers(2**31))
    out: dict[str, Any] = {
        "index": trial.index,
        "layout_seed": layout_seed,
        "plans": len(plans),
        "known_by_lead": len(subset),
        "scenarios": {},
    }
    timing: dict[str, Any] = {}
    for scenario, scheme in SCENARIOS.items():
        known = subset if scenario == "unpredictable" else plans
        out["scenarios"][scenario] = {}
        timing[scenario] = {}
        for pairing, (lead_speed, support_speed) in PAIRINGS.items():
            # A fresh world for each run: its memories of boards must not speed up the run after it.
            began = time.perf_counter()
            alone = run_team(base.world.with_speeds(lead_speed, support_speed), _lead(scenario, known))
            alone_seconds = time.perf_counter() - began
            world = base.world.with_speeds(lead_speed, support_speed)
            planner = base.planner(scheme=scheme).fit(SupportProblem.of(world, plans))
            began = time.perf_counter()
            with planner:
                helped = run_team(world, _lead(scenario, known), planner, plans, seed=support_seed)
            helped_seconds = time.perf_counter() - began
            out["scenarios"][scenario][pairing] = {"alone": _outcome(alone), "supported": _outcome(helped)}
            timing[scenario][pairing] = {
                "alone": {"lead_planning_seconds": alone.lead_planning_seconds, "run_seconds": alone_seconds},
                "supported": {
                    "lead_planning_seconds": helped.lead_planning_seconds,
                    "support_planning_seconds": helped.support_planning_seconds,
                    "run_seconds": helped_seconds,
                },
            }
    out["timing"] = timing
    return out
