"""The environment-space task graph (§2.1.1–2.1.2): the union of demonstrated executions.

States are the multiset of actions completed so far (the commutativity assumption of §2.1.2), or, when a file
gives them, explicit environment states (sets of fluents). Edges are labelled with *subgoals*: an action and which
performance of it this is (``("stir", 2)`` is the second stir). Each state knows which subgoals are done, as a
bit mask over subgoal indices, which is what every algorithm works with.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Hashable, Iterator, Sequence
from dataclasses import dataclass

from supportive.errors import TaskGraphError
from supportive.tasks.htn import Leaf, to_leaves
from supportive.tasks.spec import Demonstration

__all__ = ["GraphUpdate", "TaskGraph"]


@dataclass(frozen=True)
class GraphUpdate:
    """What one added demonstration changed: new edges ``(src, subgoal, dst)`` and states that became terminal."""

    edges: tuple[tuple[int, int, int], ...]
    new_terminal: tuple[int, ...]

    @property
    def changed(self) -> bool:
        """True when the graph gained an edge or a terminal state."""
        return bool(self.edges or self.new_terminal)


class TaskGraph:
    """The learner's environment-space graph T, grown one demonstration at a time.

    >>> g = TaskGraph()
    >>> _ = g.add(["a", "b", "c"]); _ = g.add(["b", "a", "c"])
    >>> g.path_count(), g.n_states, g.n_edges
    (2, 5, 5)
    """

    def __init__(self) -> None:
        self.subgoals: list[Leaf] = []
        self._subgoal_index: dict[Leaf, int] = {}
        self.mask: list[int] = []
        self.fluents: list[frozenset[str] | None] = []
        self.out: list[dict[int, int]] = []
        self.into: list[list[tuple[int, int]]] = []
        self.initial: set[int] = set()
        self.terminal: set[int] = set()
        self.demonstrations: list[tuple[int, ...]] = []
        self.explicit_states: bool | None = None
        self._state_of: dict[Hashable, int] = {}
        self._n_edges = 0
        self._paths: int | None = None

    # ------------------------------------------------------------------ building
    def add(self, actions: Sequence[str], demo_id: str = "") -> GraphUpdate:
        """Add a demonstration given as a plain action sequence (states derived from completed actions).

        Raises:
            TaskGraphError: when the sequence is empty or earlier demonstrations gave explicit states.
        """
        return self.add_leaves(to_leaves(actions), demo_id)

    def add_leaves(self, leaves: Sequence[Leaf], demo_id: str = "") -> GraphUpdate:
        """Add a demonstration given as the subgoals it performs, ``(action, occurrence)`` each, every one at
        most once (which performance of a repeated action a step is, decided elsewhere).

        Raises:
            TaskGraphError: when the sequence is empty, repeats a subgoal or earlier demonstrations gave
                explicit states.
        """
        if not leaves:
            raise TaskGraphError(f"demonstration {demo_id or '?'} has no steps")
        if len(set(leaves)) != len(leaves):
            raise TaskGraphError(f"demonstration {demo_id or '?'} performs a subgoal twice")
        self._check_mode(False, demo_id)
        state = self._state(0, 0, None, demo_id)
        self.initial.add(state)
        new_edges: list[tuple[int, int, int]] = []
        sequence = []
        mask = 0
        index, state_of = self._subgoal_index, self._state_of
        for leaf in leaves:
            action = leaf[0]
            subgoal = index.get(leaf)
            if subgoal is None:
                subgoal = self._subgoal(leaf)
            sequence.append(subgoal)
            mask |= 1 << subgoal
            dst = state_of.get(mask)
            if dst is None:
                dst = self._state(mask, mask, None, demo_id)
            state = self._link(state, subgoal, dst, new_edges, action, demo_id)
        return self._finish(state, sequence, new_edges)

    def add_demonstration(self, demo: Demonstration) -> GraphUpdate:
        """Add one demonstration and say what changed.

        Raises:
            TaskGraphError: when the demonstration is empty, mixes explicit and derived states with earlier
                ones, or gives explicit states that contradict what is known.
        """
        if not demo.has_states:
            return self.add(demo.actions, demo.id)
        if any(step.state is None for step in demo.steps):
            raise TaskGraphError(f"demonstration {demo.id or '?'}: every step needs a state when one has it")
        self._check_mode(True, demo.id)
        state = self._state(frozenset(demo.initial_state or ()), 0, demo.initial_state, demo.id)
        self.initial.add(state)
        new_edges: list[tuple[int, int, int]] = []
        counts: Counter[str] = Counter()
        sequence = []
        mask = 0
        for step in demo.steps:
            counts[step.action] += 1
            subgoal = self._subgoal((step.action, counts[step.action]))
            sequence.append(subgoal)
            mask |= 1 << subgoal
            dst = self._state(step.state, mask, step.state, demo.id)
            state = self._link(state, subgoal, dst, new_edges, step.action, demo.id)
        return self._finish(state, sequence, new_edges)

    def _check_mode(self, explicit: bool, demo_id: str) -> None:
        if self.explicit_states is None:
            self.explicit_states = explicit
        elif self.explicit_states != explicit:
            raise TaskGraphError(
                f"demonstration {demo_id or '?'}: all demonstrations must give explicit states, or none"
            )

    def _link(
        self,
        src: int,
        subgoal: int,
        dst: int,
        new_edges: list[tuple[int, int, int]],
        action: str,
        demo_id: str,
    ) -> int:
        known = self.out[src].get(subgoal)
        if known is None:
            self.out[src][subgoal] = dst
            self.into[dst].append((subgoal, src))
            self._n_edges += 1
            new_edges.append((src, subgoal, dst))
        elif known != dst:
            raise TaskGraphError(
                f"demonstration {demo_id or '?'}: action {action!r} from the same state leads to "
                "different states in different demonstrations"
            )
        return dst

    def _finish(self, state: int, sequence: list[int], new_edges: list[tuple[int, int, int]]) -> GraphUpdate:
        new_terminal = () if state in self.terminal else (state,)
        self.terminal.add(state)
        self.demonstrations.append(tuple(sequence))
        if new_edges or new_terminal:
            self._paths = None
        return GraphUpdate(tuple(new_edges), new_terminal)

    def _subgoal(self, leaf: Leaf) -> int:
        index = self._subgoal_index.get(leaf)
        if index is None:
            index = len(self.subgoals)
            self._subgoal_index[leaf] = index
            self.subgoals.append(leaf)
        return index

    def _state(self, key: Hashable, mask: int, fluents: frozenset[str] | None, demo_id: str) -> int:
        state = self._state_of.get(key)
        if state is None:
            state = len(self.mask)
            self._state_of[key] = state
            self.mask.append(mask)
            self.fluents.append(fluents)
            self.out.append({})
            self.into.append([])
        elif self.mask[state] != mask:
            raise TaskGraphError(
                f"demonstration {demo_id or '?'}: state {sorted(fluents or ())} is reached after different "
                "actions in different demonstrations; explicit states must determine which actions are done"
            )
        return state

    # ------------------------------------------------------------------ reading
    @property
    def n_states(self) -> int:
        """Number of states."""
        return len(self.mask)

    @property
    def n_edges(self) -> int:
        """Number of labelled transitions."""
        return self._n_edges

    def subgoal_index(self, leaf: Leaf) -> int | None:
        """The index of a subgoal, or None when it was never performed."""
        return self._subgoal_index.get(leaf)

    def subgoal_label(self, subgoal: int) -> str:
        """``"stir"`` for a first performance, ``"stir#2"`` for the second."""
        action, occurrence = self.subgoals[subgoal]
        return action if occurrence == 1 else f"{action}#{occurrence}"

    def edges(self) -> Iterator[tuple[int, int, int]]:
        """Every transition ``(src, subgoal, dst)``."""
        for src, outs in enumerate(self.out):
            for subgoal, dst in outs.items():
                yield src, subgoal, dst

    def done_subgoals(self, state: int) -> tuple[int, ...]:
        """Indices of the subgoals completed in ``state``."""
        mask, out, bit = self.mask[state], [], 0
        while mask:
            if mask & 1:
                out.append(bit)
            mask >>= 1
            bit += 1
        return tuple(out)

    def prerequisites(self, state: int) -> frozenset[str]:
        """The environment state as a set of labels: its fluents when explicit, else the completed subgoals."""
        fluents = self.fluents[state]
        if fluents is not None:
            return fluents
        return frozenset(self.subgoal_label(s) for s in self.done_subgoals(state))

    def is_subset_state(self, small: int, big: int) -> bool:
        """True when state ``small``'s description is contained in state ``big``'s (for redundant CTG edges)."""
        fs, fb = self.fluents[small], self.fluents[big]
        if fs is not None and fb is not None:
            return fs <= fb
        return self.mask[small] & ~self.mask[big] == 0

    def topological_order(self) -> list[int]:
        if not self.explicit_states:
            return sorted(range(self.n_states), key=lambda s: self.mask[s].bit_count())
        order, seen = [], set()
        for root in sorted(self.initial):
            stack = [(root, iter(self.out[root].values()))]
            seen.add(root)
            while stack:
                node, children = stack[-1]
                child = next(children, None)
                if child is None:
                    order.append(node)
                    stack.pop()
                elif child not in seen:
                    seen.add(child)
                    stack.append((child, iter(self.out[child].values())))
        return order[::-1]

    def path_count(self) -> int:
        """Exact number of known origin→terminal paths (known valid executions), by dynamic programming."""
        if self._paths is None:
            paths = [0] * self.n_states
            for state in reversed(self.topological_order()):
                paths[state] = int(state in self.terminal) + sum(paths[d] for d in self.out[state].values())
            self._paths = sum(paths[s] for s in self.initial)
        return self._paths

    def contains(self, actions: Sequence[str]) -> bool:
        """True when ``actions`` is a known execution (a path from an initial to a terminal state)."""
        counts: Counter[str] = Counter()
        for start in self.initial:
            state: int | None = start
            counts.clear()
            for action in actions:
                counts[action] += 1
                subgoal = self._subgoal_index.get((action, counts[action]))
                state = None if subgoal is None or state is None else self.out[state].get(subgoal)
                if state is None:
                    break
            if state is not None and state in self.terminal:
                return True
        return False

    def iter_paths(self) -> Iterator[tuple[Leaf, ...]]:
        """Every known execution as a leaf sequence. Mind :meth:`path_count` first: it can be huge."""
        for start in sorted(self.initial):
            stack: list[tuple[int, tuple[Leaf, ...]]] = [(start, ())]
            while stack:
                state, prefix = stack.pop()
                if state in self.terminal:
                    yield prefix
                for subgoal, dst in sorted(self.out[state].items(), reverse=True):
                    stack.append((dst, (*prefix, self.subgoals[subgoal])))
