"""Task-graph accuracy with the protocol of *Differentiable Task Graph Learning* (Seminara et al., NeurIPS 2024).

Their CaptainCook4D benchmark scores a learned task graph edge by edge against the recipe's published one:

1. the learned "a before b" relation becomes a graph, transitively reduced (an edge for each precondition
   no other precondition already implies);
2. ``START`` is the precondition of every step that has none, and ``END`` depends on every step nothing
   depends on;
3. precision and recall are taken over the flattened adjacency matrices (every ordered pair of nodes), i.e.
   over the two edge sets, and F1 from them; the ground truth is the published graph as given, with its own
   ``START`` and ``END`` edges.

Scored against itself this way, a published graph gets 1.0 unless it holds an edge that other edges imply
(the reduction drops it from the learned side). Edges are written ``(earlier, later)``; the direction of
"precondition of" is the reverse, which changes no count.

>>> a, b, c = ("a", 1), ("b", 1), ("c", 1)
>>> sorted(reduced_edges({(a, b), (b, c), (a, c)}, [a, b, c]), key=str)
[('START', ('a', 1)), (('a', 1), ('b', 1)), (('b', 1), ('c', 1)), (('c', 1), 'END')]
>>> edge_scores({(a, b)}, [a, b, c], {("START", a), (a, b), (b, "END"), ("START", c), (c, "END")}).f1
1.0
"""

from __future__ import annotations

from collections.abc import Collection, Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from supportive.errors import LearningError
from supportive.learning.precedence import Pair, PrecedenceScore, precedence_scores
from supportive.tasks.htn import Leaf

if TYPE_CHECKING:  # imported where used: networkx is a fifth of every command's start-up
    import networkx as nx

__all__ = [
    "EDGE_ERRORS",
    "END_NODE",
    "PEERS",
    "START_NODE",
    "EdgeComparison",
    "GraphEdge",
    "compare_edges",
    "edge_errors",
    "edge_scores",
    "reduced_edges",
]

START_NODE = "START"
END_NODE = "END"

GraphEdge = tuple[Leaf | str, Leaf | str]
"""An edge ``(earlier, later)`` between steps (leaves) or the ``START``/``END`` terminals."""

PEERS: dict[str, dict[str, float]] = {
    "DO (Seminara et al. 2024)": {"full": 0.878, "5-shot": 0.837},
    "Count-Based (ibid.)": {"full": 0.606},
    "MSG² (ibid.)": {"full": 0.711},
}
"""Task-graph F1 on CaptainCook4D published in *Differentiable Task Graph Learning* (Table 1), by setting."""


EDGE_ERRORS = (
    "false: steps the published graph leaves unordered",
    "false: a shortcut of published orders",
    "false: against a published order",
    "false: from START or to END",
    "missed: reduced away by a learned order through other steps",
    "missed: an order not learned",
    "missed: from START or to END",
)
"""The kinds of wrong edge :func:`edge_errors` counts: the learned graph's edges the published one lacks (by
how the published graph relates their two steps), then the published edges the learned graph lacks (by
whether the learned relation orders their two steps at all)."""


def reduced_edges(pairs: Iterable[Pair], steps: Collection[Leaf]) -> frozenset[GraphEdge]:
    """The relation ``pairs`` over ``steps`` as the protocol's graph: transitively reduced, with ``START``
    before every step nothing precedes and ``END`` after every step nothing follows. Pairs naming a step
    outside ``steps`` are left out (the published graph cannot judge them).

    Raises:
        LearningError: when the relation has a cycle (it is then no precedence relation).
    """
    import networkx as nx  # here: networkx is a fifth of every command's start-up

    graph = _step_graph(pairs, steps)
    if not nx.is_directed_acyclic_graph(graph):
        raise LearningError("the learned precedences have a cycle: no task graph")
    reduced = nx.transitive_reduction(graph)
    edges: set[GraphEdge] = set(reduced.edges())
    for step in steps:
        if reduced.in_degree(step) == 0:
            edges.add((START_NODE, step))
        if reduced.out_degree(step) == 0:
            edges.add((step, END_NODE))
    return frozenset(edges)


