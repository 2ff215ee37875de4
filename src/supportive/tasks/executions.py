"""The executions a Clique/Chain HTN admits, as a state machine over its leaves.

A state (:class:`Progress`) is what is done (a bit mask over the hierarchy's leaves), which leaf was done last
and, for a partial hierarchy, the top-level state in which the root now under way began. That is all that
decides what may come next: in a chain or a clique at most one child is under way (the one holding the last
leaf); a child that was started and left is finished for good (no interleaving, §2.1.4); an optional node not
started may still be started or skipped; a node may end once everything it still lacks is optional.

The same machine answers "is this sequence admitted", "what may come next" and "may the task end here", for
leaf sequences (``("pick_leg", 3)``) and for action ids (``"pick_leg"``: then a step may be any leaf of that
action that is allowed, so which leg was picked is decided by the hierarchy, not by counting). When a clique's
children are instances of one repeated subtask (the same shape with other occurrence numbers: four legs),
action-level runs start the lowest-numbered instance not yet started, which removes the k! equivalent
labellings without changing which action sequences are admitted.

>>> from supportive.tasks.htn import HTN, ActionNode, ChainNode
>>> task = HTN("t", (ChainNode((ActionNode("a"), ActionNode("b", optional=True), ActionNode("c"))),))
>>> task.executions.accepts(["a", "c"]), task.executions.accepts(["a", "c", "b"])
(True, False)
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import Protocol

from supportive.tasks.nodes import ActionNode, ChainNode, Leaf, Node, TopLevel, nullable, shape

__all__ = ["Executions", "Hierarchy", "Progress", "Step", "Table"]

Step = str | Leaf
"""A step of a run: an action id, or a leaf (``("pick_leg", 3)``)."""


class Hierarchy(Protocol):
    """What the machine reads of a hierarchy (an :class:`~supportive.tasks.htn.HTN`): its roots and, for a
    partial one, its top level."""

    @property
    def roots(self) -> tuple[Node, ...]:
        """The top-level nodes; one when the hierarchy is complete."""

    @property
    def top_level(self) -> TopLevel | None:
        """How a partial hierarchy's roots follow one another (``None`` when it is complete)."""


@dataclass(frozen=True, slots=True)
class Progress:
    """Where an execution is: ``done`` leaves (bit ``i`` for ``Executions.leaves[i]``), the index of the
    ``last`` leaf done (-1 before the first) and the ``top``-level state in which the current root began
    (always 0 for a complete hierarchy; past the top level's own states, one standing for several in which
    it may have begun, see :meth:`Executions.top_successors`)."""

    top: int
    done: int
    last: int


@dataclass(frozen=True, slots=True)
class Table:
    """One internal node, flattened: its kind, children's node ids, masks and symmetry classes."""

    chain: bool
    children: tuple[int, ...]
    classes: tuple[int, ...]


