"""P(safe | τ), Eq. 3.2: is the novice's trajectory drawn from the experts' model of normal motion?

    P(safe | τ) = Π θ_{s_k}(a_k) P(safe) / (Π θ_{s_k}(a_k) P(safe) + Π ρ_{s_k}(a_k) (1 − P(safe)))

with ρ the unsafe model (uniform over the four moves, §3.5.3) and P(safe) = 0.5. The products are kept as one
running log-odds, log θ − log ρ added per step, so a trajectory of any length neither underflows nor costs
more than one addition per step.

``memory`` (γ, default 1: the thesis's Eq. 3.2 exactly) lets older steps fade: each step the log-odds'
distance from the prior's is multiplied by γ before the new step is added, so with γ < 1 the estimate
reflects roughly the last 1 / (1 − γ) moves. Over a whole 200-step trajectory Eq. 3.2 saturates — a novice
whose moves are mostly goal-directed is judged safe with probability ≈ 1 even while its random moves take it
down the stairs — and the caregiver then never acts for it; see docs/caregiver.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from supportive.errors import SafetyError
from supportive.safety.priors import ActionPriors
from supportive.worlds.household.grid_map import MOVES, Cell

__all__ = ["SafetyEstimate"]


@dataclass
class SafetyEstimate:
    """A running P(safe | τ) over a novice's moves.

    Args:
        priors: The action priors θ.
        prior_safe: P(safe), in (0, 1).
        unsafe: ρ_s(a), the unsafe model's probability of any move (uniform: 1/4).
        memory: γ in (0, 1]: how much of the past trajectory's evidence each step keeps (1: all of it).

    >>> from supportive.worlds.household import MapDistances, parse_map
    >>> priors = ActionPriors.from_experts(MapDistances(parse_map("#####\\n#B..#\\n#####\\n")), hyperprior=1.0)
    >>> estimate = SafetyEstimate(priors)
    >>> estimate.observe((1, 3), "west")
    0.6153846153846154
    """

    priors: ActionPriors
    prior_safe: float = 0.5
    unsafe: float = 1.0 / len(MOVES)
    memory: float = 1.0
    log_odds: float = field(init=False)
    steps: int = field(init=False, default=0)

    def __post_init__(self) -> None:
        if not 0.0 < self.prior_safe < 1.0:
            raise SafetyError(f"prior_safe must be in (0, 1), got {self.prior_safe}")
        if not 0.0 < self.unsafe <= 1.0:
            raise SafetyError(f"unsafe must be in (0, 1], got {self.unsafe}")
        if not 0.0 < self.memory <= 1.0:
            raise SafetyError(f"memory must be in (0, 1], got {self.memory}")
        self._prior_log_odds = math.log(self.prior_safe) - math.log1p(-self.prior_safe)
        self.reset()

    def reset(self) -> None:
        """Forget the trajectory."""
        self.log_odds = self._prior_log_odds
        self.steps = 0

    def observe(self, cell: Cell, move: str) -> float:
        """Add the novice's move ``move`` from ``cell``; return the new P(safe | τ)."""
        evidence = math.log(self.priors.probability(cell, move)) - math.log(self.unsafe)
        self.log_odds = self._prior_log_odds + self.memory * (self.log_odds - self._prior_log_odds) + evidence
        self.steps += 1
        return self.probability

    @property
    def probability(self) -> float:
        """P(safe | τ) for the trajectory so far (a logistic of the log-odds, stable at both ends)."""
        if self.log_odds >= 0:
            return 1.0 / (1.0 + math.exp(-self.log_odds))
        odds = math.exp(self.log_odds)
        return odds / (1.0 + odds)
