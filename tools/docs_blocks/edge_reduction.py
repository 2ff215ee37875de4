"""edge-reduction: docs/results/edge-reduction.json."""

from __future__ import annotations

from .common import RESULTS, Block, read_json
from .reports import report_table

_EDGES = "docs/results/edge-reduction.json (supportive reproduce edge-reduction)"


def edge_reduction_counts() -> str:
    """docs/experiments.md: how many learned hierarchies are complete, and inside the thesis's depth range."""
    metrics = read_json(RESULTS / "edge-reduction.json")
    tasks = metrics["tasks"]
    low, high = metrics["thesis"]["mean_action_depth"]["min"], metrics["thesis"]["mean_action_depth"]["max"]
    learned = metrics["models"]["learned"]
    inside = sum(low <= t["learned"]["depth"] <= high for t in tasks)
    orderings = metrics["all_orderings"]
    sizes = [t["subgoals"] for t in tasks if t.get("all_orderings")]
    return (
        f"Learned from 4 paths, {learned['complete']} of {len(tasks)} hierarchies are complete and {inside} of "
        f"{len(tasks)} tasks have a depth inside {low}–{high}. From all orderings ({orderings['qualified']} tasks, "
        f"with {min(sizes)}–{max(sizes)} subgoals; the larger ones admit more than {orderings['limit']:,} orderings) "
        f"the learner recovered **{orderings['recovered']} of {orderings['qualified']}** structures exactly.\n"
    )


def edge_reduction_learned() -> str:
    """docs/learning.md: complete hierarchies and mean depth, learned from 4 paths, beside the truth's."""
    metrics = read_json(RESULTS / "edge-reduction.json")
    learned, truth = metrics["models"]["learned"], metrics["models"]["ground_truth"]
    return (
        f"complete hierarchies {learned['complete']} of {learned['tasks']}, mean action depth "
        f"{learned['depth']['mean']:.2f} (ground truth {truth['depth']['mean']:.2f}; the thesis reports "
        f"{metrics['thesis']['mean_action_depth']['mean']} for its CC-HTNs).\n"
    )


BLOCKS: dict[str, Block] = {
    "edge-reduction-depth": report_table("edge-reduction", "edge-reduction.json", "| model | tasks | mean |"),
    "edge-reduction-counts": Block(_EDGES, edge_reduction_counts),
    "edge-reduction-bins": report_table("edge-reduction", "edge-reduction.json", "| subgoals |"),
    "edge-reduction-totals": report_table(
        "edge-reduction", "edge-reduction.json", "| model | tasks | complete |"
    ),
    "edge-reduction-learned": Block(_EDGES, edge_reduction_learned),
}
