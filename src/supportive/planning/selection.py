"""Choosing the supportive action (§3.2.7): ξ* = argmin_{ξ ∈ Ξ} Σ_{π ∈ Π_T} w_π · duration(T, π, ξ, s_c, γ).

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

from supportive.errors import PlanningError
from supportive.planning.duration import Decay, estimate_duration, no_decay
from supportive.planning.evaluation import Scorer, ScoringContext, open_scorer
from supportive.planning.hypothetical import Hypothetical, HypotheticalSet, hypothetical_environments
from supportive.planning.problem import SupportProblem
from supportive.planning.weighting import WeightingScheme, parse_scheme, plan_weights
from supportive.planning.world import Operator

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
        score: Its weighted duration sum.
        idle_score: The weighted duration sum of doing nothing.
        weights: w_π of every known plan.
        idle_durations: Each plan's estimated duration without support from s_c.
        chosen_durations: Each plan's estimated duration with ξ*.
        candidates: Ξ as sampled (without the idle candidate), with discard counts.
        scores: The score of every candidate of Ξ, in order.
    """

    chosen: Hypothetical[StateT, OperatorT, MoveT]
    score: float
    idle_score: float
    weights: tuple[float, ...]
    idle_durations: tuple[float, ...]
    chosen_durations: tuple[float, ...]
    candidates: HypotheticalSet[StateT, OperatorT, MoveT]
    scores: tuple[float, ...]

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


class SupportPlanner(Generic[StateT, OperatorT, MoveT]):
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
    ) -> None:
        if environments < 1:
            raise PlanningError(f"environments must be >= 1, got {environments}")
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
        self._scorer: Scorer | None = None
        self._context: ScoringContext[StateT, OperatorT, MoveT] | None = None

    def fit(self, problem: SupportProblem[StateT, OperatorT, MoveT]) -> Self:
        """Estimate every known plan in s_0 without support, and set the weights and the penalty.

        Raises:
            PlanningError: when a known plan cannot be executed in s_0.
        """
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
            PlanningError: when the planner was not fitted, or was fitted on other plans.
        """
        context = self._fitted(problem)
        candidates = hypothetical_environments(problem, self.environments, seed)
        idle = Hypothetical[StateT, OperatorT, MoveT].idle(problem.state)
        busy = problem.lead_busy
        idle_durations = context.durations(idle, busy)
        weights = self._weights_at(idle_durations) if self.reweight else self.weights_
        idle_score = float(np.dot(weights, idle_durations))
        scores = (
            self._scorer_for(context).scores(candidates.environments, weights, busy) if any(weights) else []
        )
        chosen, score = idle, idle_score
        if scores:
            best = int(np.argmin(scores))
            if scores[best] < idle_score - _RELATIVE_GAIN * abs(idle_score):
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
            raise PlanningError("the support planner is not fitted: call fit(problem) first")
        if self._context.plans != problem.plans or self._context.world is not problem.world:
            raise PlanningError("the support planner was fitted on another world or plan set: fit it again")
        return self._context

    def _scorer_for(self, context: ScoringContext[StateT, OperatorT, MoveT]) -> Scorer:
        if self._scorer is None:
            self._scorer = open_scorer(context, self.workers, self.client)
        return self._scorer
