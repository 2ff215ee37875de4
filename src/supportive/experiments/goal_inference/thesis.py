"""Goal inference: what the thesis says (§2.1.7.1–2.1.7.3, Figure 2.4), word for word where it matters."""

from __future__ import annotations

from typing import Any

__all__ = ["THESIS"]

THESIS: dict[str, Any] = {
    "tasks": 76,
    "subgoals": {"min": 10, "max": 100},
    "figure_2_4": (
        "Mean computation times for estimating an agent’s last completed subgoal using HMMs, as a function of "
        "task complexity. Timings were measured using a single thread of an Intel i7-3930K CPU. The "
        "responsiveness required in collaborative task execution mandates high frequency state estimation "
        "capabilities. In most cases, the CC-HTN model completed its computation faster than 1Hz."
    ),
    "timing_claim": "In most cases, the CC-HTN model completed its computation faster than 1Hz.",
    "update_seconds_bound": 1.0,
    "cpu": "Intel i7-3930K, a single thread",
    "computational_claim": (
        "CC-HTNs provide considerable computational benefits over flat task models despite being built from "
        "the same base representation."
    ),
    "accuracy_statement": (
        "In practice, hierarchical state estimation accuracy benefits will be dependent on observation set "
        "overlap between sub-tasks, however for cases where there is suitable distinction, these observed "
        "computational benefits apply."
    ),
    "figure_2_4_numbers": None,
    "accuracy": None,
}
"""What §2.1.7.1–2.1.7.3 and Figure 2.4 report. The evaluation set is §2.1.7.2's (76 IKEA-like tasks of
10–100 subgoals). The text prints no values for Figure 2.4 (``figure_2_4_numbers`` is ``None``) and no
accuracy at all (``accuracy`` is ``None``): it only says that accuracy benefits depend on observation overlap.
``update_seconds_bound`` is "faster than 1Hz" as seconds per update."""
