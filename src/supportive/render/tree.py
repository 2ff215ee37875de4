"""A learned HTN as a tree people read in a terminal (rich)."""

from __future__ import annotations

from collections.abc import Mapping

from rich.text import Text
from rich.tree import Tree

from supportive.render.terminal import plain, printable, terminal_console
from supportive.tasks.htn import HTN, ActionNode, Node

__all__ = ["htn_tree", "render_tree"]

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
    when the clique was inferred); optional parts say so; leaves show their action text."""
    texts = texts or {}
    label = plain(htn.task or "task", style="bold")
    if not htn.complete:
        label.append(f" (partial: {len(htn.roots)} top-level parts)", style="yellow")
    tree = Tree(label)
    for root in htn.roots:
        _add(tree, root, texts)
    return tree


def render_tree(htn: HTN, texts: Mapping[str, str] | None = None, *, width: int = 100) -> str:
    """The tree as plain text."""
    console = terminal_console(width=width, soft_wrap=False, record=True, color_system=None, force_terminal=False)
    with console.capture() as capture:
        console.print(htn_tree(htn, texts))
    return capture.get()
