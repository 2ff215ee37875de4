"""Running the support-TAMP experiment: one trial = one random table of the thesis-size circuit task, every
scenario and speed pairing run with the lead alone and with the support agent.

* ``unpredictable`` (scenario 1): the lead knows a random subset of Π_T (each plan with probability ½, at
  least one) and follows the quickest valid plan of it; the support agent uses conservative weights.
* ``heuristic`` (scenario 2): the lead plans online with the greedy proximity heuristic; the support agent
  uses aggressive weights.

Lead and support agent are each fast (100 %) or slow (33 %). The same table, the same known subset and the
same seeds are used with and without support (common random numbers), and under every reading.

**Readings** (:data:`READINGS`): what the support agent minimises. ``duration`` is §3.2.7's Σ_π w_π ·
duration; ``search-aware`` adds the greedy lead's search effort in the environment it would make (§3.2.5,
:class:`~supportive.envs.circuits.greedy.GreedySearchEffort`, weight λ = 1: see
:class:`~supportive.planning.selection.SupportPlanner`). A plan-following lead has no search to model, so in
scenario 1 both readings are the same run.

**The motion model's ceiling.** Every trial also records, per scenario and lead speed, the least time
perfect, free staging could leave the lead for the plan it follows alone (:func:`alone_plan`): every piece
already lying on its target spot, turned right (:func:`staged_floor`) — only the hand's travel between
targets and one grasp and release per piece remain.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from typing import Any

from supportive.envs.circuits.greedy import GreedySearchEffort, greedy_search
from supportive.envs.circuits.leads import GreedyCircuitLead
from supportive.envs.circuits.plans import loop_plan
from supportive.envs.circuits.scenario import thesis_scenario
from supportive.envs.circuits.world import CircuitWorld
from supportive.envs.tabletop.leads import PlanFollowingLead
from supportive.envs.tabletop.operators import Install
from supportive.envs.tabletop.team import LeadPolicy, TeamResult, run_team
from supportive.envs.tabletop.world import TabletopWorld
from supportive.errors import PlanningError
from supportive.experiments.readings import Reading, reading_names
from supportive.experiments.trials import Trial, spawn_trials
from supportive.planning.duration import estimate_duration
from supportive.planning.hypothetical import Hypothetical
from supportive.planning.problem import SupportProblem

__all__ = [
    "DEFAULT_TRIALS",
    "ENVIRONMENTS",
    "PAIRINGS",
    "READINGS",
    "SCENARIOS",
    "SEARCH_WEIGHT",
    "SLOW",
    "alone_plan",
    "make_trials",
    "run_trial",
    "staged_floor",
]

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
SEARCH_WEIGHT = 1.0
"""λ of the ``search-aware`` reading: a 1 % smaller search weighs as much as 1 % of the expected weighted
duration (not tuned: the neutral weight of two relative changes)."""

DEFAULT_TRIALS = 30
"""Random tables of a full run."""
READINGS = (
    Reading(
        "duration",
        "the support agent minimises Σ_π w_π · duration(π, ξ), the expected duration of the lead's plans",
        "§3.2.7 prints the objective the algorithm minimises, min_ξ Σ_π w_π · duration(T, π, ξ, s_c, γ), and "
        "§3.2.9 does not say it changes for the heuristic lead: the default.",
    ),
    Reading(
        "search-aware",
        "the same plus λ = 1 times the greedy lead's relative search effort in ξ.s (scenario 2 only)",
        "§3.2.5: a solution to Σ \"reduces the expected duration … or reduces the expected search complexity "
        "required for agents in A to find solutions\", environments are evaluated \"based on metrics such as "
        "the estimated cognitive (planning complexity) or physical (motion complexity) demands\", and §3.2.9.3 "
        "credits a support agent \"aware of a lead agent's planner heuristic(s)\" with reducing its search.",
    ),
)
"""What the support agent minimises, as named readings; the first (``duration``) is the default."""


def make_trials(trials: int, seed: int, readings: Sequence[str] | None = None) -> Sequence[Trial]:
    """``trials`` random tables, each trial with its own seed, under ``readings`` (default: all)."""
    chosen = list(readings if readings is not None else reading_names(READINGS))
    return spawn_trials(seed, [{"environments": ENVIRONMENTS, "readings": chosen} for _ in range(trials)])


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


def staged_floor(world: TabletopWorld[Any, Any], plan: Sequence[Any]) -> float:
    """The lead's time for ``plan`` if every piece it installs already lay on its target spot, turned as it
    goes in (perfect, free staging): the hand's travel from its start to each target in turn plus one grasp
    and one release per piece, under the world's motion model."""
    arm = world.lead_arm
    hand = world.initial_state.hands[0]
    total = 0.0
    for op in plan:
        if isinstance(op, Install):
            target = world.target_point(op.target)
            total += arm.travel(hand, target) + arm.handling(grasps=1, releases=1)
            hand = target
    return total


