"""CaptainCook4D: ``supportive captaincook --json`` > docs/results/captaincook.json, and the reports of the
experiments on it (captaincook, captaincook-prediction, mistake-detection)."""

from __future__ import annotations

from statistics import mean
from typing import Any

from .common import RESULTS, Block, read_json
from .reports import report_table

CAPTAINCOOK = "docs/results/captaincook.json (supportive captaincook --json)"


def captaincook_recipes() -> list[dict[str, Any]]:
    """The recorded per-recipe scores (``docs/results/captaincook.json``)."""
    recipes: list[dict[str, Any]] = read_json(RESULTS / "captaincook.json")
    return recipes


def _f(value: float, digits: int = 3) -> str:
    return f"{value:.{digits}f}"


def captaincook_precedence() -> str:
    """docs/exports.md: the means over the recipes, where recall falls below 1 and the lowest precision."""
    recipes = captaincook_recipes()
    below = [r for r in recipes if r["recall"] < 1]
    lowest = min(recipes, key=lambda r: r["precision"])
    misses = ", ".join(f"`{r['recipe']}` ({_f(r['recall'])})" for r in below) or "none"
    admitted = sum(r["admits_demonstrations"] for r in recipes)
    return (
        f"Measured: mean precision {_f(mean(r['precision'] for r in recipes))}, "
        f"recall {_f(mean(r['recall'] for r in recipes))}, F1 {_f(mean(r['f1'] for r in recipes))} over the "
        f"{len(recipes)} recipes; {admitted} of {len(recipes)} learned models admit all their recordings. Recall is "
        f"below 1 in {len(below)} recipe{'' if len(below) == 1 else 's'}: {misses}. Precision is lowest in `{lowest['recipe']}` "
        f"({_f(lowest['precision'])}).\n"
    )


def captaincook_edges() -> str:
    """docs/learning.md: task-graph edge F1, full and 5-shot, the means over the recipes."""
    recipes = captaincook_recipes()
    full = mean(r["edges"]["f1"] for r in recipes)
    few = mean(r["edges_5_shot"]["f1"] for r in recipes)
    return f"{_f(full)} full, {_f(few)} 5-shot\n"


def captaincook_edge_errors() -> str:
    """docs/learning.md: the default learner's wrong task-graph edges, summed over the recipes, by kind, full
    and 5-shot."""
    recipes = captaincook_recipes()
    lines = ["| kind of wrong edge | full | 5-shot |", "|---|---:|---:|"]
    for kind in recipes[0]["edge_errors"]:
        full = sum(r["edge_errors"][kind] for r in recipes)
        few = sum(r["edge_errors_5_shot"][kind] for r in recipes)
        lines.append(f"| {kind} | {full} | {few} |")
    return "\n".join(lines) + "\n"


BLOCKS: dict[str, Block] = {
    "captaincook-precedence": Block(CAPTAINCOOK, captaincook_precedence),
    "captaincook-edges": Block(CAPTAINCOOK, captaincook_edges),
    "captaincook-edge-errors": Block(CAPTAINCOOK, captaincook_edge_errors),
    "captaincook-curves-f1": report_table("captaincook", "captaincook-curves.json", "| k | recipes |"),
    "captaincook-curves-own-k": report_table("captaincook", "captaincook-curves.json", "| condition |"),
    "captaincook-curves-queries": report_table(
        "captaincook", "captaincook-curves.json", "| strategy | asked |"
    ),
    "captaincook-prediction-models": report_table(
        "captaincook-prediction", "captaincook-prediction.json", "| model | top-1 |"
    ),
    "captaincook-prediction-reliability": report_table(
        "captaincook-prediction", "captaincook-prediction.json", "| top-1 probability |"
    ),
    "mistake-detection-thresholds": report_table(
        "mistake-detection", "mistake-detection.json", "| threshold |"
    ),
    "mistake-detection-captaincook": report_table(
        "mistake-detection", "mistake-detection.json", "| method | precision |"
    ),
    "mistake-detection-kinds": report_table(
        "mistake-detection", "mistake-detection.json", "| method | kind |"
    ),
    "mistake-detection-correct": report_table(
        "mistake-detection", "mistake-detection.json", "| method | precision |", 1
    ),
    "mistake-detection-correct-kinds": report_table(
        "mistake-detection", "mistake-detection.json", "| method | kind |", 1
    ),
}
