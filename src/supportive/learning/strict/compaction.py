"""Algorithm 2: compact maximal cliques and maximal chains, pass after pass, until one root or no change.

Every pass finds all maximal cliques and chains of the current level at once (they are disjoint: a node that
always hands over to one successor never commutes with anything) and rewrites the level in one sweep, so a pass
costs about the size of the level's graph. The passes are kept, so that a new demonstration only re-runs the
passes it changes (:meth:`Compaction.update`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from supportive.learning.strict.levels import Group, LevelGraph, Ordering
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, Node, TopLevel
from supportive.tasks.task_graph import TaskGraph

__all__ = ["Compaction", "Registry", "level_zero"]


@dataclass
class Registry:
    """The HTN nodes made so far: subgoals are ids 0, 1, …; compacted nodes are -1, -2, …"""

    nodes: dict[int, Node] = field(default_factory=dict)
    mask: dict[int, int] = field(default_factory=dict)
    ordering: Ordering = field(default_factory=Ordering)
    made: int = 0

    @classmethod
    def of(cls, graph: TaskGraph) -> Registry:
        """One leaf per subgoal of ``graph``."""
        registry = cls()
        for index, (action, occurrence) in enumerate(graph.subgoals):
            registry.nodes[index] = ActionNode(action, occurrence)
            registry.mask[index] = 1 << index
            registry.ordering.rank[index] = index
        return registry

    def add(self, group: Group) -> int:
        """Make the chain or clique node of ``group`` and return its id."""
        children: list[Node] = []
        for member in group.members:
            child = self.nodes[member]
            if group.ordered and isinstance(child, ChainNode):
                children.extend(child.children)
            else:
                children.append(child)
        self.made += 1
        node_id = -self.made
        self.nodes[node_id] = ChainNode(tuple(children)) if group.ordered else CliqueNode(tuple(children))
        self.mask[node_id] = group.mask
        self.ordering.rank[node_id] = self.ordering.key(group.members)
        return node_id

    def truncate(self, made: int) -> None:
        """Forget nodes made after the first ``made``."""
        for index in range(made + 1, self.made + 1):
            del self.nodes[-index], self.mask[-index], self.ordering.rank[-index]
        self.made = made

    def copy(self) -> Registry:
        """An independent copy (for trying alternatives)."""
        return Registry(dict(self.nodes), dict(self.mask), Ordering(dict(self.ordering.rank)), self.made)


Decision = list[tuple[Group, dict[int, int]]]


def decide(graph: LevelGraph, ordering: Ordering) -> Decision:
    """One pass of Algorithm 2: the verified maximal cliques, then the maximal chains, all disjoint."""
    chosen: Decision = []
    used: set[int] = set()
    for candidate in graph.clique_candidates(graph.commuting_pairs(), ordering):
        if candidate & used:
            continue
        exits = graph.verify_clique(candidate)
        if exits is None:
            continue
        members = tuple(sorted(candidate, key=lambda n: ordering.rank[n]))
        chosen.append((Group(members, False, graph.mask_of(members)), exits))
        used |= candidate
    for chain in graph.chains(ordering):
        if used.isdisjoint(chain.members):
            chosen.append((chain, graph.chain_exits(chain)))
    return chosen


def level_zero(graph: TaskGraph, registry: Registry) -> LevelGraph:
    """The task graph as level 0: one edge per transition, labelled with its subgoal."""
    by_node: dict[int, list[tuple[int, int]]] = {}
    for src, subgoal, dst in graph.edges():
        by_node.setdefault(subgoal, []).append((src, dst))
    return LevelGraph(by_node, frozenset(graph.initial), frozenset(graph.terminal), graph.mask, registry.mask)


class Compaction:
    """Algorithm 2 over a task graph, with every level kept.

    >>> g = TaskGraph()
    >>> for order in (["knife", "carrots", "celery"], ["knife", "celery", "carrots"]):
    ...     _ = g.add(order)
    >>> c = Compaction(g); c.run()
    >>> [type(n).__name__ for n in c.roots()]
    ['ChainNode']
    """

    def __init__(self, graph: TaskGraph) -> None:
        self.graph = graph
        self.registry = Registry.of(graph)
        self.levels: list[LevelGraph] = []
        self.decisions: list[Decision] = []
        self.made_before: list[int] = []

    @property
    def top(self) -> LevelGraph:
        """The last level: where compaction stopped."""
        return self.levels[-1]

    @classmethod
    def resumed(cls, graph: TaskGraph, level: LevelGraph, registry: Registry) -> Compaction:
        """Compact onwards from ``level`` (a restriction of ``graph``'s, say), adding nodes to ``registry``."""
        compaction = cls(graph)
        compaction.registry = registry
        compaction._continue(0, level)
        return compaction

    def run(self) -> None:
        """Compact from scratch."""
        self.registry = Registry.of(self.graph)
        self._continue(0, level_zero(self.graph, self.registry))

    def update(self) -> int:
        """Bring the hierarchy up to date after demonstrations were added to the task graph.

        Levels are recomputed bottom up only while the new executions change them: at the first level whose
        graph is unchanged, everything above is kept as it was.

        Returns:
            How many levels were recomputed.
        """
        if len(self.registry.nodes) - self.registry.made != len(self.graph.subgoals):
            self.run()
            return len(self.levels)
        level = level_zero(self.graph, self.registry)
        for depth in range(len(self.levels)):
            if level.signature() == self.levels[depth].signature():
                return depth
            if depth == len(self.decisions):
                break
            decision = decide(level, self.registry.ordering)
            if [g for g, _ in decision] != [g for g, _ in self.decisions[depth]]:
                self._continue(depth, level, decision)
                return len(self.levels) - depth
            self.levels[depth], self.decisions[depth] = level, decision
            first = self.made_before[depth]
            level = level.compact([(-(first + i + 1), g, exits) for i, (g, exits) in enumerate(decision)])
        depth = len(self.decisions)
        self._continue(depth, level)
        return len(self.levels) - depth

    def _continue(self, depth: int, level: LevelGraph, decision: Decision | None = None) -> None:
        self.registry.truncate(self.made_before_level(depth))
        del self.levels[depth:], self.decisions[depth:], self.made_before[depth:]
        while True:
            self.levels.append(level)
            if len(level.by_node) <= 1:
                return
            if decision is None:
                decision = decide(level, self.registry.ordering)
            if not decision:
                return
            self.made_before.append(self.registry.made)
            self.decisions.append(decision)
            level = level.compact([(self.registry.add(g), g, exits) for g, exits in decision])
            decision = None

    def made_before_level(self, depth: int) -> int:
        """How many compacted nodes existed before level ``depth`` was compacted."""
        if depth < len(self.made_before):
            return self.made_before[depth]
        return self.registry.made

    def roots(self) -> list[Node]:
        """The top-level nodes, in the order their members first occur."""
        return [self.registry.nodes[n] for n in self.root_ids()]

    def root_ids(self) -> list[int]:
        """Ids of the top-level nodes, in first-occurrence order."""
        return sorted(self.top.by_node, key=lambda n: self.registry.ordering.rank[n])

    def top_level(self) -> TopLevel | None:
        """How the roots follow one another, or None when there is one root."""
        return top_level_of(self.top, self.root_ids())


def top_level_of(level: LevelGraph, root_ids: Sequence[int]) -> TopLevel | None:
    """The :class:`TopLevel` of a stalled level, states renumbered from 0."""
    if len(root_ids) <= 1:
        return None
    index = {node: i for i, node in enumerate(root_ids)}
    number: dict[int, int] = {}

    def num(state: int) -> int:
        return number.setdefault(state, len(number))

    edges = []
    for state in sorted(level.initial):
        num(state)
    for node in root_ids:
        for src, dst in level.by_node[node]:
            edges.append((num(src), index[node], num(dst)))
    return TopLevel(
        initial=tuple(sorted(num(s) for s in level.initial)),
        terminal=tuple(sorted(num(s) for s in level.terminal)),
        edges=tuple(sorted(edges)),
    )
