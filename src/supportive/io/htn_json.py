"""A learned HTN as JSON (the format of ``supportive learn --format json``), and back."""

from __future__ import annotations

from typing import Any

from supportive.errors import TaskFileError
from supportive.tasks.htn import HTN, ActionNode, ChainNode, CliqueNode, Node, TopLevel

__all__ = ["htn_from_dict", "htn_to_dict", "node_from_dict", "node_to_dict"]


def node_to_dict(node: Node) -> dict[str, Any]:
    """``{"kind": "action", "action": id}`` (plus ``occurrence`` for a repeated action) or
    ``{"kind": "chain"|"clique", "name": …, "children": […]}``."""
    if isinstance(node, ActionNode):
        data: dict[str, Any] = {"kind": "action", "action": node.action}
        if node.occurrence != 1:
            data["occurrence"] = node.occurrence
        return data
    return {"kind": node.kind, "name": node.name, "children": [node_to_dict(c) for c in node.children]}


def node_from_dict(data: Any, place: str = "node") -> Node:
    """Inverse of :func:`node_to_dict`.

    Raises:
        TaskFileError: when ``data`` is not a node.
    """
    if not isinstance(data, dict) or data.get("kind") not in ("action", "chain", "clique"):
        raise TaskFileError("expected a node with kind 'action', 'chain' or 'clique'", place=place)
    if data["kind"] == "action":
        if not isinstance(data.get("action"), str):
            raise TaskFileError("an action node needs an 'action' id", place=place)
        return ActionNode(data["action"], int(data.get("occurrence", 1)))
    children = data.get("children")
    if not isinstance(children, list) or not children:
        raise TaskFileError("a chain or clique needs a non-empty 'children' list", place=place)
    nodes = tuple(node_from_dict(c, f"{place}.children[{i}]") for i, c in enumerate(children))
    return (
        ChainNode(nodes, data.get("name")) if data["kind"] == "chain" else CliqueNode(nodes, data.get("name"))
    )


def htn_to_dict(htn: HTN, stats: dict[str, Any] | None = None) -> dict[str, Any]:
    """The JSON form of docs/exports.md; ``top_level`` is added for a partial hierarchy (how its roots may follow
    one another: ``edges`` are ``[from state, root index, to state]``)."""
    data: dict[str, Any] = {
        "task": htn.task,
        "complete": htn.complete,
        "roots": [node_to_dict(r) for r in htn.roots],
    }
    if htn.top_level is not None:
        top = htn.top_level
        data["top_level"] = {
            "initial": list(top.initial),
            "terminal": list(top.terminal),
            "edges": [list(e) for e in top.edges],
        }
    data["alternatives"] = [{"roots": [node_to_dict(r) for r in alt.roots]} for alt in htn.alternatives]
    if stats is not None:
        data["stats"] = stats
    return data


def htn_from_dict(data: Any) -> HTN:
    """Inverse of :func:`htn_to_dict` (``stats`` are ignored)."""
    if not isinstance(data, dict) or not isinstance(data.get("roots"), list):
        raise TaskFileError("expected an HTN object with a 'roots' list")
    roots = tuple(node_from_dict(r, f"roots[{i}]") for i, r in enumerate(data["roots"]))
    top = data.get("top_level")
    top_level = None
    if top is not None:
        try:
            edges = tuple((int(src), int(root), int(dst)) for src, root, dst in top["edges"])
            top_level = TopLevel(tuple(map(int, top["initial"])), tuple(map(int, top["terminal"])), edges)
        except (KeyError, TypeError, ValueError):
            raise TaskFileError(
                "top_level needs 'initial', 'terminal' and 'edges' of [from, root, to]", place="top_level"
            ) from None
    alternatives = tuple(
        HTN(data.get("task", ""), tuple(node_from_dict(r, f"alternatives[{i}]") for r in alt["roots"]))
        for i, alt in enumerate(data.get("alternatives", []))
    )
    return HTN(data.get("task", ""), roots, top_level, alternatives)
