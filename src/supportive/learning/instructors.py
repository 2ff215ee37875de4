"""Simulated instructors and pooled instruction (§2.2.10.1).

The thesis models its pilot participants three ways, and :class:`SimulatedInstructor` copies them:

* **A fixed preferred order.** Each instructor has a preferred demonstration path: a canonical base path with
  small random perturbations, drawn once (from the seed) and kept for every demonstration and every query
  strategy ("participants were likely to remain true to their initial demonstration sequence").
* **Queries within reach are heeded.** When the robot asks for an action that can be performed within
  ``horizon`` (3) steps by some valid continuation, the instructor changes plan to perform it at the earliest
  allowable time, then goes back to her preference. Queries further away are ignored.
* **Pooling.** Instructors teach separate learners; the pooled result is the union of the learned
  environment-space graphs (:func:`pooled_task_graph`, :func:`pooled_learner`).

The true task is a nested chain/clique structure or a :class:`PartialOrder` ("must come before" pairs, as
in a published task graph: a leaf may come next when all its predecessors are done).

>>> from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode
>>> task = ChainNode((ActionNode("knife"), CliqueNode((ActionNode("carrots"), ActionNode("celery")))))
>>> person = SimulatedInstructor(task, perturbation=0.0)
>>> demonstrate(person)
['knife', 'carrots', 'celery']
>>> person.begin_demonstration()
>>> person.next_action(("knife",), "celery")
'celery'
"""

from __future__ import annotations

import copy
from collections import Counter
from collections.abc import Iterable, Sequence
from typing import Any

from supportive.errors import LearningError
from supportive.learning.learner import HTNLearner
from supportive.seeding import Seed, rng_from
from supportive.tasks.htn import (
    ActionNode,
    ChainNode,
    CliqueNode,
    Leaf,
    Node,
    admits,
    allowed_next,
    to_leaves,
)
from supportive.tasks.task_graph import TaskGraph

__all__ = ["PartialOrder", "SimulatedInstructor", "demonstrate", "pooled_learner", "pooled_task_graph"]

_PREFIXES_KEPT = 4096
"""How many checked prefixes an instructor keeps (a bound on memory; the answers never depend on it)."""


