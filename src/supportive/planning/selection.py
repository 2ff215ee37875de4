"""Choosing the supportive action (§3.2.7): ξ* = argmin_{ξ ∈ Ξ} Σ_{π ∈ Π_T} w_π · duration(T, π, ξ, s_c, γ).

Given a model of the lead's search (``search``, a :class:`~supportive.planning.world.LeadSearch`), the
objective also counts §3.2.5's other aim, "reduces the expected search complexity required for agents in A
to find solutions": + λ · D · S(ξ.s) / S(s_c), where S is the lead's search effort, D = Σ |w_π| ·
duration(π, idle) the scale of the weighted durations at s_c and λ the ``search_weight`` — with λ = 1 a
search 1 % smaller weighs as much as 1 % of the expected duration. Searching is costly, so the candidates are
taken in order of their duration score and each search is given only the effort that could still make its
candidate the best (branch and bound: S ≥ 0, so the choice is the one a full evaluation would make).

:class:`SupportPlanner` is fitted once on Σ — plan durations without support in s_0, their weights, the
nullification penalty — and then decides at any s_c: it samples hypothetical environments, scores them
(in this process, in local worker processes, or on Dask) together with doing nothing, and returns the best.
Doing nothing is candidate 0 and wins ties, so the support agent never acts for no expected gain.
"""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass
from types import TracebackType
from typing import Any, Generic, Self, TypeVar

import numpy as np

from supportive.errors import NotFittedError, PlanningError
from supportive.estimator import Estimator
from supportive.planning.duration import Decay, estimate_duration, no_decay
from supportive.planning.evaluation import Scorer, ScoringContext, open_scorer
from supportive.planning.hypothetical import Hypothetical, HypotheticalSet, hypothetical_environments
from supportive.planning.problem import SupportProblem
from supportive.planning.weighting import WeightingScheme, parse_scheme, plan_weights
from supportive.planning.world import LeadSearch, Operator

__all__ = ["SupportDecision", "SupportPlanner"]

StateT = TypeVar("StateT", bound=Hashable)
OperatorT = TypeVar("OperatorT", bound=Operator)
MoveT = TypeVar("MoveT", bound=Hashable)

_RELATIVE_GAIN = 1e-9


@dataclass(frozen=True)
class SupportDecision(Generic[StateT, OperatorT, MoveT]):
    """What the support agent chose at s_c, and why.

    Attributes:
        chosen: ξ*, the best hypothetical environment (``Hypothetical.idle`` when doing nothing is best).
        score: Its weighted duration sum, plus the search term with a search model.
        idle_score: The same for doing nothing.
        weights: w_π of every known plan.
        idle_durations: Each plan's estimated duration without support from s_c.
        chosen_durations: Each plan's estimated duration with ξ*.
        candidates: Ξ as sampled (without the idle candidate), with discard counts.
        scores: The weighted duration sum of every candidate of Ξ, in order.
        search_scale: What one unit of the lead's search effort adds to a score (0 without a search model).
        idle_search: The lead's search effort at s_c (None without a search model).
        chosen_search: Its search effort in ξ*.s (None without a search model).
    """

    chosen: Hypothetical[StateT, OperatorT, MoveT]
    score: float
    idle_score: float
    weights: tuple[float, ...]
    idle_durations: tuple[float, ...]
    chosen_durations: tuple[float, ...]
    candidates: HypotheticalSet[StateT, OperatorT, MoveT]
    scores: tuple[float, ...]
    search_scale: float = 0.0
    idle_search: float | None = None
    chosen_search: float | None = None

    @property
    def helps(self) -> bool:
        """Whether the support agent acts (its chosen plan is not empty)."""
        return bool(self.chosen.plan)

    @property
    def expected_saving(self) -> float:
        """Seconds the lead is expected to save: the change of each positively weighted plan's duration,
        averaged with the weights as probabilities (plans made impossible count their penalty)."""
        w = np.array(self.weights)
        keep = w > 0
        if not keep.any():
            return 0.0
        change = np.array(self.idle_durations) - np.array(self.chosen_durations)
        return float((w[keep] * change[keep]).sum() / w[keep].sum())

    def favoured(self, count: int = 3) -> list[int]:
        """Indices of the plans ξ* shortens most (largest saving first; ties by index), at most ``count``."""
        change = np.array(self.idle_durations) - np.array(self.chosen_durations)
        order = sorted((i for i in range(len(change)) if change[i] > 0), key=lambda i: (-change[i], i))
        return order[:count]


