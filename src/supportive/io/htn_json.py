"""A learned HTN as JSON (the format of ``supportive learn --format json``), and back."""

from __future__ import annotations

import math
from typing import Any

from supportive.errors import TaskFileError
from supportive.tasks.htn import HTN, ActionNode, ChainNode, CliqueNode, Counts, Node, Support, TopLevel
from supportive.tasks.naming import full_name

__all__ = ["JSON_EXACT", "htn_from_dict", "htn_to_dict", "json_count", "node_from_dict", "node_to_dict"]

JSON_EXACT = 2**53
"""Counts up to this are written as JSON integers (every JSON reader holds them exactly)."""


def json_count(count: int) -> int | str:
    """A count as JSON holds it: the integer up to :data:`JSON_EXACT`, beyond it a string in scientific
    notation with six significant digits (a valid task may admit more than 10^4300 orderings, more digits
    than Python converts to text, and more than any JSON reader holds as a number).

    >>> json_count(720), json_count(10**4301 * 3)
    (720, '3.00000e+4301')
    """
    if count <= JSON_EXACT:
        return count
    exponent = int(math.log10(count))
    leading = count // 10 ** max(exponent - 5, 0)
    while leading >= 10**6:  # log10 of a huge integer can round up to the next power
        exponent += 1
        leading = count // 10 ** (exponent - 5)
    while leading < 10**5:
        exponent -= 1
        leading = count // 10 ** (exponent - 5)
    return f"{leading / 10**5:.5f}e+{exponent}"


def _json_numbers(value: Any) -> Any:
    if isinstance(value, dict):
        return {key: _json_numbers(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_json_numbers(item) for item in value]
    if isinstance(value, int) and not isinstance(value, bool):
        return json_count(value)
    return value


def node_to_dict(node: Node) -> dict[str, Any]:
    """``{"kind": "action", "action": id}`` (plus ``occurrence`` for a repeated action) or
    ``{"kind": "chain"|"clique", "name": …, "children": […]}``; any node may add ``"optional": true``,
    ``"counts"`` (:meth:`Counts.as_dict`) and ``"support"`` (:meth:`Support.as_dict`)."""
    if isinstance(node, ActionNode):
        data: dict[str, Any] = {"kind": "action", "action": node.action}
        if node.occurrence != 1:
            data["occurrence"] = node.occurrence
    else:
        data = {"kind": node.kind, "name": full_name(node), "children": [node_to_dict(c) for c in node.children]}
    if node.optional:
        data["optional"] = True
    if node.counts is not None:
        data["counts"] = node.counts.as_dict()
    if node.support is not None:
        data["support"] = node.support.as_dict()
    return data


def _counts_from(data: Any, place: str) -> Counts | None:
    if data is None:
        return None
    try:
        return Counts(
            performed=int(data.get("performed", 0)),
            skipped=int(data.get("skipped", 0)),
            first=tuple(int(x) for x in data.get("first", ())),
            after=tuple(tuple(int(x) for x in row) for row in data.get("after", ())),
        )
    except (AttributeError, TypeError, ValueError):
        raise TaskFileError("counts need integer 'performed', 'skipped', 'first' and 'after'", place=place) from None


def _support_from(data: Any, place: str) -> Support | None:
    if data is None:
        return None
    try:
        return Support(
            int(data["demonstrations"]), int(data["orders_seen"]), int(data["orders"]), data["observed"] == "full"
        )
    except (KeyError, TypeError, ValueError):
        raise TaskFileError(
            "support needs 'demonstrations', 'orders_seen', 'orders' and 'observed' (full or inferred)",
            place=place,
        ) from None


def node_from_dict(data: Any, place: str = "node") -> Node:
    """Inverse of :func:`node_to_dict`.

    Raises:
        TaskFileError: when ``data`` is not a node.
    """
    if not isinstance(data, dict) or data.get("kind") not in ("action", "chain", "clique"):
        raise TaskFileError("expected a node with kind 'action', 'chain' or 'clique'", place=place)
    optional = data.get("optional", False)
    if not isinstance(optional, bool):
        raise TaskFileError("'optional' must be true or false", place=place)
    counts = _counts_from(data.get("counts"), f"{place}.counts")
    support = _support_from(data.get("support"), f"{place}.support")
    if data["kind"] == "action":
        if not isinstance(data.get("action"), str):
            raise TaskFileError("an action node needs an 'action' id", place=place)
        return ActionNode(data["action"], int(data.get("occurrence", 1)), optional, counts, support)
    children = data.get("children")
    if not isinstance(children, list) or not children:
        raise TaskFileError("a chain or clique needs a non-empty 'children' list", place=place)
    nodes = tuple(node_from_dict(c, f"{place}.children[{i}]") for i, c in enumerate(children))
    kind = ChainNode if data["kind"] == "chain" else CliqueNode
    return kind(nodes, data.get("name"), optional, counts, support)


def htn_to_dict(htn: HTN, stats: dict[str, Any] | None = None) -> dict[str, Any]:
    """The JSON form of docs/exports.md; ``top_level`` is added for a partial hierarchy (how its roots may follow
    one another: ``edges`` are ``[from state, root index, to state]``; ``free``, when any, the roots whose
    passing unlocks nothing, :attr:`~supportive.tasks.htn.TopLevel.free`); counts in ``stats`` beyond 2^53 are
    strings (:func:`json_count`)."""
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
        if top.counts is not None:
            data["top_level"]["counts"] = top.counts.as_dict()
        if top.free:
            data["top_level"]["free"] = sorted(top.free)
    data["alternatives"] = [{"roots": [node_to_dict(r) for r in alt.roots]} for alt in htn.alternatives]
    if stats is not None:
        data["stats"] = _json_numbers(stats)
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
            top_level = TopLevel(
                tuple(map(int, top["initial"])),
                tuple(map(int, top["terminal"])),
                edges,
                _counts_from(top.get("counts"), "top_level.counts"),
                frozenset(map(int, top.get("free", []))),
            )
        except (KeyError, TypeError, ValueError):
            raise TaskFileError(
                "top_level needs 'initial', 'terminal' and 'edges' of [from, root, to] (and 'free', if given, "
                "a list of root indices)",
                place="top_level",
            ) from None
    alternatives = tuple(
        HTN(data.get("task", ""), tuple(node_from_dict(r, f"alternatives[{i}]") for r in alt["roots"]))
        for i, alt in enumerate(data.get("alternatives", []))
    )
    return HTN(data.get("task", ""), roots, top_level, alternatives)