def alone_plan(scenario: str, world: CircuitWorld, known: Sequence[Sequence[Any]]) -> tuple[Any, ...]:
    """The plan the lead starts on when alone: for the unpredictable lead the quickest known plan from s_0
    (Algorithm 5, as :class:`~supportive.envs.tabletop.leads.PlanFollowingLead` chooses), for the greedy lead
    the circuit its first search finds."""
    start = world.initial_state
    if scenario == "heuristic":
        loop, _ = greedy_search(world, start)
        if loop is None:
            raise PlanningError("the greedy lead finds no circuit on this table")
        return loop_plan(loop)
    idle = Hypothetical[Any, Any, Any].idle(start)
    plans = [tuple(plan) for plan in known]
    return min(plans, key=lambda plan: estimate_duration(world, plan, idle, float("inf")))


def run_trial(trial: Trial) -> dict[str, Any]:
    """Every scenario and pairing on one random table, alone and supported under each reading."""
    rng = trial.rng()
    layout_seed = int(rng.integers(2**31))
    environments = int(trial.params.get("environments", ENVIRONMENTS))
    readings = list(trial.params.get("readings", reading_names(READINGS)))
    base = thesis_scenario(layout_seed, environments=environments)
    plans = base.plans()
    subset = [plan for plan in plans if rng.random() < 0.5] or [plans[int(rng.integers(len(plans)))]]
    support_seed = int(rng.integers(2**31))
    effort = GreedySearchEffort(base.world)  # the search does not depend on speeds: one cache per table
    out: dict[str, Any] = {
        "index": trial.index,
        "layout_seed": layout_seed,
        "plans": len(plans),
        "known_by_lead": len(subset),
        "scenarios": {},
        "floor": {},
    }
    timing: dict[str, Any] = {}
    for scenario, scheme in SCENARIOS.items():
        known = subset if scenario == "unpredictable" else plans
        out["scenarios"][scenario] = {}
        out["floor"][scenario] = {}
        timing[scenario] = {}
        for pairing, (lead_speed, support_speed) in PAIRINGS.items():
            # A fresh world for each run: its memories of boards must not speed up the run after it.
            began = time.perf_counter()
            alone_world = base.world.with_speeds(lead_speed, support_speed)
            alone = run_team(alone_world, _lead(scenario, known))
            alone_seconds = time.perf_counter() - began
            out["floor"][scenario][pairing] = staged_floor(alone_world, alone_plan(scenario, alone_world, known))
            supported: dict[str, Any] = {}
            timing[scenario][pairing] = {
                "alone": {"lead_planning_seconds": alone.lead_planning_seconds, "run_seconds": alone_seconds}
            }
            for reading in readings:
                searching = reading == "search-aware" and scenario == "heuristic"
                if scenario == "unpredictable" and supported:
                    supported[reading] = next(iter(supported.values()))  # the same run: no search to model
                    continue
                world = base.world.with_speeds(lead_speed, support_speed)
                options: dict[str, Any] = {"scheme": scheme}
                if searching:
                    options.update(search=effort, search_weight=SEARCH_WEIGHT)
                planner = base.planner(**options).fit(SupportProblem.of(world, plans))
                began = time.perf_counter()
                with planner:
                    helped = run_team(world, _lead(scenario, known), planner, plans, seed=support_seed)
                supported[reading] = _outcome(helped)
                timing[scenario][pairing][reading] = {
                    "lead_planning_seconds": helped.lead_planning_seconds,
                    "support_planning_seconds": helped.support_planning_seconds,
                    "run_seconds": time.perf_counter() - began,
                }
            out["scenarios"][scenario][pairing] = {"alone": _outcome(alone), "supported": supported}
    out["timing"] = timing
    return out
