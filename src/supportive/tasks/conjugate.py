"""The Conjugate Task Graph (§2.1.3): subgoals as vertices, environmental prerequisites on edges.

Built by :func:`supportive.learning.strict.conjugate.conjugate_task_graph` (Algorithm 1). Edges between the same two
vertices keep only their minimal prerequisite sets (lines 15–16 of Algorithm 1): an edge whose prerequisites
contain another's is redundant.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal, TypeAlias

from supportive.tasks.task_graph import TaskGraph

if TYPE_CHECKING:  # imported where used: networkx is a fifth of every command's start-up
    import networkx as nx

__all__ = ["ORIGIN", "TERMINAL", "CTGEdge", "ConjugateTaskGraph", "Vertex"]

ORIGIN: Literal["origin"] = "origin"
TERMINAL: Literal["terminal"] = "terminal"
Vertex: TypeAlias = int | Literal["origin", "terminal"]
"""A subgoal index of the task graph, or one of the two virtual vertices."""

EMPTY = -1
"""Prerequisite marker for the empty set (edges out of the origin vertex)."""


@dataclass(frozen=True)
class CTGEdge:
    """An edge of the CTG: ``target`` may follow ``source`` once ``prerequisites`` hold."""

    source: Vertex
    target: Vertex
    prerequisites: frozenset[str]


class ConjugateTaskGraph:
    """A CTG over a :class:`TaskGraph`. Prerequisites are stored as task-graph states and shown as label sets."""

    def __init__(self, task_graph: TaskGraph) -> None:
        self.task_graph = task_graph
        self._edges: dict[tuple[Vertex, Vertex], list[int]] = {}
        self._succ: dict[Vertex, set[Vertex]] = {}
        self._pred: dict[Vertex, set[Vertex]] = {}

    def add(self, source: Vertex, target: Vertex, state: int) -> bool:
        """Add an edge whose prerequisites are task-graph ``state`` (or :data:`EMPTY`); keep only minimal ones.

        Returns:
            True when the CTG changed.
        """
        known = self._edges.setdefault((source, target), [])
        graph = self.task_graph
        if state == EMPTY:
            if EMPTY in known:
                return False
            known.clear()
        else:
            if any(p == EMPTY or graph.is_subset_state(p, state) for p in known):
                return False
            known[:] = [p for p in known if not graph.is_subset_state(state, p)]
        known.append(state)
        self._succ.setdefault(source, set()).add(target)
        self._pred.setdefault(target, set()).add(source)
        return True

    @property
    def vertices(self) -> list[Vertex]:
        """Origin, every subgoal, terminal."""
        return [ORIGIN, *range(len(self.task_graph.subgoals)), TERMINAL]

    @property
    def n_vertices(self) -> int:
        """Number of vertices, the two virtual ones included."""
        return len(self.task_graph.subgoals) + 2

    @property
    def n_edges(self) -> int:
        """Number of edges left after redundant-edge removal."""
        return sum(len(states) for states in self._edges.values())

    def successors(self, vertex: Vertex) -> set[Vertex]:
        """Vertices reachable from ``vertex`` by one edge."""
        return set(self._succ.get(vertex, ()))

    def predecessors(self, vertex: Vertex) -> set[Vertex]:
        """Vertices with an edge into ``vertex``."""
        return set(self._pred.get(vertex, ()))

    def prerequisite_states(self, source: Vertex, target: Vertex) -> list[int]:
        """The task-graph states (minimal prerequisites) on the edges from ``source`` to ``target``."""
        return list(self._edges.get((source, target), ()))

    def prerequisites(self, state: int) -> frozenset[str]:
        """The label set of a prerequisite state."""
        return frozenset() if state == EMPTY else self.task_graph.prerequisites(state)

    def label(self, vertex: Vertex) -> str:
        """Display name of a vertex."""
        return vertex if isinstance(vertex, str) else self.task_graph.subgoal_label(vertex)

    def edges(self) -> Iterator[CTGEdge]:
        """Every edge with its prerequisites as labels."""
        for (source, target), states in self._edges.items():
            for state in states:
                yield CTGEdge(source, target, self.prerequisites(state))

    def to_networkx(self) -> nx.MultiDiGraph:
        """A networkx multigraph with vertex labels and ``prerequisites`` on each edge."""
        import networkx as nx

        graph = nx.MultiDiGraph()
        for vertex in self.vertices:
            graph.add_node(vertex, label=self.label(vertex))
        for edge in self.edges():
            graph.add_edge(edge.source, edge.target, prerequisites=sorted(edge.prerequisites))
        return graph
