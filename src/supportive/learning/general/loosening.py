"""The least loosening of a hierarchy that admits a step out of place: the lowest subtask holding the step,
flattened to a clique of its steps.

The slip search asks whether a step's slips are likelier by chance than the hierarchy learned without them
allows (:meth:`~supportive.learning.general.noise._Search._chance`): how many orders the tighter hierarchy
admits, against a looser one that admits the slips. The hierarchy learned with the slips kept in is one such
reference, but not always a fair one: kept in, a slipped step can make the learner read its neighbours
otherwise (three free steps of which two came in one order by chance, read as a subtask, loosen the whole
chain around them when the third is kept in), so that it admits far more orders than the slips need, and a
tighter hierarchy falling short of it looks improbable on clean data. :func:`loosened_for` gives the other
reference, the one the slips need: the tight hierarchy with, for each slip, only the lowest subtask around
the slipped step that must loosen for its demonstration to be admitted, flattened.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Iterator, Sequence

from supportive.tasks.htn import HTN
from supportive.tasks.nodes import ActionNode, CliqueNode, Leaf, Node, with_children

__all__ = ["flattened", "loosened_for"]


def flattened(node: Node) -> Node:
    """``node`` as a clique of its actions, performed in any order: an action is optional when it, ``node``
    or a subtask between them is, and the clique when ``node`` is. An action is itself.

    >>> from supportive.tasks.nodes import ChainNode
    >>> chain = ChainNode((ActionNode("a"), ChainNode((ActionNode("b"), ActionNode("c")), optional=True)))
    >>> [(leaf.action, leaf.optional) for leaf in flattened(chain).children]
    [('a', False), ('b', True), ('c', True)]
    """
    if isinstance(node, ActionNode):
        return node
    return CliqueNode(tuple(_actions(node, optional=False)), optional=node.optional)


def _actions(node: Node, *, optional: bool) -> Iterator[ActionNode]:
    """The actions under ``node``, depth first, each optional when it or a node above it (``optional``) is."""
    if isinstance(node, ActionNode):
        yield dataclasses.replace(node, optional=True) if optional and not node.optional else node
        return
    for child in node.children:
        yield from _actions(child, optional=optional or node.optional)


def loosened_for(htn: HTN, cases: Iterable[tuple[Sequence[Leaf], Leaf]]) -> HTN | None:
    """``htn`` loosened, case by case, just enough to admit each ``(demonstration, leaf)``: when the
    hierarchy so far does not admit the demonstration, the lowest subtask holding ``leaf`` whose flattening
    (:func:`flattened`) makes it admit it is flattened. None when for some case none does (not even the root
    holding the leaf: the demonstration breaks more than that root) or no root holds the leaf.
    """
    current = htn
    for demonstration, leaf in cases:
        if current.admits_leaves(demonstration):
            continue
        loosened = next(
            (
                candidate
                for candidate in _flattenings(current, leaf)
                if candidate.admits_leaves(demonstration)
            ),
            None,
        )
        if loosened is None:
            return None
        current = loosened
    return current


def _flattenings(htn: HTN, leaf: Leaf) -> Iterator[HTN]:
    """``htn`` with one subtask holding ``leaf`` flattened, the lowest first, up to its root."""
    for index, root in enumerate(htn.roots):
        path = _path(root, leaf)
        if path is None:
            continue
        for depth in range(len(path) - 1, -1, -1):
            roots = list(htn.roots)
            roots[index] = _replaced(path[: depth + 1], flattened(path[depth]))
            yield HTN(htn.task, tuple(roots), htn.top_level)
        return


def _path(node: Node, leaf: Leaf) -> list[Node] | None:
    """The internal nodes from ``node`` down to the parent of the action ``leaf``; None when ``node`` does not
    hold it."""
    if isinstance(node, ActionNode):
        return None
    for child in node.children:
        if isinstance(child, ActionNode):
            if child.leaf == leaf:
                return [node]
            continue
        below = _path(child, leaf)
        if below is not None:
            return [node, *below]
    return None


def _replaced(path: Sequence[Node], new: Node) -> Node:
    """The tree ``path[0]`` with the node ``path[-1]`` (reached along ``path``) replaced by ``new``."""
    if len(path) == 1:
        return new
    parent, child = path[0], path[1]
    assert not isinstance(parent, ActionNode)
    replaced = _replaced(path[1:], new)
    return with_children(parent, (replaced if c is child else c for c in parent.children))
