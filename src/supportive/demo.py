"""``supportive demo``: learn the IKEA chair from its demonstrations and say what the data did and did not pin
down, against the ground truth in the task file."""

from __future__ import annotations

import math
from dataclasses import dataclass

from rich.console import Console
from rich.panel import Panel
from rich.table import Table

from supportive import examples
from supportive.io.tree import htn_tree
from supportive.learning.learner import HTNLearner, learn
from supportive.learning.precedence import implied_precedences
from supportive.tasks.htn import (
    HTN,
    ActionNode,
    ChainNode,
    CliqueNode,
    Leaf,
    canonical,
    count_orderings,
    internal_nodes,
    to_leaves,
)
from supportive.tasks.spec import TaskSpec

__all__ = ["SubtaskFinding", "run_demo", "subtask_findings"]


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


def _root_names(htn: HTN) -> dict[Leaf, str]:
    names = {}
    for root in htn.roots:
        label = root.label if isinstance(root, ActionNode) else (root.name or root.kind)
        for leaf in root.leaves:
            names[leaf] = label
    return names


def run_demo(console: Console, example: str = "ikea-chair") -> HTNLearner:
    """Print the demo to ``console`` and return the fitted learner."""
    spec = examples.load(example)
    learner = learn(spec)
    htn, stats = learner.htn_, learner.stats_
    people = sorted({d.agent for d in spec.demonstrations if d.agent})
    console.rule(f"[bold]supportive demo[/] — learning {spec.name} from its demonstrations")
    console.print(
        f"{len(spec.demonstrations)} demonstrations by {len(people)} people ({', '.join(people)}), "
        f"{stats.actions} primitive actions. The robot builds the environment-space task graph, its conjugate "
        "(Algorithm 1), and compacts cliques and chains into a hierarchy (Algorithm 2).\n"
    )
    console.print(htn_tree(htn, spec.texts()))
    valid = count_orderings(spec.structure) if spec.structure is not None else None
    table = Table(title="What the robot has seen", show_header=False, box=None)
    table.add_row(
        "known valid orders", f"{stats.task_graph['paths']:,}" + (f" of {valid:,}" if valid else "")
    )
    table.add_row(
        "task graph", f"{stats.task_graph['states']} states, {stats.task_graph['edges']} transitions"
    )
    table.add_row("conjugate task graph", f"{stats.ctg['vertices']} vertices, {stats.ctg['edges']} edges")
    table.add_row(
        "hierarchy",
        f"{stats.htn['nodes']} nodes, {len(htn.roots)} top-level part(s), "
        f"mean depth of an action {stats.htn['mean_action_depth']:.2f}",
    )
    table.add_row("learning time", f"{stats.seconds * 1000:.1f} ms")
    console.print(table)

    findings = subtask_findings(spec, htn)
    if findings:
        console.print("\n[bold]What the demonstrations pinned down[/] (against the file's ground truth)")
        for f in findings:
            mark = "[green]✓[/]" if f.learned else "[red]✗[/]"
            how = (
                "in order"
                if f.kind == "chain"
                else f"any order, {f.orders_seen} of {f.orders_valid} orders seen"
            )
            console.print(f"  {mark} {f.name} ({how})")
    if not htn.complete and htn.top_level is not None:
        tops = htn.top_level.count_orderings()
        console.print(
            f"\n[bold]Still open:[/] {len(htn.roots)} top-level parts, seen in {tops} of their "
            f"{math.factorial(len(htn.roots)):,} conceivable orders."
        )
        if spec.structure is not None:
            truth = implied_precedences(HTN(spec.name, (spec.structure,)))
            wrong = implied_precedences(htn) - truth
            names = _root_names(htn)
            beliefs = sorted({(names[a], names[b]) for a, b in wrong if names[a] != names[b]})
            if beliefs:
                console.print(
                    "  The robot still believes these must come first, though the true task does not require it:"
                )
                for first, then in beliefs[:6]:
                    console.print(f"    • {first} before {then}")
                if len(beliefs) > 6:
                    console.print(f"    • … and {len(beliefs) - 6} more")
            missing = [f for f in findings if not f.learned and f.kind == "clique"]
            if missing:
                console.print(
                    "  A few more demonstrations showing "
                    + ", ".join(f"{f.name.lower()}" for f in missing)
                    + " in other orders would settle it."
                )
    if htn.alternatives:
        console.print(f"\n[bold]Alternative readings[/] ({len(htn.alternatives)}), best first:")
        for alternative in htn.alternatives[:3]:
            console.print(htn_tree(alternative, spec.texts()))
    console.print(Panel.fit("Try it on your own task:  supportive learn my-task.yaml --format json"))
    return learner
