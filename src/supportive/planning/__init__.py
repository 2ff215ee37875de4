"""Supportive-behavior task and motion planning (§3.2): help a lead by rearranging its environment.

The core is domain-agnostic: a world implements :class:`~supportive.planning.world.SupportWorld`; the
problem Σ (:class:`SupportProblem`) adds the known lead plans Π_T; :class:`SupportPlanner` samples
hypothetical environments, estimates every known plan in each (Algorithm 5), weights the plans and picks
the best environment to make. See docs/support.md.
"""

from supportive.planning.duration import Decay, GeometricDecay, estimate_duration, no_decay
from supportive.planning.hypothetical import Hypothetical, HypotheticalSet, hypothetical_environments
from supportive.planning.problem import SupportProblem
from supportive.planning.prototypes import Prototype, parse_prototypes
from supportive.planning.selection import SupportDecision, SupportPlanner
from supportive.planning.weighting import WeightingScheme, plan_weights
from supportive.planning.world import LEAD, SUPPORT, Effects, Operator, Predicate, SupportWorld

__all__ = [
    "LEAD",
    "SUPPORT",
    "Decay",
    "Effects",
    "GeometricDecay",
    "Hypothetical",
    "HypotheticalSet",
    "Operator",
    "Predicate",
    "Prototype",
    "SupportDecision",
    "SupportPlanner",
    "SupportProblem",
    "SupportWorld",
    "WeightingScheme",
    "estimate_duration",
    "hypothetical_environments",
    "no_decay",
    "parse_prototypes",
    "plan_weights",
]
