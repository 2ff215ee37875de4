"""Anti-edges (§2.2.5.1): (state, action) pairs the instructor refused, assumed not to be transitions.

A state is the multiset of actions done so far in a demonstration (the commutativity assumption of §2.1.2), so
an anti-edge recorded after ``a, b`` also holds after ``b, a``.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Iterator, Sequence
from typing import TypeAlias

from supportive.errors import LearningError

__all__ = ["AntiEdges", "StateKey", "state_key"]

StateKey: TypeAlias = frozenset[tuple[str, int]]
"""A state as a done-multiset: ``{(action, how many times it was done)}``."""

StateLike: TypeAlias = Sequence[str] | StateKey


def state_key(done: StateLike) -> StateKey:
    """The done-multiset of a prefix of actions (a :data:`StateKey` is returned as is).

    >>> state_key(["a", "b", "a"]) == state_key(["b", "a", "a"])
    True

    Raises:
        LearningError: when ``done`` is a string rather than a sequence of action ids.
    """
    if isinstance(done, frozenset):
        return done
    if isinstance(done, str):
        raise LearningError(f"a state is a sequence of action ids, not the string {done!r}")
    return frozenset(Counter(done).items())


class AntiEdges:
    """The anti-edges learned so far, keyed by (done-multiset, action).

    Args:
        edges: Initial anti-edges as ``(done, action)`` pairs.

    >>> anti = AntiEdges()
    >>> anti.add(["red"], "blue")
    True
    >>> anti.contains(["red"], "blue"), anti.contains([], "blue"), len(anti)
    (True, False, 1)
    """

    def __init__(self, edges: Iterable[tuple[StateLike, str]] = ()) -> None:
        self._blocked: dict[StateKey, set[str]] = {}
        self._count = 0
        for done, action in edges:
            self.add(done, action)

    def add(self, done: StateLike, action: str) -> bool:
        """Record that ``action`` is assumed impossible after ``done``.

        Returns:
            True when the anti-edge is new.
        """
        blocked = self._blocked.setdefault(state_key(done), set())
        if action in blocked:
            return False
        blocked.add(action)
        self._count += 1
        return True

    def contains(self, done: StateLike, action: str) -> bool:
        """True when ``(done, action)`` is an anti-edge."""
        return action in self._blocked.get(state_key(done), ())

    def blocked(self, done: StateLike) -> frozenset[str]:
        """The actions ruled out after ``done``."""
        return frozenset(self._blocked.get(state_key(done), ()))

    def __contains__(self, item: object) -> bool:
        if not isinstance(item, tuple) or len(item) != 2:
            return False
        done, action = item
        return isinstance(action, str) and self.contains(done, action)

    def __iter__(self) -> Iterator[tuple[StateKey, str]]:
        for key, actions in self._blocked.items():
            for action in sorted(actions):
                yield key, action

    def __len__(self) -> int:
        return self._count

    def __repr__(self) -> str:
        return f"AntiEdges({len(self)} anti-edges)"
