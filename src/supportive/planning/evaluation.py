"""Scoring hypothetical environments, in this process, in worker processes, or on a Dask cluster.

A candidate ξ scores Σ_π w_π · duration(T, π, ξ, s_c, γ) (§3.2.7). Candidates are independent, which is why
the thesis notes that the decoupled design parallelises well: they are split into contiguous chunks, scored
where the backend runs them, and put back in order, so the scores — and the choice — never depend on the
backend or the number of workers.
"""

from __future__ import annotations

import itertools
import signal
from abc import ABC, abstractmethod
from collections.abc import Hashable, Iterable, Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from typing import Any, Generic, Protocol, TypeVar

import numpy as np

from supportive.errors import MissingExtraError, PlanningError
from supportive.planning.duration import Decay, estimate_duration
from supportive.planning.hypothetical import Hypothetical
from supportive.planning.world import Operator, SupportWorld

__all__ = ["DaskScorer", "InProcessScorer", "ProcessScorer", "Scorer", "ScoringContext", "open_scorer"]

StateT = TypeVar("StateT", bound=Hashable)
OperatorT = TypeVar("OperatorT", bound=Operator)
MoveT = TypeVar("MoveT", bound=Hashable)

_CHUNKS_PER_WORKER = 4


@dataclass(frozen=True)
class ScoringContext(Generic[StateT, OperatorT, MoveT]):
    """What scoring a candidate needs besides the candidate, the plan weights and the lead's busy time:
    fixed for one fitted planner (so worker processes receive it once)."""

    world: SupportWorld[StateT, OperatorT, MoveT]
    plans: tuple[tuple[OperatorT, ...], ...]
    penalty: float
    decay: Decay
    lead: str

    def durations(
        self, support: Hypothetical[StateT, OperatorT, MoveT], lead_busy: float = 0.0
    ) -> np.ndarray:
        """Algorithm 5 for every known plan under ``support`` (weight-0 plans included)."""
        return np.array([self._estimate(plan, support, lead_busy) for plan in self.plans])

    def score(
        self,
        support: Hypothetical[StateT, OperatorT, MoveT],
        weights: Sequence[float],
        lead_busy: float = 0.0,
    ) -> float:
        """Σ_π w_π · duration(π, ξ): plans of weight 0 are not estimated."""
        total = 0.0
        for weight, plan in zip(weights, self.plans, strict=True):
            if weight != 0.0:
                total += weight * self._estimate(plan, support, lead_busy)
        return total

    def scores(
        self,
        candidates: Sequence[Hypothetical[StateT, OperatorT, MoveT]],
        weights: Sequence[float],
        lead_busy: float = 0.0,
    ) -> list[float]:
        """The score of every candidate, in order."""
        return [self.score(candidate, weights, lead_busy) for candidate in candidates]

    def _estimate(
        self, plan: tuple[OperatorT, ...], support: Hypothetical[StateT, OperatorT, MoveT], lead_busy: float
    ) -> float:
        return estimate_duration(self.world, plan, support, self.penalty, self.decay, self.lead, lead_busy)


class Scorer(Protocol):
    """Scores candidates for one context; ``close`` frees what it holds (processes, a cluster)."""

    description: str

    def scores(
        self,
        candidates: Sequence[Hypothetical[Any, Any, Any]],
        weights: Sequence[float],
        lead_busy: float = 0.0,
    ) -> list[float]:
        """The score of every candidate under plan weights ``weights``, in order."""
        ...

    def close(self) -> None:
        """Release workers."""
        ...


@dataclass
class InProcessScorer:
    """Scores candidates one after another in this process."""

    context: ScoringContext[Any, Any, Any]
    description: str = "in process"

    def scores(
        self,
        candidates: Sequence[Hypothetical[Any, Any, Any]],
        weights: Sequence[float],
        lead_busy: float = 0.0,
    ) -> list[float]:
        """The score of every candidate, in order."""
        return self.context.scores(candidates, weights, lead_busy)

    def close(self) -> None:
        """Nothing to release."""


_WORKER_CONTEXT: ScoringContext[Any, Any, Any] | None = None


def _install(context: ScoringContext[Any, Any, Any]) -> None:
    """A worker process's start: keep the context, and ignore Ctrl-C (a terminal sends it to the whole process
    group: the process that started the pool stops it, and a worker would only print a traceback)."""
    global _WORKER_CONTEXT
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _WORKER_CONTEXT = context