class SupportPlanner(Estimator, Generic[StateT, OperatorT, MoveT]):
    """Chooses supportive actions for an SB-TAMP problem (§3.2.5–3.2.7).

    Args:
        scheme: Plan weighting (§3.2.6): ``conservative``, ``greedy`` or ``aggressive``.
        environments: How many hypothetical environments to sample per decision.
        power: p of the conservative weights.
        epsilon: ε of the aggressive weights, a multiple of the best duration m.
        alpha: Aggressive weights: total negative magnitude as a share of the positive.
        decay: γ, the weight of each step of a lead plan (default: none).
        penalty_factor: PLAN_NULLIFICATION_PENALTY as a multiple of the worst known plan's duration in
            s_0 (> 1, the thesis's "greater than the cost of the worst known plan").
        reweight: Weigh the plans at every decision by their durations from s_c, over the plans still
            possible there (those the state does not contradict; the others weigh 0), instead of once by
            their durations from s_0 (the thesis's definition of m). Once the lead has started, the plans it
            may be following are then the ones that count, and the best of them sets m.
        workers: Local worker processes that score candidates (1: in this process).
        client: A ``dask.distributed.Client`` to score on instead.
        search: The lead's search effort in a state (:class:`~supportive.planning.world.LeadSearch`), to
            prefer environments where the lead's planner has less to search; None: durations only (§3.2.7).
        search_weight: λ, the weight of the relative search effort against the relative expected duration
            (see the module docstring); used only with ``search``.

    Attributes (after ``fit``):
        baseline_: Each plan's duration in s_0 without support.
        weights_: w_π.
        penalty_: The nullification penalty, seconds.
    """

    def __init__(
        self,
        scheme: WeightingScheme | str = WeightingScheme.CONSERVATIVE,
        *,
        environments: int = 200,
        power: float = 2.0,
        epsilon: float = 1.1,
        alpha: float = 0.5,
        decay: Decay = no_decay,
        penalty_factor: float = 2.0,
        reweight: bool = True,
        workers: int = 1,
        client: Any = None,
        search: LeadSearch[StateT] | None = None,
        search_weight: float = 1.0,
    ) -> None:
        if environments < 1:
            raise PlanningError(f"environments must be >= 1, got {environments}")
        if search_weight < 0:
            raise PlanningError(f"search_weight must be >= 0, got {search_weight}")
        if penalty_factor <= 1:
            raise PlanningError(f"penalty_factor must be > 1, got {penalty_factor}")
        self.scheme = parse_scheme(scheme)
        self.environments = environments
        self.power = power
        self.epsilon = epsilon
        self.alpha = alpha
        self.decay = decay
        self.penalty_factor = penalty_factor
        self.reweight = reweight
        self.workers = workers
        self.client = client
        self.search = search
        self.search_weight = search_weight
        self._scorer: Scorer | None = None
        self._context: ScoringContext[StateT, OperatorT, MoveT] | None = None

    def fit(self, problem: SupportProblem[StateT, OperatorT, MoveT]) -> Self:
        """Estimate every known plan in s_0 without support, and set the weights and the penalty.

        Raises:
            PlanningError: when a known plan cannot be executed in s_0.
        """
        self._forget()
        world = problem.world
        start = Hypothetical[StateT, OperatorT, MoveT].idle(world.initial_state)
        baseline = [
            estimate_duration(world, plan, start, float("inf"), no_decay, problem.lead_agent)
            for plan in problem.plans
        ]
        broken = [i for i, d in enumerate(baseline) if not np.isfinite(d)]
        if broken:
            raise PlanningError(f"known plans {broken} cannot be executed from the initial state")
        weights = plan_weights(
            baseline, self.scheme, power=self.power, epsilon=self.epsilon, alpha=self.alpha
        )
        self.baseline_ = tuple(baseline)
        self.weights_ = tuple(float(w) for w in weights)
        self.penalty_ = self.penalty_factor * max(baseline)
        self.close()
        self._context = ScoringContext(world, problem.plans, self.penalty_, self.decay, problem.lead_agent)
        return self

    def decide(
        self, problem: SupportProblem[StateT, OperatorT, MoveT], seed: int | np.random.Generator | None = None
    ) -> SupportDecision[StateT, OperatorT, MoveT]:
        """The best supportive action at ``problem.state`` (s_c).

        Raises:
            NotFittedError: when the planner was not fitted.
            PlanningError: when it was fitted on other plans.
        """
        context = self._fitted(problem)
        candidates = hypothetical_environments(problem, self.environments, seed)
        idle = Hypothetical[StateT, OperatorT, MoveT].idle(problem.state)
        busy = problem.lead_busy
        idle_durations = context.durations(idle, busy)
        weights = self._weights_at(idle_durations) if self.reweight else self.weights_
        idle_score = float(np.dot(weights, idle_durations))
        idle_search, scale = None, 0.0
        if self.search is not None:
            idle_search = float(self.search(problem.state))
            if idle_search > 0:
                scale = self.search_weight * float(np.dot(np.abs(weights), idle_durations)) / idle_search
            idle_score += scale * idle_search
        scores = self._scorer_for(context).scores(candidates.environments, weights, busy) if any(weights) else []
        chosen, score, chosen_search = idle, idle_score, idle_search
        bar = idle_score - _RELATIVE_GAIN * abs(idle_score)
        if scores and scale > 0 and self.search is not None:
            for i in sorted(range(len(scores)), key=scores.__getitem__):
                room = (bar - scores[i]) / scale
                if room <= 0:
                    break  # every later candidate has a duration score at least as high
                effort = float(self.search(candidates.environments[i].state, room))
                if effort < room:
                    chosen, score, chosen_search = candidates.environments[i], scores[i] + scale * effort, effort
                    bar = score
        elif scores:
            best = int(np.argmin(scores))
            if scores[best] < bar:
                chosen, score = candidates.environments[best], scores[best]
        return SupportDecision(
            chosen,
            score,
            idle_score,
            tuple(weights),
            tuple(float(d) for d in idle_durations),
            tuple(float(d) for d in (idle_durations if chosen is idle else context.durations(chosen, busy))),
            candidates,
            tuple(scores),
            scale,
            idle_search,
            chosen_search,
        )

    def _weights_at(self, durations: np.ndarray) -> tuple[float, ...]:
        """Plan weights from the plans' durations at s_c: the plans still possible are weighted by the
        scheme, the others weigh 0; all weigh 0 once a plan is finished (there is nothing left to help)."""
        possible = durations < self.penalty_
        if not possible.any() or np.any(durations[possible] <= 0):
            return tuple(0.0 for _ in durations)
        weights = np.zeros(len(durations))
        weights[possible] = plan_weights(
            durations[possible].tolist(),
            self.scheme,
            power=self.power,
            epsilon=self.epsilon,
            alpha=self.alpha,
        )
        return tuple(float(w) for w in weights)

    def close(self) -> None:
        """Stop any worker processes the planner started."""
        if self._scorer is not None:
            self._scorer.close()
            self._scorer = None

    def __enter__(self) -> Self:
        return self

    def __exit__(
        self, kind: type[BaseException] | None, value: BaseException | None, trace: TracebackType | None
    ) -> None:
        self.close()

    def _fitted(
        self, problem: SupportProblem[StateT, OperatorT, MoveT]
    ) -> ScoringContext[StateT, OperatorT, MoveT]:
        if self._context is None:
            raise NotFittedError("the support planner is not fitted: call fit(problem) first")
        if self._context.plans != problem.plans or self._context.world is not problem.world:
            raise PlanningError("the support planner was fitted on another world or plan set: fit it again")
        return self._context

    def _scorer_for(self, context: ScoringContext[StateT, OperatorT, MoveT]) -> Scorer:
        if self._scorer is None:
            self._scorer = open_scorer(context, self.workers, self.client)
        return self._scorer
