"""Macro actions from a learned HTN (§2.1.7.4): its internal nodes as reusable action sequences.

A planner or explorer adds these to its action dictionary to take larger steps: one macro performs a whole
subtask. A chain's macro has one sequence; a clique's may be performed in any of its orders, and ``actions`` is
one of them (the learned order of its children).
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Iterator
from dataclasses import dataclass
from itertools import islice

from supportive.seeding import Seed
from supportive.tasks.htn import (
    HTN,
    Node,
    canonical,
    count_orderings,
    internal_nodes,
    iter_orderings,
    sample_ordering,
)
from supportive.tasks.naming import named

__all__ = ["MacroAction", "macro_actions", "macro_library"]


@dataclass(frozen=True)
class MacroAction:
    """A subtask usable as one action.

    Attributes:
        name: The subtask's name.
        node: The HTN node it stands for.
        actions: One valid sequence of action ids that performs it.
    """

    name: str
    node: Node
    actions: tuple[str, ...]

    @property
    def size(self) -> int:
        """Number of primitive actions it performs."""
        return len(self.actions)

    def count_sequences(self) -> int:
        """How many action sequences perform it (exact)."""
        return count_orderings(self.node)

    def sequences(self, limit: int | None = None) -> Iterator[tuple[str, ...]]:
        """Action sequences that perform it, at most ``limit`` of them."""
        for leaves in islice(iter_orderings(self.node), limit):
            yield tuple(action for action, _ in leaves)

    def sample(self, seed: Seed = None) -> tuple[str, ...]:
        """One sequence that performs it, drawn uniformly."""
        return tuple(action for action, _ in sample_ordering(self.node, seed))

    def applicable(self, available: Collection[str]) -> bool:
        """True when every action it performs is in ``available`` (for transfer to another task)."""
        return all(action in available for action in self.actions)


def macro_actions(htn: HTN, *, min_size: int = 2) -> list[MacroAction]:
    """Every chain and clique of ``htn`` performing at least ``min_size`` actions, outermost first.

    >>> from supportive.learning import HTNLearner
    >>> htn = HTNLearner(mode="strict").fit([["knife", "carrots", "celery"], ["knife", "celery", "carrots"]]).htn_
    >>> [(m.name, m.actions) for m in macro_actions(htn)]
    [('knife → {carrots, celery}', ('knife', 'carrots', 'celery')), ('{carrots, celery}', ('carrots', 'celery'))]
    """
    return macro_library([htn], min_size=min_size)


def macro_library(htns: Iterable[HTN], *, min_size: int = 2) -> list[MacroAction]:
    """The macro actions of several HTNs (say, every other task a robot knows), each subtask once."""
    seen: set[tuple[object, ...]] = set()
    macros = []
    for htn in htns:
        for root in htn.roots:
            for node in internal_nodes(named(root)):
                key = canonical(node)
                if len(node.leaves) < min_size or key in seen:
                    continue
                seen.add(key)
                name = node.name or node.kind
                macros.append(MacroAction(name, node, tuple(action for action, _ in node.leaves)))
    return macros
