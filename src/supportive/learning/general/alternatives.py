"""The ``general`` learner's alternative: one complete hierarchy that admits every execution a partial one does.

A partial hierarchy's top level (:class:`~supportive.tasks.htn.TopLevel`) admits orders of its roots that no
chain/clique tree admits exactly (two chains interleaved, say). Its alternative reads the top level as a
series of **blocks**: root ``s`` *may precede* root ``r`` when some execution the top level admits does ``s``
before ``r``; the roots that may precede one another both ways (directly or through others) form one block
(a strongly connected component of that relation), and every root of an earlier block precedes every root of
a later one in every execution. The alternative is the chain of the blocks in that order, each block a clique
of its roots (a block of one root is that root; each root keeps its own structure, and is ``optional`` when
it is, or when some execution of the top level leaves it out).

It admits every execution the partial hierarchy admits: each root is performed without interruption in both,
the blocks come in the order every admitted execution keeps, and a clique admits every order of its members.
It admits more where the top level orders roots within a block (the price of a tree): the strict learner's
alternatives are restrictions of the known executions, this one is a generalisation of what was learned.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import TYPE_CHECKING

from supportive.tasks.htn import ChainNode, CliqueNode, Node, TopLevel

if TYPE_CHECKING:  # imported where used: networkx is a fifth of every command's start-up
    import networkx as nx

__all__ = ["complete_alternative", "may_precede"]


def complete_alternative(roots: Sequence[Node], top_level: TopLevel) -> Node:
    """The chain of blocks of ``roots`` under ``top_level`` (see the module docstring).

    >>> from supportive.tasks.htn import ActionNode
    >>> a, b, c = ActionNode("a"), ActionNode("b"), ActionNode("c")
    >>> either = TopLevel((0,), (3,), ((0, 0, 1), (0, 1, 2), (1, 1, 3), (2, 0, 3)))  # a b, or b a
    >>> complete_alternative((a, b), either).kind
    'clique'
    >>> then_c = TopLevel((0,), (4,), ((0, 0, 1), (0, 1, 2), (1, 1, 3), (2, 0, 3), (3, 2, 4)))
    >>> [child.kind for child in complete_alternative((a, b, c), then_c).children]
    ['clique', 'action']
    """
    import networkx as nx  # here: networkx is a fifth of every command's start-up

    graph: nx.DiGraph[int] = nx.DiGraph()
    graph.add_nodes_from(range(len(roots)))
    graph.add_edges_from((s, r) for s, later in enumerate(may_precede(top_level, len(roots))) for r in later)
    required = top_level.required_roots(len(roots))
    roots = [root if root.optional or i in required else replace(root, optional=True) for i, root in enumerate(roots)]
    blocks = nx.condensation(graph)
    members: dict[int, list[int]] = {b: sorted(blocks.nodes[b]["members"]) for b in blocks.nodes}
    order = nx.lexicographical_topological_sort(blocks, key=lambda b: members[b][0])
    children: list[Node] = []
    for block in order:
        nodes = [roots[i] for i in members[block]]
        single = nodes[0] if len(nodes) == 1 else CliqueNode(tuple(nodes))
        if isinstance(single, ChainNode) and not single.optional:
            children.extend(single.children)  # a chain in a chain means the same order
        else:
            children.append(single)
    return children[0] if len(children) == 1 else ChainNode(tuple(children))


def may_precede(top_level: TopLevel, n_roots: int) -> list[set[int]]:
    """For each root ``s``, the roots ``r != s`` some execution of ``top_level`` performs after ``s``
    (a root performed after ``s`` on some path from a state an ``s``-edge enters)."""
    out = top_level.successors()
    ahead: dict[int, int] = {}  # state -> roots (bits) on some path from it
    for state in top_level.successors_first():
        bits = 0
        for root, dst in out.get(state, {}).items():
            bits |= 1 << root | ahead[dst]
        ahead[state] = bits
    after: list[int] = [0] * n_roots
    for moves in out.values():
        for root, dst in moves.items():
            after[root] |= ahead[dst]
    return [{r for r in range(n_roots) if bits >> r & 1 and r != s} for s, bits in enumerate(after)]
