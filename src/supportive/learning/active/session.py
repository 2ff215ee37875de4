"""An interactive teaching session (§2.2.5–2.2.7): demonstrations interleaved with the learner's queries.

The instructor performs steps one at a time; at scheduled moments the learner asks for an action. Performing a
different action refuses the query and records an anti-edge at the current state. At the end of each
demonstration the learner is updated incrementally (task graph, CTG and CC-HTN).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

from supportive.errors import LearningError
from supportive.learning.active.anti_edges import AntiEdges
from supportive.learning.active.context import QueryContext
from supportive.learning.active.registry import strategy as strategy_named
from supportive.learning.active.schedule import QuerySchedule
from supportive.learning.active.strategies import QueryStrategy
from supportive.learning.learner import HTNLearner
from supportive.seeding import Seed, rng_from
from supportive.tasks.spec import Demonstration

__all__ = ["QueryRecord", "TeachingSession"]


@dataclass(frozen=True)
class QueryRecord:
    """One query: in which demonstration (0-based), after how many steps, what was asked, and the answer.

    ``honoured`` is None while the instructor has not answered yet.
    """

    demonstration: int
    step: int
    action: str
    honoured: bool | None = None


class TeachingSession:
    """Teach a learner by demonstration while it asks for actions.

    Args:
        actions: The action vocabulary (ids the instructor may perform and the learner may ask for).
        strategy: A strategy name (``"random"``, ``"distance"``, ``"connectivity"``) or a strategy object.
        schedule: When to ask.
        seed: Seeds the tie-breaking (and random) choices.
        learner: The learner to update; a new :class:`HTNLearner` when None. It may already be fitted.

    >>> session = TeachingSession(["knife", "carrots", "celery"], schedule=QuerySchedule((0,)), seed=1)
    >>> session.begin(); session.query() is not None
    True
    >>> for step in ["knife", "carrots", "celery"]:
    ...     session.observe(step)
    >>> session.end().actions, session.learner.htn_.complete
    (('knife', 'carrots', 'celery'), True)

    Raises:
        LearningError: for an empty or repeated vocabulary or an unknown strategy name.
    """

    def __init__(
        self,
        actions: Sequence[str],
        strategy: str | QueryStrategy = "distance",
        schedule: QuerySchedule | None = None,
        seed: Seed = None,
        learner: HTNLearner | None = None,
    ) -> None:
        if isinstance(actions, str):
            raise LearningError("the session's actions are a sequence of action ids, not a string")
        vocabulary = tuple(actions)
        if not vocabulary:
            raise LearningError("a teaching session needs at least one action")
        repeated = sorted({a for a in vocabulary if vocabulary.count(a) > 1})
        if repeated:
            raise LearningError(f"the session's actions repeat {', '.join(map(repr, repeated))}")
        if any(not isinstance(a, str) or not a for a in vocabulary):
            raise LearningError("every action id of a teaching session must be a non-empty string")
        self.actions = vocabulary
        self.strategy = strategy_named(strategy) if isinstance(strategy, str) else strategy
        self.schedule = schedule if schedule is not None else QuerySchedule()
        self.rng = rng_from(seed)
        self.learner = learner if learner is not None else HTNLearner(mode="strict")
        self.anti_edges = AntiEdges()
        self.demonstrations: list[Demonstration] = []
        self._queries: list[QueryRecord] = []
        self._known = frozenset(vocabulary)
        self._done: list[str] | None = None
        self._pending: int | None = None  # index into _queries
        self._asked_at: set[int] = set()

    # ------------------------------------------------------------------ reading
    @property
    def queries(self) -> tuple[QueryRecord, ...]:
        """Every query made so far, in order."""
        return tuple(self._queries)

    @property
    def done(self) -> tuple[str, ...]:
        """Actions performed so far in the current demonstration."""
        return tuple(self._done or ())

    @property
    def pending(self) -> str | None:
        """The query waiting for the instructor's next step, if any."""
        return None if self._pending is None else self._queries[self._pending].action

    def context(self) -> QueryContext:
        """The query context at this moment of the current demonstration."""
        learner = self.learner
        fitted = hasattr(learner, "task_graph_")
        return QueryContext(
            task_graph=learner.task_graph_ if fitted else None,
            ctg=learner.ctg_ if fitted else None,
            done=self.done,
            actions=self.actions,
            anti_edges=self.anti_edges,
            rng=self.rng,
        )

    # ------------------------------------------------------------------ teaching
    def begin(self) -> None:
        """Start a demonstration.

        Raises:
            LearningError: when a demonstration is already in progress.
        """
        if self._done is not None:
            raise LearningError("a demonstration is already in progress: end() it before begin()")
        self._done = []
        self._pending = None
        self._asked_at = set()

    def query(self) -> str | None:
        """The action to ask for now, or None when the schedule says not to ask or nothing may be asked.

        Asking twice before the next step returns the same pending query and counts once.

        Raises:
            LearningError: when no demonstration is in progress.
        """
        done = self._require_demonstration("query()")
        if self._pending is not None:
            return self._queries[self._pending].action
        step = len(done)
        if step in self._asked_at or not self.schedule.should_query(
            demonstration=len(self.demonstrations), step=step, asked=len(self._asked_at)
        ):
            return None
        choice = self.strategy.choose(self.context())
        if choice is None:
            return None
        self._asked_at.add(step)
        self._pending = len(self._queries)
        self._queries.append(QueryRecord(len(self.demonstrations), step, choice))
        return choice

    def observe(self, action: str) -> None:
        """Record the instructor's next step, answering a pending query.

        Raises:
            LearningError: when no demonstration is in progress or ``action`` is not in the vocabulary.
        """
        done = self._require_demonstration("observe()")
        if not isinstance(action, str) or action not in self._known:
            raise LearningError(
                f"step {len(done) + 1} of demonstration {len(self.demonstrations) + 1}: unknown action "
                f"{action!r}; expected one of {', '.join(self.actions)}"
            )
        self._answer(action)
        done.append(action)

    def end(self) -> Demonstration:
        """Finish the demonstration, update the learner (``partial_fit``) and return the demonstration.

        A query still pending counts as refused: the instructor finished instead.

        Raises:
            LearningError: when no demonstration is in progress or it has no steps.
        """
        done = self._require_demonstration("end()")
        if not done:
            raise LearningError(
                f"demonstration {len(self.demonstrations) + 1} has no steps: observe() at least one action"
            )
        self._answer(None)
        demonstration = Demonstration.of(done, id=f"d{len(self.demonstrations) + 1}")
        self.learner.partial_fit(demonstration)
        self.demonstrations.append(demonstration)
        self._done = None
        return demonstration

    def _answer(self, action: str | None) -> None:
        if self._pending is None:
            return
        record = self._queries[self._pending]
        honoured = record.action == action
        self._queries[self._pending] = replace(record, honoured=honoured)
        if not honoured:
            self.anti_edges.add(self.done, record.action)
        self._pending = None

    def _require_demonstration(self, call: str) -> list[str]:
        if self._done is None:
            raise LearningError(f"{call} needs a demonstration in progress: call begin() first")
        return self._done