class PartialOrder:
    """A task given as a partial order over its leaves: a leaf may come next when all its predecessors are done.

    Args:
        leaves: The task's leaves ``(action id, occurrence)``; a leaf named only in ``before`` is added.
        before: Pairs ``(a, b)``: ``a`` must be performed before ``b``. Their transitive closure is used.

    Attributes:
        leaves: Every leaf, in a valid order (the given order, each leaf moved after its predecessors).
        predecessors: For each leaf, every leaf that must come before it (transitively).

    Raises:
        LearningError: when the pairs form a cycle or a leaf repeats.

    >>> order = PartialOrder([("knife", 1), ("carrots", 1), ("celery", 1)],
    ...                      [(("knife", 1), ("carrots", 1)), (("knife", 1), ("celery", 1))])
    >>> sorted(a for a, _ in order.allowed_next([("knife", 1)]))
    ['carrots', 'celery']
    >>> order.linearize(["celery", "knife", "carrots"])
    ('knife', 'celery', 'carrots')
    """

    def __init__(self, leaves: Iterable[Leaf], before: Iterable[tuple[Leaf, Leaf]]) -> None:
        given = list(leaves)
        if len(set(given)) != len(given):
            raise LearningError("a partial order's leaves must not repeat")
        pairs = [(a, b) for a, b in before]
        for a, b in pairs:
            for leaf in (a, b):
                if leaf not in given:
                    given.append(leaf)
        direct: dict[Leaf, set[Leaf]] = {leaf: set() for leaf in given}
        for a, b in pairs:
            direct[b].add(a)
        closed: dict[Leaf, frozenset[Leaf]] = {}

        def close(leaf: Leaf, path: frozenset[Leaf]) -> frozenset[Leaf]:
            if leaf in path:
                raise LearningError(
                    f"the order is cyclic: {leaf[0]!r} (performance {leaf[1]}) precedes itself"
                )
            if leaf not in closed:
                out: set[Leaf] = set()
                for parent in direct[leaf]:
                    out.add(parent)
                    out |= close(parent, path | {leaf})
                closed[leaf] = frozenset(out)
            return closed[leaf]

        for leaf in given:
            close(leaf, frozenset())
        self.predecessors: dict[Leaf, frozenset[Leaf]] = closed
        self.leaves: tuple[Leaf, ...] = self._linear(given)

    def allowed_next(self, done: Iterable[Leaf]) -> frozenset[Leaf]:
        """The leaves that may be performed next after ``done``: nothing when every leaf is done.

        Raises:
            LearningError: when ``done`` holds an unknown leaf or one whose predecessors are not all done.
        """
        done_set = frozenset(done)
        for leaf in done_set:
            if leaf not in self.predecessors:
                raise LearningError(f"{leaf[0]!r} (performance {leaf[1]}) is not in the task")
            if not self.predecessors[leaf] <= done_set:
                raise LearningError(f"{leaf[0]!r} (performance {leaf[1]}) is done before its predecessors")
        return frozenset(
            leaf for leaf in self.leaves if leaf not in done_set and self.predecessors[leaf] <= done_set
        )

    def required(self, target: Leaf, done: frozenset[Leaf]) -> frozenset[Leaf]:
        """The leaves still to be done before ``target`` can be performed (its undone predecessors)."""
        return self.predecessors[target] - done

    def admits(self, path: Sequence[Leaf]) -> bool:
        """True when ``path`` performs every leaf once, each after all its predecessors."""
        if len(path) != len(self.leaves) or set(path) != set(self.leaves):
            return False
        seen: set[Leaf] = set()
        for leaf in path:
            if not self.predecessors[leaf] <= seen:
                return False
            seen.add(leaf)
        return True

    def linearize(self, preference: Sequence[str]) -> tuple[str, ...]:
        """The valid ordering closest to ``preference`` (action ids, e.g. a real recording that may break the
        order): at each step, among the leaves allowed, the one earliest in the preference (leaves it lacks
        come last, in :attr:`leaves` order)."""
        return tuple(a for a, _ in self._linear(to_leaves(preference)))

    def _linear(self, preference: Sequence[Leaf]) -> tuple[Leaf, ...]:
        rank = {leaf: i for i, leaf in enumerate(preference)}
        known = list(self.predecessors)
        order = {leaf: (rank.get(leaf, len(rank)), i) for i, leaf in enumerate(known)}
        done: list[Leaf] = []
        done_set: set[Leaf] = set()
        while len(done) < len(known):
            leaf = min(
                (x for x in known if x not in done_set and self.predecessors[x] <= done_set),
                key=order.__getitem__,
            )
            done.append(leaf)
            done_set.add(leaf)
        return tuple(done)


KnownTask = Node | PartialOrder
"""What an instructor knows: a nested chain/clique structure or a partial order over leaves."""


def _allowed_next(task: KnownTask, done: Iterable[Leaf]) -> frozenset[Leaf]:
    return task.allowed_next(done) if isinstance(task, PartialOrder) else allowed_next(task, done)


def _admits(task: KnownTask, path: Sequence[Leaf]) -> bool:
    return task.admits(path) if isinstance(task, PartialOrder) else admits(task, path)


