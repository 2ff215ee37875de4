"""What every online goal filter is: the :class:`Filter` protocol, the :class:`Belief` a filter gives, and the
one way to list a belief's most probable entries (:func:`top`).

The verbs mean one thing everywhere in :mod:`supportive.inference`: ``update(events)`` takes one *moment's
contact events* (the set of touching pairs); ``observe(action)`` takes one *completed action* (an action id a
task board or a dataset reports; only filters that know what is done take these, see :class:`ActionFilter`).
Both return the belief after the evidence, which ``last`` keeps; ``reset()`` forgets all of it.

The filters: :class:`~supportive.inference.hmm.GoalFilter` (the flat and the hierarchical HMM, contact events)
and :class:`~supportive.inference.tracker.ProgressFilter` (the progress-aware tracker, both kinds).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from functools import cached_property
from typing import Protocol, runtime_checkable

import numpy as np

from supportive.inference.transitions import TaskLayout
from supportive.tasks.htn import ActionNode

__all__ = ["ActionFilter", "Belief", "Filter", "Labels", "top"]


class Belief:
    """What a filter believes after some evidence.

    Attributes:
        step: How many pieces of evidence have been taken in.
        subgoals: Probability of each subgoal (in :attr:`Filter.subgoal_labels` order) being the current one.
        log_likelihood: log P(all evidence so far).
    """

    def __init__(
        self, step: int, subgoals: np.ndarray, arriving: np.ndarray, layout: TaskLayout, ll: float
    ) -> None:
        self.step = step
        self.subgoals = subgoals
        self.log_likelihood = ll
        self._arriving = arriving
        self._layout = layout

    @cached_property
    def subtasks(self) -> np.ndarray:
        """Probability of each internal node of the HTN (in :attr:`Filter.subtask_labels` order) being
        under way: the mass of its leaves."""
        return np.asarray(self._layout.membership @ self.subgoals)

    @cached_property
    def enclosing(self) -> np.ndarray:
        """Probability of each internal node being the *immediate* parent of the current subgoal (entry 0: the
        subgoal sits directly at the top of a partial hierarchy; entry j + 1: node j). Unlike
        :attr:`subtasks`, these add up to one."""
        parents = self._layout.parent_of_leaf + 1
        return np.bincount(parents, weights=self.subgoals, minlength=len(self._layout.nodes) + 1)

    @cached_property
    def next_subgoals(self) -> np.ndarray:
        """Probability of each subgoal being the next one started."""
        total = self._arriving.sum()
        return self._arriving / total if total > 0 else self._arriving


def top(values: np.ndarray, labels: Sequence[str], k: int = 3) -> list[tuple[str, float]]:
    """The ``k`` most probable entries of a belief vector, with their labels (ties in label order).

    >>> top(np.array([0.2, 0.5, 0.3]), ("a", "b", "c"), 2)
    [('b', 0.5), ('c', 0.3)]
    """
    order = np.argsort(-values, kind="stable")[:k]
    return [(labels[i], float(values[i])) for i in order]


class Labels:
    """The names a filter gives the entries of its beliefs, from the task's layout, and :meth:`top` over
    them (shared by every filter of this package).

    Attributes:
        subgoal_labels: One per subgoal (``action`` or ``action#k``).
        subtask_labels: One per internal node of the hierarchy (its name, else its kind).
        enclosing_labels: ``"(top level)"``, then the subtask labels (the entries of :attr:`Belief.enclosing`).
    """

    def __init__(self, layout: TaskLayout) -> None:
        self.layout = layout
        self.subgoal_labels = tuple(ActionNode(a, k).label for a, k in layout.leaves)
        self.subtask_labels = tuple(node.name or node.kind for node in layout.nodes)
        self.enclosing_labels = ("(top level)", *self.subtask_labels)

    def top(self, values: np.ndarray, labels: Sequence[str], k: int = 3) -> list[tuple[str, float]]:
        """The ``k`` most probable entries of a belief vector, with their labels (:func:`top`)."""
        return top(values, labels, k)


@runtime_checkable
class Filter(Protocol):
    """An online goal filter fed with contact events (see the module docstring for the verbs)."""

    subgoal_labels: tuple[str, ...]
    subtask_labels: tuple[str, ...]
    enclosing_labels: tuple[str, ...]
    step: int
    log_likelihood: float

    @property
    def last(self) -> Belief:
        """The belief after the last evidence (before any: the task not started)."""

    def reset(self) -> None:
        """Forget all evidence."""

    def update(self, events: Iterable[str]) -> Belief:
        """Take one moment's contact events into account; the belief after it."""

    def summary(self, belief: Belief, k: int = 3) -> dict[str, object]:
        """``belief`` as plain data (the ``k`` most probable entries of each part)."""

    def top(self, values: np.ndarray, labels: Sequence[str], k: int = 3) -> list[tuple[str, float]]:
        """The ``k`` most probable entries of a belief vector, with their labels."""


@runtime_checkable
class ActionFilter(Filter, Protocol):
    """A filter that also takes completed actions (it knows what is done)."""

    def observe(self, action: str) -> Belief:
        """Take one completed action into account; the belief after it."""