def _score_in_worker(
    candidates: Sequence[Hypothetical[Any, Any, Any]], weights: Sequence[float], lead_busy: float
) -> list[float]:
    if _WORKER_CONTEXT is None:  # pragma: no cover - the pool's initializer always ran
        raise PlanningError("worker process has no scoring context")
    return _WORKER_CONTEXT.scores(candidates, weights, lead_busy)


def _score_on_dask(
    context: ScoringContext[Any, Any, Any],
    candidates: Sequence[Any],
    weights: Sequence[float],
    lead_busy: float,
) -> list[float]:
    return context.scores(candidates, weights, lead_busy)


def _chunks(items: Sequence[Any], parts: int) -> list[Sequence[Any]]:
    """``items`` cut into at most ``parts`` contiguous, nearly equal chunks."""
    bounds = np.linspace(0, len(items), min(parts, len(items)) + 1).round().astype(int)
    return [items[a:b] for a, b in itertools.pairwise(bounds) if b > a]


class _ChunkedScorer(ABC):
    """Cuts the candidates into contiguous chunks, has them scored elsewhere, and puts the scores back in
    order; subclasses say where (:meth:`_score_chunks`)."""

    _parts: int

    def scores(
        self,
        candidates: Sequence[Hypothetical[Any, Any, Any]],
        weights: Sequence[float],
        lead_busy: float = 0.0,
    ) -> list[float]:
        """The score of every candidate, in order."""
        if not candidates:
            return []
        chunks = self._score_chunks(_chunks(list(candidates), self._parts), tuple(weights), lead_busy)
        return [score for chunk in chunks for score in chunk]

    @abstractmethod
    def _score_chunks(
        self, parts: list[Sequence[Any]], weights: tuple[float, ...], lead_busy: float
    ) -> Iterable[list[float]]:
        """The scores of every chunk, in order."""


class ProcessScorer(_ChunkedScorer):
    """Scores candidates in ``workers`` local processes that received the context once, at start."""

    def __init__(self, context: ScoringContext[Any, Any, Any], workers: int) -> None:
        self._parts = workers * _CHUNKS_PER_WORKER
        self.description = f"{workers} local processes"
        self._pool = ProcessPoolExecutor(max_workers=workers, initializer=_install, initargs=(context,))

    def _score_chunks(
        self, parts: list[Sequence[Any]], weights: tuple[float, ...], lead_busy: float
    ) -> Iterable[list[float]]:
        return self._pool.map(_score_in_worker, parts, [weights] * len(parts), [lead_busy] * len(parts))

    def close(self) -> None:
        """Stop the worker processes."""
        self._pool.shutdown(wait=True, cancel_futures=True)


class DaskScorer(_ChunkedScorer):
    """Scores candidates as tasks on a ``dask.distributed`` client; the context is scattered once."""

    def __init__(self, context: ScoringContext[Any, Any, Any], client: Any) -> None:
        self._client = client
        self._context = client.scatter(context, broadcast=True)
        workers = len(client.scheduler_info().get("workers", {})) or 1
        self._parts = workers * _CHUNKS_PER_WORKER
        self.description = f"dask, {workers} workers"

    def _score_chunks(
        self, parts: list[Sequence[Any]], weights: tuple[float, ...], lead_busy: float
    ) -> Iterable[list[float]]:
        futures = [
            self._client.submit(_score_on_dask, self._context, part, weights, lead_busy, pure=False)
            for part in parts
        ]
        gathered: list[list[float]] = self._client.gather(futures)
        return gathered

    def close(self) -> None:
        """Forget the scattered context (the client is the caller's)."""
        self._client.cancel([self._context])


def open_scorer(context: ScoringContext[Any, Any, Any], workers: int = 1, client: Any = None) -> Scorer:
    """A scorer for ``context``: in process (1 worker), local processes (more), or on a Dask ``client``.

    Raises:
        PlanningError: for fewer than one worker, or both ``workers > 1`` and a client.
        MissingExtraError: for a client when dask.distributed is not installed.
    """
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise PlanningError(f"workers must be an int >= 1, got {workers!r}")
    if client is not None:
        if workers != 1:
            raise PlanningError("give either a number of local workers or a dask client, not both")
        try:
            import dask.distributed  # noqa: F401
        except ImportError:
            raise MissingExtraError("scoring on a dask cluster", "dask.distributed", "distributed") from None
        return DaskScorer(context, client)
    if workers == 1:
        return InProcessScorer(context)
    return ProcessScorer(context, workers)
