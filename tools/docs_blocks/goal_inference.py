"""goal-inference: docs/results/goal-inference.json and goal-inference-timing.json."""

from __future__ import annotations

from .common import RESULTS, Block, read_json
from .reports import report_table, timing_part
from .runs import digest


def _signed(value: float) -> str:
    return f"{value:+.3f}".replace("-", "−")


def goal_inference_tracker() -> str:
    """docs/inference.md: the progress-aware tracker beside the hierarchical HMM at overlap 0.8, per task size."""
    sizes = read_json(RESULTS / "goal-inference.json")["sizes"]

    def ahead(setting: str) -> int:
        return sum(
            s["accuracy"][setting]["progress"]["subgoal"] > s["accuracy"][setting]["hierarchical"]["subgoal"]
            for s in sizes
        )

    parts, excluding = [], []
    for size in sizes:
        accuracy, difference = (
            size["accuracy"]["overlap-0.8-noisy"],
            size["progress_difference"]["overlap-0.8-noisy"],
        )
        parts.append(
            f"{size['subgoals']:,}: {accuracy['hierarchical']['subgoal']:.3f} → {accuracy['progress']['subgoal']:.3f} "
            f"({_signed(difference['mean'])} [{_signed(difference['low'])}, {_signed(difference['high'])}])"
        )
        excluding += [f"{size['subgoals']:,}"] if difference["low"] > 0 else []
    return (
        f"at overlap 0.8 the tracker's mean subgoal accuracy is above the hierarchical HMM's in "
        f"{ahead('overlap-0.8-clean')} of {len(sizes)} task sizes clean and {ahead('overlap-0.8-noisy')} of "
        f"{len(sizes)} noisy. Noisy, hierarchical → tracker (paired difference, 95% CI), by subgoals: "
        f"{', '.join(parts)}; the interval excludes zero at {', '.join(excluding) or 'no size'} subgoals ("
        f"{sizes[0]['trials']} trials per size).\n"
    )


BLOCKS: dict[str, Block] = {
    "goal-inference-sha": digest("goal-inference.json"),
    "goal-inference-accuracy": report_table(
        "goal-inference", "goal-inference.json", "| setting | flat: subgoal |"
    ),
    "goal-inference-work": report_table(
        "goal-inference", "goal-inference.json", "| subgoals | trials | subtasks |"
    ),
    "goal-inference-timing": timing_part(
        "goal-inference", "goal-inference-timing.json", "| subgoals |", "## "
    ),
    "goal-inference-accuracy-summary": report_table(
        "goal-inference", "goal-inference.json", "| setting | flat: subgoal |"
    ),
    "goal-inference-tracker": Block(
        "docs/results/goal-inference.json (supportive reproduce goal-inference)", goal_inference_tracker
    ),
    "goal-inference-figure": timing_part(
        "goal-inference", "goal-inference-timing.json", "## Beside Figure 2.4"
    ),
}
