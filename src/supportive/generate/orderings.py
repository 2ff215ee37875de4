"""Valid orderings of a structure, enumerated when few and sampled uniformly otherwise, as demonstrations."""

from __future__ import annotations

from collections.abc import Iterable

from supportive.errors import GenerationError, TooManyOrderingsError
from supportive.seeding import Seed, rng_from
from supportive.tasks.htn import Leaf, Node, count_orderings, iter_orderings, sample_ordering
from supportive.tasks.spec import Demonstration

__all__ = [
    "all_demonstrations",
    "as_demonstrations",
    "sample_demonstrations",
    "sample_orderings",
    "valid_orderings",
]

Ordering = tuple[Leaf, ...]


def sample_orderings(
    structure: Node, count: int, seed: Seed = None, *, distinct: bool = False
) -> list[Ordering]:
    """``count`` orderings drawn uniformly from those ``structure`` admits.

    Args:
        structure: The hierarchy.
        count: How many to draw (0 or more).
        seed: Seed or generator (see :mod:`supportive.seeding`).
        distinct: Draw without replacement (uniformly among sets of distinct orderings). When the structure
            admits ``count`` orderings or fewer, all of them are returned, in random order (so fewer than
            ``count`` may come back).

    Raises:
        GenerationError: when ``count`` is negative.
    """
    if count < 0:
        raise GenerationError(f"cannot draw {count} orderings")
    rng = rng_from(seed)
    if not distinct:
        return [sample_ordering(structure, rng) for _ in range(count)]
    if count_orderings(structure) <= count:
        every = list(iter_orderings(structure))
        return [every[i] for i in rng.permutation(len(every))]
    seen: dict[Ordering, None] = {}
    while len(seen) < count:
        seen.setdefault(sample_ordering(structure, rng), None)
    return list(seen)


def valid_orderings(
    structure: Node,
    *,
    limit: int = 1000,
    sample: int | None = None,
    seed: Seed = None,
    distinct: bool = False,
) -> list[Ordering]:
    """Every ordering when there are at most ``limit``; otherwise ``sample`` uniform draws.

    Args:
        structure: The hierarchy.
        limit: Enumerate when ``count_orderings(structure) <= limit`` (in :func:`iter_orderings` order).
        sample: How many to draw when there are more than ``limit``; ``None`` raises instead.
        seed: Seed or generator for the draws.
        distinct: Draw without replacement (see :func:`sample_orderings`).

    Raises:
        TooManyOrderingsError: when there are more than ``limit`` orderings and ``sample`` is ``None``.

    >>> from supportive.tasks.htn import ActionNode, CliqueNode
    >>> len(valid_orderings(CliqueNode((ActionNode("a"), ActionNode("b"), ActionNode("c")))))
    6
    """
    total = count_orderings(structure)
    if total <= limit:
        return list(iter_orderings(structure))
    if sample is None:
        raise TooManyOrderingsError(total, limit)
    return sample_orderings(structure, sample, seed, distinct=distinct)


def as_demonstrations(orderings: Iterable[Ordering]) -> tuple[Demonstration, ...]:
    """Leaf sequences as demonstrations with ids ``d1``, ``d2``, …"""
    return tuple(
        Demonstration.of([action for action, _ in ordering], id=f"d{i}")
        for i, ordering in enumerate(orderings, 1)
    )


def all_demonstrations(structure: Node, limit: int = 1000) -> tuple[Demonstration, ...]:
    """One demonstration per ordering ``structure`` admits.

    Raises:
        TooManyOrderingsError: when there are more than ``limit`` orderings.
    """
    total = count_orderings(structure)
    if total > limit:
        raise TooManyOrderingsError(total, limit)
    return as_demonstrations(iter_orderings(structure))


def sample_demonstrations(
    structure: Node, count: int, seed: Seed = None, *, distinct: bool = False
) -> tuple[Demonstration, ...]:
    """``count`` demonstrations drawn uniformly (see :func:`sample_orderings`)."""
    return as_demonstrations(sample_orderings(structure, count, seed, distinct=distinct))
