"""Query strategies by name: ``strategy("distance")``."""

from __future__ import annotations

from collections.abc import Callable

from supportive.errors import LearningError
from supportive.learning.active.strategies import (
    ConnectivityQuery,
    DistanceQuery,
    QueryStrategy,
    RandomQuery,
)

__all__ = ["register_strategy", "strategy", "strategy_names"]

_REGISTRY: dict[str, Callable[[], QueryStrategy]] = {
    RandomQuery.name: RandomQuery,
    DistanceQuery.name: DistanceQuery,
    ConnectivityQuery.name: ConnectivityQuery,
}


def strategy(name: str) -> QueryStrategy:
    """A new strategy of the given name.

    >>> strategy("connectivity")
    ConnectivityQuery()

    Raises:
        LearningError: when no strategy has that name.
    """
    factory = _REGISTRY.get(name)
    if factory is None:
        raise LearningError(f"unknown query strategy {name!r}: expected one of {', '.join(strategy_names())}")
    return factory()


def strategy_names() -> tuple[str, ...]:
    """The registered names, sorted."""
    return tuple(sorted(_REGISTRY))


def register_strategy(name: str, factory: Callable[[], QueryStrategy]) -> None:
    """Register (or replace) a strategy under ``name``.

    Raises:
        LearningError: when the name is empty.
    """
    if not name:
        raise LearningError("a query strategy needs a non-empty name")
    _REGISTRY[name] = factory
