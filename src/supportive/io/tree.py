"""A learned HTN as a tree people read in a terminal (rich)."""

from __future__ import annotations

from collections.abc import Mapping

from rich.console import Console
from rich.tree import Tree

from supportive.tasks.htn import HTN, ActionNode, Node

__all__ = ["htn_tree", "render_tree"]

_KIND = {"chain": "[bold cyan]in order[/]", "clique": "[bold magenta]any order[/]"}


def _add(parent: Tree, node: Node, texts: Mapping[str, str]) -> None:
    optional = "[yellow]optional[/] " if node.optional else ""
    if isinstance(node, ActionNode):
        text = texts.get(node.action)
        parent.add(f"{optional}{node.label}" + (f" [dim]— {text}[/]" if text and text != node.action else ""))
        return
    support = node.support
    inferred = (
        f" [dim](inferred: {support.orders_seen} of {support.orders} orders seen)[/]"
        if support is not None and not support.observed and node.kind == "clique"
        else ""
    )
    branch = parent.add(f"{optional}{_KIND[node.kind]} {node.name or ''}".rstrip() + inferred)
    for child in node.children:
        _add(branch, child, texts)


def htn_tree(htn: HTN, texts: Mapping[str, str] | None = None) -> Tree:
    """A rich Tree: chains read "in order", cliques "any order" (with how many of their orders were seen,
    when the clique was inferred); optional parts say so; leaves show their action text."""
    texts = texts or {}
    if htn.complete:
        label = f"[bold]{htn.task or 'task'}[/]"
    else:
        label = f"[bold]{htn.task or 'task'}[/] [yellow](partial: {len(htn.roots)} top-level parts)[/]"
    tree = Tree(label)
    for root in htn.roots:
        _add(tree, root, texts)
    return tree


def render_tree(htn: HTN, texts: Mapping[str, str] | None = None, *, width: int = 100) -> str:
    """The tree as plain text."""
    console = Console(width=width, record=True, color_system=None, force_terminal=False)
    with console.capture() as capture:
        console.print(htn_tree(htn, texts))
    return capture.get()