class SimulatedInstructor:
    """A virtual person who knows the true task and demonstrates it, answering the robot's queries.

    **Preferred path.** Starting from ``base_path`` (default: the structure's leaves in order), one pass runs
    over adjacent positions left to right; at each position the pair is swapped with probability
    ``perturbation`` when the swapped path is still a valid ordering of the structure, and a swapped pair is
    then stepped over, so a leaf moves at most one place. The result is always a valid ordering, drawn once
    from ``seed`` and kept for the instructor's lifetime.

    **Next action.** Without a pending plan the instructor performs, among the leaves allowed next, the one
    earliest in her preferred path (so, untroubled, she performs exactly her preferred path).

    **Queries.** A query for action ``q`` means its next performance (a repeated action's next occurrence).
    It is heeded when that performance can come within ``horizon`` steps, i.e. when the fewest leaves that
    must be done first number at most ``horizon - 1`` (:meth:`steps_to`). A heeded query becomes the plan:
    over the next calls she performs those required leaves (in preference order among those allowed) and
    then ``q``, the shortest valid prefix ending in ``q``, after which she follows her preference again. A
    later heeded query replaces a pending plan (she answers the latest question); an ignored query leaves it
    alone. Queries for an action not in the task, or whose performances are all done, are ignored.

    A repeated action's k-th performance is the k-th one done (:func:`~supportive.tasks.htn.to_leaves`), so
    only an action's next performance is ever chosen; the structure should number performances in an order
    they can be done in (a ``LearningError`` says so when a demonstration gets stuck on that).

    Answers are deterministic: the only randomness is the preferred path, so the same seed gives the same
    path and the same answers.

    Args:
        structure: The true task: a nested chain/clique structure, or a :class:`PartialOrder` (a leaf may come
            next when all its predecessors are done; a query then requires its undone predecessors first).
        base_path: The canonical base path, action ids in order (default: the structure's leaves in order,
            which must then number each repeated action's performances in that order).
        perturbation: Probability of each adjacent swap, in [0, 1]; 0 keeps the base path exactly.
        horizon: Most steps ahead (counting the queried action itself) a query is heeded; 0 ignores all.
        deviation: Per demonstration, the probability of each adjacent swap of the preferred path for that
            demonstration only — the "tendency towards unprompted demonstration deviations" of §2.2.10.1
            (0: every unprompted demonstration is the preferred path).
        seed: Seed or generator (see :mod:`supportive.seeding`).

    Attributes:
        preferred_path: The instructor's preferred demonstration, action ids in order.
        preferred_leaves: The same as (action, occurrence) leaves.

    Raises:
        LearningError: when ``base_path`` is not a valid ordering of ``structure``, ``perturbation`` is not in
            [0, 1] or ``horizon`` is negative.
    """

    def __init__(
        self,
        structure: KnownTask,
        base_path: Sequence[str] | None = None,
        *,
        perturbation: float = 0.2,
        horizon: int = 3,
        deviation: float = 0.0,
        seed: Seed = None,
    ) -> None:
        if not 0.0 <= perturbation <= 1.0 or not 0.0 <= deviation <= 1.0:
            raise LearningError(
                f"perturbation and deviation must be in [0, 1], got {perturbation}, {deviation}"
            )
        if horizon < 0:
            raise LearningError(f"horizon must be >= 0, got {horizon}")
        if isinstance(base_path, str):
            raise LearningError("base_path is a sequence of action ids, not a string")
        base = to_leaves(a for a, _ in structure.leaves) if base_path is None else to_leaves(base_path)
        if not _admits(structure, base):
            raise LearningError(
                f"base_path {[a for a, _ in base]} is not a valid ordering of the task "
                f"(expected an ordering of {sorted({a for a, _ in structure.leaves})})"
            )
        self.structure = structure
        self.perturbation = perturbation
        self.horizon = horizon
        self.deviation = deviation
        self._rng = rng_from(seed)
        self.preferred_leaves: tuple[Leaf, ...] = _perturb(structure, base, perturbation, self._rng)
        self.preferred_path: tuple[str, ...] = tuple(a for a, _ in self.preferred_leaves)
        self._rank = {leaf: i for i, leaf in enumerate(self.preferred_leaves)}
        self._ancestry: dict[Leaf, list[tuple[ChainNode | CliqueNode, int]]] = (
            {} if isinstance(structure, PartialOrder) else _ancestry(structure)
        )
        self._target: Leaf | None = None
        # Prefix -> (its leaves, the leaves allowed next): the task never changes, so copies share it.
        self._prefixes: dict[tuple[str, ...], tuple[tuple[Leaf, ...], frozenset[Leaf]]] = {}

    def __deepcopy__(self, memo: dict[int, Any]) -> SimulatedInstructor:
        """A twin who draws from here on what this instructor would draw: her random generator is copied; the
        task, her paths and what she derived from them (the prefixes she has checked among them), which she
        never changes but by adding what follows from the task, are shared."""
        twin = copy.copy(self)
        twin._rng = copy.deepcopy(self._rng, memo)
        return twin

    def begin_demonstration(self) -> None:
        """Start a new demonstration: forget any plan a query made in the previous one and, with a
        ``deviation``, drift from the preferred path for this demonstration only (unprompted variation)."""
        self._target = None
        if self.deviation > 0:
            today = _perturb(self.structure, self.preferred_leaves, self.deviation, self._rng)
            self._rank = {leaf: i for i, leaf in enumerate(today)}

    def steps_to(self, done: Sequence[str], action: str) -> int | None:
        """In how many steps ``action`` (its next performance) can be performed at the earliest after ``done``.

        1 means it is allowed next; ``k`` means ``k - 1`` other leaves must be done first.

        Args:
            done: Actions done so far in this demonstration (a valid prefix).
            action: The action asked about.

        Returns:
            The number of steps, or None when the action is not in the task or all its performances are done.

        Raises:
            LearningError: when ``done`` is not a valid prefix of the task.
        """
        leaves, _ = self._check(done)
        target = self._next_leaf(leaves, action)
        if target is None:
            return None
        return len(self._required(target, frozenset(leaves))) + 1

    def next_action(self, done: tuple[str, ...], query: str | None = None) -> str | None:
        """The action the instructor performs next.

        Args:
            done: Actions done so far in this demonstration (a valid prefix). An empty ``done`` starts a new
                demonstration, like :meth:`begin_demonstration`.
            query: The robot's pending query (an action id), or None.

        Returns:
            The next action id, or None when the task is complete.

        Raises:
            LearningError: when ``done`` is not a valid prefix of the task.
        """
        leaves, every = self._check(done)
        if not leaves:
            self.begin_demonstration()
        done_set = frozenset(leaves)
        if not every:
            self._target = None
            return None
        # Only an action's next performance can be done next: the k-th "stir" is the k-th stir performed.
        counts = Counter(a for a, _ in leaves)
        allowed = frozenset(leaf for leaf in every if leaf[1] == counts[leaf[0]] + 1)
        if not allowed:
            raise LearningError(
                f"done {list(done)}: the task numbers performances of {sorted({a for a, _ in every})} out of "
                "the order they can be performed in"
            )
        if self._target is not None and self._target in done_set:
            self._target = None
        if query is not None:
            target = self._next_leaf(leaves, query)
            if target is not None and len(self._required(target, done_set)) + 1 <= self.horizon:
                self._target = target
        if self._target is not None:
            required = self._required(self._target, done_set)
            candidates = allowed & required if required else allowed & {self._target}
            if candidates:
                return min(candidates, key=self._rank.__getitem__)[0]
            self._target = None  # unreachable for a valid prefix; fall back to the preference
        return min(allowed, key=self._rank.__getitem__)[0]

    def _check(self, done: Sequence[str]) -> tuple[tuple[Leaf, ...], frozenset[Leaf]]:
        """``done`` as leaves, and the leaves allowed next after them; a clear error when it is not a valid
        prefix of the task."""
        if isinstance(done, str):
            raise LearningError("done is a sequence of action ids, not a string")
        key = tuple(done)
        known = self._prefixes.get(key)
        if known is not None:
            return known
        leaves = to_leaves(key)
        unknown = [leaf for leaf in leaves if leaf not in self._rank]
        if unknown:
            raise LearningError(
                f"done {list(done)}: {unknown[0][0]!r} (performance {unknown[0][1]}) is not in the task"
            )
        try:
            checked = leaves, _allowed_next(self.structure, leaves)
        except ValueError as exc:
            raise LearningError(f"done {list(done)} is not a valid prefix of the task: {exc}") from exc
        if len(self._prefixes) >= _PREFIXES_KEPT:
            self._prefixes.clear()
        self._prefixes[key] = checked
        return checked

    def _next_leaf(self, leaves: Sequence[Leaf], action: str) -> Leaf | None:
        leaf = (action, sum(a == action for a, _ in leaves) + 1)
        return leaf if leaf in self._rank else None

    def _required(self, target: Leaf, done: frozenset[Leaf]) -> frozenset[Leaf]:
        """The leaves that must be done (fewest possible) before ``target`` can be performed.

        Walking down from the root to ``target``: in a chain, every child before the one holding ``target``
        must be finished; in a clique, a child under way (other than the one holding ``target``) must be
        finished first. Those leaves, in some valid order, then ``target``, is the shortest way to it.
        """
        if isinstance(self.structure, PartialOrder):
            return self.structure.required(target, done)
        out: set[Leaf] = set()
        for node, index in self._ancestry[target]:
            for j, child in enumerate(node.children):
                if j == index:
                    if isinstance(node, ChainNode):
                        break
                    continue
                undone = [leaf for leaf in child.leaves if leaf not in done]
                if isinstance(node, ChainNode) or 0 < len(undone) < len(child.leaves):
                    out.update(undone)
        return frozenset(out)