def edge_scores(pairs: Iterable[Pair], steps: Collection[Leaf], truth: Iterable[GraphEdge]) -> PrecedenceScore:
    """Precision, recall and F1 of the learned relation ``pairs`` over ``steps`` against the published graph
    ``truth`` (edges with their ``START``/``END`` ones), by the protocol of the module docstring."""
    return precedence_scores(reduced_edges(pairs, steps), truth)


def edge_errors(pairs: Iterable[Pair], steps: Collection[Leaf], truth: Iterable[GraphEdge]) -> dict[str, int]:
    """Where the learned relation ``pairs`` over ``steps`` and the published graph ``truth`` differ, edge by
    edge after the protocol's reduction, counted by :data:`EDGE_ERRORS` kind (every kind, 0 included).

    A false edge between two steps is read against the published graph's orders (its transitive closure):
    the graph leaves them unordered (an order the recordings kept that the recipe does not ask for), orders
    them the same way through other steps (a shortcut), or the other way. A missed edge is one the learned
    relation orders too but through a step it puts between them (reduced away), or does not order.

    >>> a, b, c = ("a", 1), ("b", 1), ("c", 1)
    >>> truth = {("START", a), ("START", b), (a, c), (b, c), (c, "END")}
    >>> errors = edge_errors({(a, b), (b, c)}, [a, b, c], truth)  # a before b: a habit, not in the recipe
    >>> {kind: n for kind, n in errors.items() if n}
    {'false: steps the published graph leaves unordered': 1, 'missed: reduced away by a learned order through other steps': 1, 'missed: from START or to END': 1}
    """
    relation = set(pairs)
    return _errors(reduced_edges(relation, steps), relation, steps, set(truth))


@dataclass(frozen=True)
class EdgeComparison:
    """A learned relation against a published graph: :func:`edge_scores` and :func:`edge_errors` of it."""

    score: PrecedenceScore
    errors: dict[str, int]


def compare_edges(pairs: Iterable[Pair], steps: Collection[Leaf], truth: Iterable[GraphEdge]) -> EdgeComparison:
    """:func:`edge_scores` and :func:`edge_errors` of the learned relation ``pairs`` over ``steps`` against
    ``truth``, the relation reduced once for both."""
    relation, published = set(pairs), set(truth)
    learned = reduced_edges(relation, steps)
    return EdgeComparison(precedence_scores(learned, published), _errors(learned, relation, steps, published))


def _errors(
    learned: frozenset[GraphEdge], pairs: set[Pair], steps: Collection[Leaf], truth: set[GraphEdge]
) -> dict[str, int]:
    """:func:`edge_errors` of ``pairs`` whose reduced graph is ``learned``."""
    import networkx as nx  # here: networkx is a fifth of every command's start-up

    learned_closure = nx.transitive_closure_dag(_step_graph(pairs, steps))
    published_closure = nx.transitive_closure_dag(_step_graph(truth, steps))
    counts = dict.fromkeys(EDGE_ERRORS, 0)
    for a, b in learned - truth:
        if isinstance(a, str) or isinstance(b, str):
            counts[EDGE_ERRORS[3]] += 1
        elif published_closure.has_edge(a, b):
            counts[EDGE_ERRORS[1]] += 1
        elif published_closure.has_edge(b, a):
            counts[EDGE_ERRORS[2]] += 1
        else:
            counts[EDGE_ERRORS[0]] += 1
    for a, b in truth - learned:
        if isinstance(a, str) or isinstance(b, str):
            counts[EDGE_ERRORS[6]] += 1
        elif learned_closure.has_edge(a, b):
            counts[EDGE_ERRORS[4]] += 1
        else:
            counts[EDGE_ERRORS[5]] += 1
    return counts


def _step_graph(pairs: Iterable[tuple[Leaf | str, Leaf | str]], steps: Collection[Leaf]) -> nx.DiGraph[Leaf]:
    """``pairs`` as a graph over ``steps`` (pairs naming anything else, ``START`` and ``END`` included, left
    out)."""
    import networkx as nx  # here: networkx is a fifth of every command's start-up

    graph: nx.DiGraph[Leaf] = nx.DiGraph()
    graph.add_nodes_from(steps)
    graph.add_edges_from((a, b) for a, b in pairs if a in graph and b in graph)
    return graph
