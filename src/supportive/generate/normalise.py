"""Bring a chain/clique structure to normal form, and check that it is in it."""

from __future__ import annotations

from supportive.errors import GenerationError
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, Node

__all__ = ["is_normalised", "normalise"]


def normalise(node: Node) -> Node:
    """The same hierarchy in normal form: no chain or clique with fewer than two children, no chain directly
    inside a chain.

    A one-child node is replaced by its child and a chain's chain children are spliced into it (both change
    nothing about the orderings admitted). A clique inside a clique is kept: it forbids interleaving the inner
    clique's children with the outer clique's other children, so it means something. Names are kept, except
    those of the nodes that disappear.

    Raises:
        GenerationError: when a chain or clique has no children.

    >>> a, b, c = ActionNode("a"), ActionNode("b"), ActionNode("c")
    >>> flat = normalise(ChainNode((a, ChainNode((b, CliqueNode((c,)))))))
    >>> flat == ChainNode((a, b, c))
    True
    """
    if isinstance(node, ActionNode):
        return node
    children: list[Node] = []
    for child in node.children:
        child = normalise(child)
        if isinstance(node, ChainNode) and isinstance(child, ChainNode):
            children.extend(child.children)
        else:
            children.append(child)
    if not children:
        raise GenerationError(f"a {node.kind} with no children cannot be normalised")
    if len(children) == 1:
        return children[0]
    if isinstance(node, ChainNode):
        return ChainNode(tuple(children), node.name)
    return CliqueNode(tuple(children), node.name)


def is_normalised(node: Node) -> bool:
    """True when every chain and clique under ``node`` has two or more children and no chain is a chain's child.

    >>> is_normalised(ChainNode((ActionNode("a"), ChainNode((ActionNode("b"), ActionNode("c"))))))
    False
    """
    if isinstance(node, ActionNode):
        return True
    if len(node.children) < 2:
        return False
    if isinstance(node, ChainNode) and any(isinstance(child, ChainNode) for child in node.children):
        return False
    return all(is_normalised(child) for child in node.children)