class Executions:
    """The state machine of an HTN's executions (see the module docstring).

    Besides the runs, the flattened hierarchy is public for models that walk it (the progress model of
    :mod:`supportive.learning.distribution`): nodes are numbered depth first; ``parents[n]`` is ``(parent,
    position)`` (``(-1, r)`` for root ``r``), ``tables[n]`` a chain or clique's children and symmetry classes,
    ``masks[n]`` its leaves as bits, ``nullables[n]`` whether it may be performed as nothing, ``leaf_nodes[i]``
    the node of leaf ``i``, ``root_nodes[r]`` and ``root_of_leaf[i]`` the roots, ``top_out`` the top-level
    graph (``state -> {root -> state}``; for a complete hierarchy ``0 -> {0: 1}``), ``top_terminal`` its
    terminal states; :meth:`top_successors` and :meth:`top_ends` answer the same of every top-level state a
    :class:`Progress` may hold.

    Args:
        htn: A complete hierarchy or a partial one with its ``top_level``.
    """

    def __init__(self, htn: Hierarchy) -> None:
        self.htn = htn
        self.leaves: tuple[Leaf, ...] = tuple(leaf for root in htn.roots for leaf in root.leaves)
        self.index: dict[Leaf, int] = {leaf: i for i, leaf in enumerate(self.leaves)}
        self.masks: list[int] = []
        self.nullables: list[bool] = []
        self.firsts: list[tuple[int, ...]] = []
        self.firsts_symmetric: list[tuple[int, ...]] = []
        self.tables: dict[int, Table] = {}
        self.parents: list[tuple[int, int]] = []  # node id -> (parent id, position), (-1, r) for root r
        self.leaf_nodes: list[int] = [0] * len(self.leaves)
        self.root_nodes: list[int] = [self._build(root, (-1, r)) for r, root in enumerate(htn.roots)]
        self.root_of_leaf = [0] * len(self.leaves)
        for r, node_id in enumerate(self.root_nodes):
            for leaf_index in _bits(self.masks[node_id]):
                self.root_of_leaf[leaf_index] = r
        if htn.top_level is None:
            self.top_out: dict[int, dict[int, int]] = {0: {r: 1 for r in range(len(htn.roots))}}
            self.top_terminal: frozenset[int] = frozenset({1})
            self.initial_tops: tuple[int, ...] = (0,)
        else:
            self.top_out = htn.top_level.successors()
            self.top_terminal = frozenset(htn.top_level.terminal)
            self.initial_tops = tuple(htn.top_level.initial)
        if htn.top_level is None and len(htn.roots) != 1:
            self.top_out = {}
        # Beginning a root after skipping others: where every skippable root is free (skipping one only
        # forbids, TopLevel.free), the state reached with the fewest skips allows all that the others do;
        # else a root begun may stand in several top-level states at once: -(the bit mask of their numbers),
        # the same number in every machine of the hierarchy.
        free = htn.top_level.free if htn.top_level is not None else frozenset()
        self._fewest_skips = all(r in free for r, node in enumerate(self.root_nodes) if self.nullables[node])
        self._several_out: dict[int, dict[int, int]] = {}
        self._several_end: dict[int, bool] = {}
        self._closures: dict[int, tuple[int, ...]] = {}
        self._begins: dict[tuple[int, bool], tuple[tuple[tuple[int, int, int], ...], bool]] = {}
        self._by_action: dict[str, tuple[int, ...]] = {}
        for i, (action, _) in enumerate(self.leaves):
            self._by_action[action] = (*self._by_action.get(action, ()), i)
        self._cache: dict[tuple[Progress, bool], tuple[dict[int, Progress], bool]] = {}

    # ------------------------------------------------------------------ building
    def _build(self, node: Node, parent: tuple[int, int]) -> int:
        node_id = len(self.masks)
        self.masks.append(0)
        self.nullables.append(nullable(node))
        self.firsts.append(())
        self.firsts_symmetric.append(())
        self.parents.append(parent)
        if isinstance(node, ActionNode):
            leaf_index = self.index[node.leaf]
            self.masks[node_id] = 1 << leaf_index
            self.firsts[node_id] = self.firsts_symmetric[node_id] = (leaf_index,)
            self.leaf_nodes[leaf_index] = node_id
            return node_id
        children = tuple(self._build(child, (node_id, i)) for i, child in enumerate(node.children))
        shapes: dict[object, int] = {}
        classes = tuple(shapes.setdefault(shape(child), len(shapes)) for child in node.children)
        chain = isinstance(node, ChainNode)
        self.tables[node_id] = Table(chain, children, classes)
        mask = 0
        for child in children:
            mask |= self.masks[child]
        self.masks[node_id] = mask
        self.firsts[node_id] = self._starts(children, classes, chain, symmetric=False)
        self.firsts_symmetric[node_id] = self._starts(children, classes, chain, symmetric=True)
        return node_id

    def _starts(
        self, children: Sequence[int], classes: Sequence[int], chain: bool, *, symmetric: bool
    ) -> tuple[int, ...]:
        firsts = self.firsts_symmetric if symmetric else self.firsts
        out: list[int] = []
        if chain:
            for child in children:
                out.extend(firsts[child])
                if not self.nullables[child]:
                    break
            return tuple(out)
        seen: set[int] = set()
        for child, cls in zip(children, classes, strict=True):
            if symmetric and cls in seen:
                continue
            seen.add(cls)
            out.extend(firsts[child])
        return tuple(out)

    # ------------------------------------------------------------------ moves
    def initial(self) -> tuple[Progress, ...]:
        """The states before anything is done (one per initial top-level state)."""
        return tuple(Progress(top, 0, -1) for top in self.initial_tops)

    def moves(self, state: Progress, *, symmetric: bool = False) -> dict[int, Progress]:
        """Leaf index -> the state after performing that leaf, for every leaf allowed next.

        Args:
            state: Where the execution is.
            symmetric: Start only the lowest-numbered unstarted instance of a repeated subtask (for runs over
                action ids; see the module docstring).
        """
        return self._step(state, symmetric)[0]

    def can_finish(self, state: Progress) -> bool:
        """True when the task may end in ``state`` (everything it still lacks is optional)."""
        return self._step(state, False)[1]

    def _step(self, state: Progress, symmetric: bool) -> tuple[dict[int, Progress], bool]:
        key = (state, symmetric)
        cached = self._cache.get(key)
        if cached is None:
            cached = self._cache[key] = self._compute(state, symmetric)
        return cached

    def _compute(self, state: Progress, symmetric: bool) -> tuple[dict[int, Progress], bool]:
        firsts = self.firsts_symmetric if symmetric else self.firsts
        moves: dict[int, Progress] = {}
        if state.last < 0:
            return self._starts_from(state.top, 0, symmetric, moves)
        within: list[int] = []
        can_end = True
        node = self.leaf_nodes[state.last]
        parent, position = self.parents[node]
        while parent >= 0 and can_end:
            table = self.tables[parent]
            can_end = True
            if table.chain:
                for child in table.children[position + 1 :]:
                    within.extend(firsts[child])
                    if not self.nullables[child]:
                        can_end = False
                        break
            else:
                seen: set[int] = set()
                for child, cls in zip(table.children, table.classes, strict=True):
                    if state.done & self.masks[child]:
                        continue
                    if not (symmetric and cls in seen):
                        within.extend(firsts[child])
                    seen.add(cls)
                    if not self.nullables[child]:
                        can_end = False
            parent, position = self.parents[parent]
        for leaf in within:
            moves[leaf] = Progress(state.top, state.done | 1 << leaf, leaf)
        if not can_end:
            return moves, False
        root = self.root_of_leaf[state.last]
        after = self.top_successors(state.top).get(root)
        if after is None:
            return moves, False
        return self._starts_from(after, state.done, symmetric, moves)

    def _starts_from(
        self, top: int, done: int, symmetric: bool, moves: dict[int, Progress]
    ) -> tuple[dict[int, Progress], bool]:
        """Add to ``moves`` the leaves that begin a root not yet begun (in ``done``) from top-level state
        ``top`` (or from a state that skipping roots that may be performed as nothing leads to); and say
        whether the task may end there."""
        begins, can_end = self._begins_from(top, symmetric)
        for root_mask, leaf, begun in begins:
            if not done & root_mask:
                moves.setdefault(leaf, Progress(begun, done | 1 << leaf, leaf))
        return moves, can_end

    def _begins_from(self, top: int, symmetric: bool) -> tuple[tuple[tuple[int, int, int], ...], bool]:
        """For top-level state ``top`` (worked out once): each leaf that may begin a root from it or from a
        state skipping leads to, as ``(the root's leaves as bits, leaf, the state the root begins in)``, in
        the order found; and whether the task may end there."""
        key = (top, symmetric)
        cached = self._begins.get(key)
        if cached is not None:
            return cached
        firsts = self.firsts_symmetric if symmetric else self.firsts
        can_end = False
        begun: dict[int, list[int]] = {}  # leaf -> the states it may begin its root from, fewest skips first
        for state in self.skip_closure(top):
            can_end |= self.top_ends(state)
            for nxt in self.top_successors(state):
                for leaf in firsts[self.root_nodes[nxt]]:
                    begun.setdefault(leaf, []).append(state)
        begins = []
        for leaf, states in begun.items():
            root = self.root_of_leaf[leaf]
            begins.append(
                (self.masks[self.root_nodes[root]], leaf, states[0] if self._fewest_skips else self._begun_in(states, root))
            )
        cached = self._begins[key] = (tuple(begins), can_end)
        return cached

    def _begun_in(self, states: Iterable[int], root: int) -> int:
        """The top-level state standing for those of ``states`` (of the states they stand for) that ``root``
        may begin in."""
        return _standing_for(
            real for state in states for real in _real(state) if root in self.top_out.get(real, {})
        )

    def skip_closure(self, top: int) -> tuple[int, ...]:
        """``top`` and the top-level states reached from it by skipping roots that may be performed as
        nothing, breadth first: fewer skips first (worked out once per state)."""
        closure = self._closures.get(top)
        if closure is None:
            order = [top]
            seen = {top}
            for state in order:  # grows as it goes: a queue
                for root, dst in self.top_successors(state).items():
                    if self.nullables[self.root_nodes[root]] and dst not in seen:
                        seen.add(dst)
                        order.append(dst)
            closure = self._closures[top] = tuple(order)
        return closure

    def top_successors(self, top: int) -> dict[int, int]:
        """``root -> state`` of the top-level edges out of ``top``: a state of the top level, or one standing
        for several (negative: a root that may have begun in any of them, after skipping one root or another;
        its edges lead, for each root, to the state standing for where that root leads from each of them)."""
        if top >= 0:
            return self.top_out.get(top, {})
        out = self._several_out.get(top)
        if out is None:
            leads: dict[int, list[int]] = {}
            for member in _real(top):
                for root, dst in self.top_out.get(member, {}).items():
                    leads.setdefault(root, []).append(dst)
            out = self._several_out[top] = {root: _standing_for(dsts) for root, dsts in leads.items()}
        return out

    def top_ends(self, top: int) -> bool:
        """Whether the task may end in top-level state ``top`` (one standing for several: when any of them
        may)."""
        if top >= 0:
            return top in self.top_terminal
        ends = self._several_end.get(top)
        if ends is None:
            ends = self._several_end[top] = any(member in self.top_terminal for member in _real(top))
        return ends

    # ------------------------------------------------------------------ runs
    def advance(self, states: Iterable[Progress], step: Step) -> tuple[Progress, ...]:
        """The states after performing ``step`` from any of ``states`` (empty when it is allowed from none):
        a leaf, or an action id (then any allowed leaf of that action)."""
        following: dict[Progress, None] = {}
        if isinstance(step, tuple):
            index = self.index.get(step)
            if index is None:
                return ()
            for state in states:
                nxt = self.moves(state).get(index)
                if nxt is not None:
                    following[nxt] = None
            return tuple(following)
        candidates = self._by_action.get(step, ())
        for state in states:
            allowed = self.moves(state, symmetric=True)
            for index in candidates:
                nxt = allowed.get(index)
                if nxt is not None:
                    following[nxt] = None
        return tuple(following)

    def run_leaves(self, leaves: Iterable[Leaf]) -> tuple[Progress, ...]:
        """The states after performing ``leaves`` in order (empty when the sequence is not a valid prefix)."""
        return self._run(leaves)

    def run(self, actions: Iterable[str]) -> tuple[Progress, ...]:
        """The states after performing ``actions`` (action ids) in order, each step any allowed leaf of its
        action (empty when no execution starts this way)."""
        return self._run(actions)

    def _run(self, steps: Iterable[Step]) -> tuple[Progress, ...]:
        states = self.initial()
        for step in steps:
            states = self.advance(states, step)
            if not states:
                return ()
        return states

    def single_moves(self, steps: Sequence[Step], positions: Iterable[int]) -> Iterator[int]:
        """The positions among ``positions`` whose step, moved to another place of ``steps``, makes a whole
        execution the hierarchy admits (lazily, in the order given).

        Exact, and far cheaper than trying every move: the runs after each prefix are shared, and a state found
        unable to finish what is left of ``steps`` is remembered as such for every later move (a run follows
        every state it may be in, so when none of them finishes, none can).

        Args:
            steps: Leaves or action ids.
            positions: Which steps to try moving.
        """
        n = len(steps)
        finishes = self._finisher(steps)
        prefixes = [self.initial()]  # runs of steps[:k]
        for step in steps:
            prefixes.append(self.advance(prefixes[-1], step) if prefixes[-1] else ())
        for i in positions:
            moved = steps[i]
            for j in range(i):  # to before steps[j]
                if finishes(self.advance(prefixes[j], moved), j, i):
                    yield i
                    break
            else:
                states = prefixes[i]
                for j in range(i + 1, n):  # to after steps[j]
                    states = self.advance(states, steps[j])
                    if not states:
                        break
                    if finishes(self.advance(states, moved), j + 1, -1):
                        yield i
                        break

    def with_insertions(self, steps: Sequence[Step], inserted: Sequence[Step]) -> list[Step] | None:
        """``steps`` with every step of ``inserted`` done somewhere, making a whole execution the hierarchy
        admits, each as early as the others allow (the first such sequence when, place by place, doing a step of
        ``inserted`` comes before going on with ``steps``, and the steps of ``inserted`` are tried in the order
        given); None when there is none. Inserting the steps together finds places that one at a time would not
        (the first step put back has no place while the second is still out). Exact: a depth-first search over
        the runs, each state found unable to finish remembered with where it stood and what was left to insert.

        >>> from supportive.tasks.htn import HTN, ActionNode, ChainNode
        >>> chain = HTN("t", (ChainNode(tuple(ActionNode(a) for a in "abcd")),))
        >>> chain.executions.with_insertions(["b", "c"], ["d", "a"])
        ['a', 'b', 'c', 'd']
        """
        n = len(steps)
        dead: set[tuple[Progress, int, tuple[Step, ...]]] = set()  # (state, next of steps, still to insert)

        def search(states: tuple[Progress, ...], k: int, left: tuple[Step, ...]) -> list[Step] | None:
            visited: list[tuple[Progress, int, tuple[Step, ...]]] = []
            done: list[Step] = []
            while True:
                states = tuple(s for s in states if (s, k, left) not in dead)
                if not states:
                    break
                visited.extend((s, k, left) for s in states)
                for i, step in enumerate(left):
                    if step in left[:i]:
                        continue  # the same step tried already
                    after = self.advance(states, step)
                    rest = search(after, k, left[:i] + left[i + 1 :]) if after else None
                    if rest is not None:
                        return [*done, step, *rest]
                if k == n:
                    if not left and any(self.can_finish(s) for s in states):
                        return done
                    break
                states = self.advance(states, steps[k])
                done.append(steps[k])
                k += 1
            dead.update(visited)
            return None

        return search(self.initial(), 0, tuple(inserted))

    def _finisher(self, steps: Sequence[Step]) -> Callable[[tuple[Progress, ...], int, int], bool]:
        """``finishes(states, start, gap)``: whether a run in ``states`` can finish with ``steps[start:]``
        less ``steps[gap]`` (-1: none left out) as a whole execution. A state found unable to is remembered
        with where it stood, for every later question about the same ``steps``."""
        n = len(steps)
        dead: set[tuple[Progress, int, int]] = set()  # (state, first step left, step left out or -1)

        def finishes(states: tuple[Progress, ...], start: int, gap: int) -> bool:
            visited: list[tuple[Progress, int, int]] = []
            for k in range(start, n + 1):
                if k == gap:
                    continue
                key_gap = gap if k < gap else -1
                states = tuple(s for s in states if (s, k, key_gap) not in dead)
                visited.extend((s, k, key_gap) for s in states)
                if not states:
                    break
                if k == n:
                    if any(self.can_finish(s) for s in states):
                        return True
                    break
                states = self.advance(states, steps[k])
            dead.update(visited)
            return False

        return finishes

    def accepts_leaves(self, leaves: Iterable[Leaf]) -> bool:
        """True when ``leaves`` is a whole execution the hierarchy admits."""
        return any(self.can_finish(s) for s in self.run_leaves(leaves))

    def accepts(self, actions: Iterable[str]) -> bool:
        """True when the action ids ``actions`` are a whole execution the hierarchy admits."""
        return any(self.can_finish(s) for s in self.run(actions))

    def allowed(self, state: Progress) -> frozenset[Leaf]:
        """The leaves allowed next in ``state``."""
        return frozenset(self.leaves[i] for i in self.moves(state))


def _standing_for(states: Iterable[int]) -> int:
    """The top-level state standing for ``states`` (each a real one or standing for several): itself when they
    are one, else -(the bit mask of the real ones)."""
    mask = 0
    for state in states:
        mask |= 1 << state if state >= 0 else -state
    return mask.bit_length() - 1 if mask & (mask - 1) == 0 else -mask


def _real(top: int) -> Iterable[int]:
    """The states of the top level that ``top`` stands for (itself, when it is one)."""
    return (top,) if top >= 0 else _bits(-top)


def _bits(mask: int) -> Iterable[int]:
    """The positions of the bits set in ``mask``, lowest first."""
    while mask:
        lowest = mask & -mask
        yield lowest.bit_length() - 1
        mask ^= lowest
