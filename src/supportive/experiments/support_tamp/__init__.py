"""Supportive-behavior TAMP (thesis §3.2.9, Figures 3.5–3.6): a support robot rearranges a circuit-building
table for a lead it cannot talk to.

One trial = one random table of the thesis-size task, run for both scenarios (an unpredictable lead that
knows a random subset of Π_T, with conservative weights; a greedy heuristic lead, with aggressive weights)
and every pairing of fast (100 %) and slow (33 %) lead and support agent, with and without support
(:mod:`.measure`), the support agent minimising the expected duration of the lead's plans (reading
``duration``, the default) or that plus the greedy lead's search (``search-aware``). Reported: makespan and
its gain as a reduction and as a speed-up, the motion model's ceiling, the lead's search nodes and planning
time, support actions and conflicts (:mod:`.report`, :mod:`.plots`).

>>> from supportive.experiments import get
>>> get("support-tamp").reference
'§3.2.9, Figures 3.5–3.6'
"""

from pathlib import Path
from typing import Any

from supportive.experiments.registry import Experiment, register
from supportive.experiments.support_tamp.measure import (
    ENVIRONMENTS,
    PAIRINGS,
    READINGS,
    SCENARIOS,
    SEARCH_WEIGHT,
    SLOW,
    alone_plan,
    make_trials,
    run_trial,
    staged_floor,
)
from supportive.experiments.support_tamp.plots import FILES, plots
from supportive.experiments.support_tamp.report import (
    GAINS,
    THESIS,
    findings,
    headline,
    report,
    summarize,
    timing_summary,
)

__all__ = [
    "ENVIRONMENTS",
    "FILES",
    "GAINS",
    "PAIRINGS",
    "READINGS",
    "SCENARIOS",
    "SEARCH_WEIGHT",
    "SLOW",
    "SUPPORT_TAMP",
    "THESIS",
    "alone_plan",
    "findings",
    "headline",
    "make_trials",
    "plots",
    "report",
    "run_trial",
    "staged_floor",
    "summarize",
    "timing_summary",
]


def _timing_report(timings: list[dict[str, Any]], directory: Path) -> list[Path]:
    import json

    path = directory / "timing-summary.json"
    path.write_text(json.dumps(timing_summary(timings), indent=2) + "\n", encoding="utf-8")
    return [path]


SUPPORT_TAMP = register(
    Experiment(
        name="support-tamp",
        title="Supportive-behavior TAMP: a support robot rearranges a circuit-building table",
        reference="§3.2.9, Figures 3.5–3.6",
        thesis=THESIS,
        default_trials=30,
        make_trials=make_trials,
        run_trial=run_trial,
        summarize=summarize,
        report=report,
        plots=plots,
        headline=headline,
        timing_report=_timing_report,
        readings=READINGS,
        findings=findings,
    )
)
"""The registered experiment."""
