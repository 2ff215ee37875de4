"""A learned HTN as Graphviz DOT."""

from __future__ import annotations

import itertools
import json

from supportive.tasks.htn import HTN, ActionNode, ChainNode, Node

__all__ = ["htn_to_dot"]


def _quote(text: str) -> str:
    return json.dumps(text, ensure_ascii=False)


def htn_to_dot(htn: HTN) -> str:
    """DOT text: boxes for chains (children linked left to right by dashed "then" edges), hexagons for
    cliques, ovals for actions, optional nodes drawn dashed; a partial hierarchy hangs its roots under one
    task node."""
    lines = ["digraph htn {", "  rankdir=TB;", '  node [fontname="Helvetica"];']
    counter = iter(range(1 << 30))

    def emit(node: Node) -> str:
        name = f"n{next(counter)}"
        style = ", style=dashed" if node.optional else ""
        if isinstance(node, ActionNode):
            label = node.label + (" (optional)" if node.optional else "")
            lines.append(f"  {name} [label={_quote(label)}, shape=ellipse{style}];")
            return name
        shape = "box" if isinstance(node, ChainNode) else "hexagon"
        title = ("in order" if isinstance(node, ChainNode) else "any order") + (
            f"\n{node.name}" if node.name else ""
        ) + ("\n(optional)" if node.optional else "")
        lines.append(f"  {name} [label={_quote(title)}, shape={shape}{style}];")
        children = [emit(child) for child in node.children]
        for child in children:
            lines.append(f"  {name} -> {child};")
        if isinstance(node, ChainNode):
            for a, b in itertools.pairwise(children):
                lines.append(f'  {a} -> {b} [style=dashed, constraint=false, label="then"];')
        return name

    if htn.complete:
        emit(htn.roots[0])
    else:
        lines.append(f"  task [label={_quote((htn.task or 'task') + ' (partial)')}, shape=doubleoctagon];")
        for root in htn.roots:
            lines.append(f"  task -> {emit(root)};")
    lines.append("}")
    return "\n".join(lines) + "\n"
