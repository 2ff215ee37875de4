"""The three query strategies of §2.2.6: random, distance-based and connectivity-based.

Each chooses one action to ask the instructor for, among :meth:`QueryContext.candidates`, or None when no
action is allowed. Ties are broken with the context's generator among the best candidates in vocabulary order.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from typing import ClassVar

from supportive.learning.active.context import QueryContext
from supportive.learning.active.scores import connectivity_scores, ctg_distances

__all__ = ["ConnectivityQuery", "DistanceQuery", "QueryStrategy", "RandomQuery"]


class QueryStrategy(ABC):
    """Chooses the action a learner asks for next."""

    name: ClassVar[str]

    @abstractmethod
    def choose(self, context: QueryContext) -> str | None:
        """The action to ask for, or None when no action may be asked for."""

    def __repr__(self) -> str:
        return f"{type(self).__name__}()"


class RandomQuery(QueryStrategy):
    """Uniformly at random among the allowed actions (§2.2.6.1, the baseline).

    >>> import numpy as np
    >>> ctx = QueryContext(None, None, ("a",), ("a", "b", "c"), rng=np.random.default_rng(1))
    >>> RandomQuery().choose(ctx) in {"b", "c"}
    True
    """

    name = "random"

    def choose(self, context: QueryContext) -> str | None:
        return context.pick(list(context.candidates()))


class DistanceQuery(QueryStrategy):
    """The allowed action whose CTG vertex is closest to the last executed subgoal (§2.2.6.2).

    Distance is the shortest path in the CTG from the current vertex (the origin at the start of a
    demonstration) to the candidate's next-occurrence vertex; actions the CTG does not reach come last.

    >>> from supportive.learning import HTNLearner
    >>> learner = HTNLearner().fit([["a", "b", "c", "d"]])
    >>> ctx = QueryContext(learner.task_graph_, learner.ctg_, (), ("a", "b", "c", "d"))
    >>> DistanceQuery().choose(ctx)  # a is known from the start; b is two edges from the origin
    'b'
    """

    name = "distance"

    def choose(self, context: QueryContext) -> str | None:
        candidates = context.candidates()
        if context.ctg is None:
            return context.pick(list(candidates))
        distance = ctg_distances(context.ctg, context.current_vertex)

        def cost(action: str) -> float:
            vertex = context.next_subgoal(action)
            return math.inf if vertex is None else distance.get(vertex, math.inf)

        costs = {action: cost(action) for action in candidates}
        best = min(costs.values(), default=math.inf)
        return context.pick([action for action in candidates if costs[action] == best])


class ConnectivityQuery(QueryStrategy):
    """The allowed action whose CTG vertex is best connected with the fewest prerequisites (§2.2.6.3).

    See :func:`~supportive.learning.active.scores.connectivity_scores`; actions without a vertex score 0.

    >>> from supportive.learning import HTNLearner
    >>> learner = HTNLearner().fit([["a", "b", "c", "d"]])
    >>> ctx = QueryContext(learner.task_graph_, learner.ctg_, (), ("a", "b", "c", "d"))
    >>> ConnectivityQuery().choose(ctx)  # scores b 5, c 4, d 3
    'b'
    """

    name = "connectivity"

    def choose(self, context: QueryContext) -> str | None:
        candidates = context.candidates()
        if context.ctg is None:
            return context.pick(list(candidates))
        scores = connectivity_scores(context.ctg)

        def score(action: str) -> float:
            vertex = context.next_subgoal(action)
            return 0.0 if vertex is None else scores.get(vertex, 0.0)

        values = {action: score(action) for action in candidates}
        best = max(values.values(), default=0.0)
        return context.pick([action for action in candidates if values[action] == best])
