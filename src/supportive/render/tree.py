"""A learned HTN as a tree people read in a terminal (rich)."""

from __future__ import annotations

from collections.abc import Mapping

from rich.text import Text
from rich.tree import Tree

from supportive.render.terminal import plain, printable, terminal_console
from supportive.tasks.htn import HTN, ActionNode, Node

__all__ = ["MAX_ORDERS", "htn_tree", "render_tree", "top_level_orders"]

_KIND = {"chain": ("in order", "bold cyan"), "clique": ("any order", "bold magenta")}


def _add(parent: Tree, node: Node, texts: Mapping[str, str]) -> None:
    """Labels are rich Text, never markup: ids and names are the user's (see :mod:`supportive.render.terminal`)."""
    optional = Text("optional ", style="yellow") if node.optional else Text("")
    if isinstance(node, ActionNode):
        text = texts.get(node.action)
        label = Text.assemble(optional, plain(node.label))
        if text and text != node.action:
            label.append(f" — {printable(text)}", style="dim")
        parent.add(label)
        return
    label = Text.assemble(optional, _KIND[node.kind])
    if node.name:
        label.append(f" {printable(node.name)}")
    support = node.support
    if support is not None and not support.observed and node.kind == "clique":
        label.append(f" (inferred: {support.orders_seen} of {support.orders} orders seen)", style="dim")
    branch = parent.add(label)
    for child in node.children:
        _add(branch, child, texts)


def htn_tree(htn: HTN, texts: Mapping[str, str] | None = None) -> Tree:
    """A rich Tree: chains read "in order", cliques "any order" (with how many of their orders were seen,
    when the clique was inferred); optional parts say so; leaves show their action text. A partial hierarchy
    ends with the orders of its top-level parts it admits (up to :data:`MAX_ORDERS`, and how many in all)."""
    texts = texts or {}
    label = plain(htn.task or "task", style="bold")
    if not htn.complete:
        label.append(f" (partial: {len(htn.roots)} top-level parts)", style="yellow")
    tree = Tree(label)
    for root in htn.roots:
        _add(tree, root, texts)
    if not htn.complete and htn.top_level is not None:
        orders, total = top_level_orders(htn)
        seen = tree.add(
            Text(f"orders of these parts it admits ({total}):" if total != 1 else "the one order of these parts it admits:", style="yellow")
        )
        for order in orders:
            seen.add(plain(" → ".join(_part(htn.roots[i]) for i in order)))
        if total > len(orders):
            seen.add(Text(f"… and {total - len(orders)} more", style="dim"))
    return tree


MAX_ORDERS = 6
"""How many orders of a partial hierarchy's parts the tree lists (it says how many more there are)."""


def top_level_orders(htn: HTN, limit: int = MAX_ORDERS) -> tuple[list[tuple[int, ...]], int]:
    """The orders of a partial hierarchy's parts (root indices) that it admits — the task graph learned at the
    level where compaction stopped — at most ``limit`` of them, in the order of the roots, and how many there
    are in all.

    >>> from supportive.examples import load
    >>> from supportive.learning.learner import learn
    >>> orders, total = top_level_orders(learn(load("two-glasses")).htn_, limit=2)
    >>> orders, total
    ([(0, 1, 2, 3), (0, 1, 3, 2)], 6)
    """
    top = htn.top_level
    if top is None:
        return [(0,)] if htn.roots else [], int(bool(htn.roots))
    successors = top.successors()
    terminal = set(top.terminal)
    found: list[tuple[int, ...]] = []

    def walk(state: int, path: tuple[int, ...]) -> None:
        if len(found) >= limit:
            return
        if state in terminal:
            found.append(path)
        for root, following in sorted(successors.get(state, {}).items()):
            walk(following, (*path, root))

    for start in sorted(top.initial):
        walk(start, ())
    return found[:limit], top.count_orderings()


def _part(node: Node) -> str:
    """A top-level part as the list of orders names it: its action, its name, or its first and last action."""
    if isinstance(node, ActionNode):
        return node.label
    if node.name:
        return node.name
    leaves = [leaf for leaf in node.leaves]
    return f"{leaves[0][0]} … {leaves[-1][0]}" if len(leaves) > 1 else leaves[0][0]


def render_tree(htn: HTN, texts: Mapping[str, str] | None = None, *, width: int = 100) -> str:
    """The tree as plain text."""
    console = terminal_console(width=width, soft_wrap=False, record=True, color_system=None, force_terminal=False)
    with console.capture() as capture:
        console.print(htn_tree(htn, texts))
    return capture.get()
