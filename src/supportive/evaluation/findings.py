"""What a learned hierarchy got right against a task's ground truth: for every subtask of the true structure,
whether it was learned exactly and how many orders of its parts the demonstrations showed."""

from __future__ import annotations

import math
from dataclasses import dataclass

from supportive.tasks.htn import HTN, ChainNode, CliqueNode, Leaf, canonical, internal_nodes, to_leaves
from supportive.tasks.spec import TaskSpec

__all__ = ["SubtaskFinding", "subtask_findings"]


@dataclass(frozen=True)
class SubtaskFinding:
    """Whether one ground-truth subtask was learned, and how many orders of its parts the data showed."""

    name: str
    kind: str
    learned: bool
    orders_seen: int
    orders_valid: int


def _child_orders(node: ChainNode | CliqueNode, demonstrations: list[tuple[Leaf, ...]]) -> int:
    """Distinct orders in which the demonstrations performed ``node``'s children (by first leaf)."""
    owner = {leaf: i for i, child in enumerate(node.children) for leaf in child.leaves}
    orders = set()
    for demo in demonstrations:
        order: list[int] = []
        for leaf in demo:
            child = owner.get(leaf)
            if child is not None and child not in order:
                order.append(child)
        orders.add(tuple(order))
    return len(orders)


def subtask_findings(spec: TaskSpec, htn: HTN) -> list[SubtaskFinding]:
    """For every subtask of the spec's ground-truth structure: learned exactly or not, and the evidence."""
    if spec.structure is None:
        return []
    learned = {canonical(node) for root in (htn.roots) for node in internal_nodes(root)}
    demos = [to_leaves(d) for d in spec.action_sequences()]
    findings = []
    for node in internal_nodes(spec.structure):
        valid = math.factorial(len(node.children)) if isinstance(node, CliqueNode) else 1
        findings.append(
            SubtaskFinding(
                name=node.name or "(unnamed)",
                kind=node.kind,
                learned=canonical(node) in learned,
                orders_seen=_child_orders(node, demos),
                orders_valid=valid,
            )
        )
    return findings