def _ancestry(structure: Node) -> dict[Leaf, list[tuple[ChainNode | CliqueNode, int]]]:
    """For each leaf, its (ancestor, index of the child holding it) pairs from the root down."""
    out: dict[Leaf, list[tuple[ChainNode | CliqueNode, int]]] = {}

    def walk(node: Node, path: list[tuple[ChainNode | CliqueNode, int]]) -> None:
        if isinstance(node, ActionNode):
            out[node.leaf] = path
            return
        for i, child in enumerate(node.children):
            walk(child, [*path, (node, i)])

    walk(structure, [])
    return out


def _perturb(structure: KnownTask, base: Sequence[Leaf], probability: float, seed: Seed) -> tuple[Leaf, ...]:
    """One left-to-right pass of adjacent swaps, each kept only when the path stays valid."""
    rng = rng_from(seed)
    path = list(base)
    i = 0
    while i < len(path) - 1:
        u, v = path[i], path[i + 1]
        if probability > 0 and rng.random() < probability and u[0] != v[0]:
            prefix = path[:i]
            # Allowed leaves depend only on the set done, so the rest of the path stays valid.
            if v in _allowed_next(structure, prefix) and u in _allowed_next(structure, [*prefix, v]):
                path[i], path[i + 1] = v, u
                i += 2
                continue
        i += 1
    return tuple(path)


