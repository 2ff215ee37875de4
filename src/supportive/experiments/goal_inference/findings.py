"""Goal inference: the rows of the summary table (deterministic numbers only: the per-update times, which
differ from run to run, are in ``timing.md``)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from supportive.experiments.readings import Finding
from supportive.experiments.statistics import above_zero, below_zero, format_ci

__all__ = ["findings"]


def findings(metrics: Mapping[str, Any]) -> list[Finding]:
    """Subgoal accuracy flat vs hierarchical at the heaviest overlap, and the work per update at the largest
    size, beside the thesis's qualitative claims."""
    hardest = metrics["settings"][-1]
    accuracy = metrics["accuracy"][hardest["key"]]
    difference = accuracy["difference"]["subgoal"]
    if above_zero(difference):
        verdict = "hierarchical ahead, but by little"
    elif below_zero(difference):
        verdict = "not reproduced: hierarchical behind"
    else:
        verdict = "no difference at this size of run"
    largest = metrics["sizes"][-1]
    entries = largest["operator_entries"]
    progress = accuracy.get("progress_difference", {}).get("subgoal")
    sizes_ahead = [
        row for row in metrics["sizes"] if row.get("progress_difference", {}).get(hardest["key"], {}).get("mean", 0) > 0
    ]
    extra: list[Finding] = []
    if progress is not None:
        extra.append(
            Finding(
                f"subgoal accuracy, progress-aware tracker − hierarchical, overlap {hardest['overlap']:g} "
                f"{hardest['noise']}",
                "– (issue #14)",
                (
                    (
                        "",
                        f"{accuracy['progress']['subgoal']['mean']:.3f} vs {accuracy['hierarchical']['subgoal']['mean']:.3f} "
                        f"({format_ci(progress, 3, signed=True)}); ahead in {len(sizes_ahead)} of "
                        f"{len(metrics['sizes'])} sizes",
                    ),
                ),
                "progress-aware ahead" if above_zero(progress) else "no difference at this size of run",
            )
        )
    return [
        Finding(
            f"subgoal accuracy, flat / hierarchical (Δ), overlap {hardest['overlap']:g} {hardest['noise']}",
            "no numbers; the benefit depends on overlap",
            (
                (
                    "",
                    f"{accuracy['flat']['subgoal']['mean']:.3f} / {accuracy['hierarchical']['subgoal']['mean']:.3f} "
                    f"({format_ci(difference, 3, signed=True)})",
                ),
            ),
            verdict,
        ),
        Finding(
            f"entries per update, flat / hierarchical, {largest['subgoals']:,} subgoals",
            "\"considerable computational benefits\"; CC-HTN faster than 1 Hz",
            (("", f"{entries['flat']:,.0f} / {entries['hierarchical']:,.0f}"),),
            "holds in work per update"
            if entries["hierarchical"] < entries["flat"]
            else "no benefit at these sizes",
        ),
        *extra,
    ]
