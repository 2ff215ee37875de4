"""Names for learned subtasks: the ground truth's name when the leaves match one, else a short description."""

from __future__ import annotations

from collections.abc import Mapping

from supportive.tasks.htn import ActionNode, ChainNode, Leaf, Node, shape, with_children

__all__ = ["full_name", "known_names", "named"]


def known_names(structure: Node | None) -> dict[frozenset[Leaf], str]:
    """Leaf set -> name, for every named node of a ground-truth structure."""
    names: dict[frozenset[Leaf], str] = {}
    if structure is None or isinstance(structure, ActionNode):
        return names
    if structure.name:
        names[frozenset(structure.leaves)] = structure.name
    for child in structure.children:
        names.update(known_names(child))
    return names


def named(node: Node, known: Mapping[frozenset[Leaf], str] | None = None) -> Node:
    """A copy of ``node`` in which every chain and clique has a name.

    A run of a chain's children whose leaves are a known subtask becomes that subtask, a chain of its own
    (a chain in a chain means the same order, so learning merges them; the name brings it back).

    >>> from supportive.tasks.htn import CliqueNode
    >>> named(ChainNode((ActionNode("knife"), CliqueNode((ActionNode("carrots"), ActionNode("celery")))))).name
    'knife → {carrots, celery}'
    """
    known = known or {}
    if isinstance(node, ActionNode):
        return node
    if isinstance(node, ChainNode) and known:
        node = _nest_known_runs(node, known)
    children = tuple(named(child, known) for child in node.children)
    name = node.name or (known.get(frozenset(node.leaves)) if known else None) or _describe(node.kind, children)
    return with_children(node, children, name=name)


def _nest_known_runs(chain: ChainNode, known: Mapping[frozenset[Leaf], str]) -> ChainNode:
    """``chain`` with each run of two or more (not all) children that holds exactly a known subtask's leaves
    made a named sub-chain, longest runs first."""
    sizes = sorted({len(leaves) for leaves in known}, reverse=True)
    children = list(chain.children)
    out: list[Node] = []
    i = 0
    while i < len(children):
        found = None
        for size in sizes:
            total, j = 0, i
            leaves: set[Leaf] = set()
            while j < len(children) and total < size:
                leaves.update(children[j].leaves)
                total += len(children[j].leaves)
                j += 1
            if total == size and j - i >= 2 and j - i < len(children) and frozenset(leaves) in known:
                found = (j, known[frozenset(leaves)])
                break
        if found is None:
            out.append(children[i])
            i += 1
            continue
        j, name = found
        out.append(ChainNode(tuple(children[i:j]), name))
        i = j
    return ChainNode(tuple(out), chain.name, chain.optional, chain.counts, chain.support) if len(out) != len(children) else chain


def _short(node: Node) -> str:
    if isinstance(node, ActionNode):
        return node.label
    name = node.name or ""
    return name if len(name) <= 28 else f"({name[:25]}…)"


def _describe(kind: str, children: tuple[Node, ...]) -> str:
    if kind == "clique" and len({shape(child, optional=False) for child in children}) == 1:
        return f"{len(children)} × {_short(children[0])}"  # instances of one repeated subtask
    parts = [_short(child) for child in children]
    if kind == "chain":
        return " → ".join(parts) if len(parts) <= 3 else f"{parts[0]} → … → {parts[-1]}"
    shown = ", ".join(parts[:3])
    return "{" + (shown if len(parts) <= 3 else f"{shown}, +{len(parts) - 3}") + "}"


def full_name(node: Node) -> str | None:
    """The node's name with nothing cut: a name :func:`named` made up (which shortens long chains and long
    names with "…" for people to read) is spelled out whole — every child, chains with " → ", cliques in
    braces; any other name as it is (what JSON exports write: a program reading them gets every part).

    >>> from supportive.tasks.htn import CliqueNode
    >>> chain = named(ChainNode(tuple(ActionNode(a) for a in "abcd")))
    >>> chain.name, full_name(chain)
    ('a → … → d', 'a → b → c → d')
    >>> full_name(named(CliqueNode(tuple(ActionNode(a) for a in "abcde"))))
    '{a, b, c, d, e}'
    """
    if isinstance(node, ActionNode):
        return node.label
    if node.name is None or node.name != _describe(node.kind, node.children):
        return node.name
    parts = [_spelled(child) for child in node.children]
    if node.kind == "clique" and len({shape(child, optional=False) for child in node.children}) == 1:
        return f"{len(parts)} × {parts[0]}"
    return " → ".join(parts) if node.kind == "chain" else "{" + ", ".join(parts) + "}"


def _spelled(node: Node) -> str:
    """A child as its parent's full name spells it: its own full name, or its parts when it has no name."""
    name = full_name(node)
    if name is not None or isinstance(node, ActionNode):
        return name or ""
    return full_name(with_children(node, node.children, name=_describe(node.kind, node.children))) or ""