def demonstrate(instructor: SimulatedInstructor) -> list[str]:
    """A full demonstration with no queries: the instructor's preferred path.

    >>> from supportive.tasks.htn import ActionNode, ChainNode
    >>> demonstrate(SimulatedInstructor(ChainNode((ActionNode("a"), ActionNode("b")))))
    ['a', 'b']
    """
    instructor.begin_demonstration()
    done: list[str] = []
    while (action := instructor.next_action(tuple(done), None)) is not None:
        done.append(action)
    return done


def _action_sequences(graph: TaskGraph, where: str) -> list[list[str]]:
    if graph.explicit_states:
        raise LearningError(
            f"{where}: pooling replays demonstrations with derived states only; this graph has explicit states"
        )
    return [[graph.subgoals[s][0] for s in demo] for demo in graph.demonstrations]


def pooled_task_graph(graphs: Sequence[TaskGraph]) -> TaskGraph:
    """The union of learned environment-space graphs: every graph's demonstrations replayed into a new graph.

    States are derived from completed actions (the multiset of §2.1.2), so the union of two graphs is a graph
    holding both; its known paths include each member's (and paths that combine them where they share states).

    Args:
        graphs: The graphs to pool (their demonstrations are replayed in order).

    Raises:
        LearningError: when a graph was built with explicit environment states.

    >>> a, b = TaskGraph(), TaskGraph()
    >>> _ = a.add(["x", "y"]); _ = b.add(["y", "x"])
    >>> pooled_task_graph([a, b]).path_count()
    2
    """
    pooled = TaskGraph()
    for g, graph in enumerate(graphs):
        for d, actions in enumerate(_action_sequences(graph, f"graph {g + 1}")):
            pooled.add(actions, f"g{g + 1}.d{d + 1}")
    return pooled


def pooled_learner(learners: Sequence[HTNLearner], **options: Any) -> HTNLearner:
    """A learner fitted on all the demonstrations the given learners saw, in order (pooled instruction).

    Its task graph equals :func:`pooled_task_graph` of theirs, so its known-path count is at least each
    member's.

    Args:
        learners: Fitted learners.
        **options: Passed to :class:`HTNLearner` (otherwise the first learner's ``mode`` and default
            hyper-parameters).

    Raises:
        LearningError: when there is no learner, one is not fitted, or one's graph has explicit states.
    """
    demos: list[list[str]] = []
    for i, learner in enumerate(learners):
        if not hasattr(learner, "task_graph_"):
            raise LearningError(f"learner {i + 1} is not fitted; fit it before pooling")
        demos.extend(_action_sequences(learner.task_graph_, f"learner {i + 1}"))
    if not demos:
        raise LearningError("no demonstrations to pool: give at least one fitted learner")
    options.setdefault("mode", learners[0].mode)
    return HTNLearner(**options).fit(demos, learners[0].task_)
