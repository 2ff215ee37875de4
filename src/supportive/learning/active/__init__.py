"""Active learning of task structure (§2.2): query strategies over the CTG and interactive teaching sessions.

>>> session = TeachingSession(["a", "b", "c"], strategy="connectivity", seed=0)
>>> session.begin()
>>> for step in ["a", "b", "c"]:
...     session.observe(step)
>>> _ = session.end()
>>> session.begin(); session.observe("a"); session.query()
'c'
"""

from supportive.learning.active.anti_edges import AntiEdges, StateKey, state_key
from supportive.learning.active.context import QueryContext
from supportive.learning.active.driver import InstructorLike, run_session
from supportive.learning.active.registry import register_strategy, strategy, strategy_names
from supportive.learning.active.schedule import QuerySchedule
from supportive.learning.active.scores import connectivity_base, connectivity_scores, ctg_distances
from supportive.learning.active.session import QueryRecord, TeachingSession
from supportive.learning.active.strategies import (
    ConnectivityQuery,
    DistanceQuery,
    QueryStrategy,
    RandomQuery,
)

__all__ = [
    "AntiEdges",
    "ConnectivityQuery",
    "DistanceQuery",
    "InstructorLike",
    "QueryContext",
    "QueryRecord",
    "QuerySchedule",
    "QueryStrategy",
    "RandomQuery",
    "StateKey",
    "TeachingSession",
    "connectivity_base",
    "connectivity_scores",
    "ctg_distances",
    "register_strategy",
    "run_session",
    "state_key",
    "strategy",
    "strategy_names",
]
