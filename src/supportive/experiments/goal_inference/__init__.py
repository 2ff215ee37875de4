"""Goal inference (thesis §2.1.7.1–2.1.7.3, Figure 2.4): flat vs CC-HTN hierarchical HMM filters, speed and
accuracy.

One trial per generated IKEA-like task, sizes 10–1,000 subgoals dealt out in turn (:mod:`.design`); each
trial measures both online filters' accuracy at six observation settings and times their updates
(:mod:`.measure`). Accuracy goes to ``metrics.json`` (:mod:`.summary`); the wall-clock times, which are not
deterministic, go under each trial's reserved ``timing`` key, which the harness writes to ``timing.json``
beside it; :func:`~.plots.timing_report` turns them into ``timing.md`` and ``timing.png``.

>>> from supportive.experiments import get
>>> get("goal-inference").default_trials
35
"""

from supportive.experiments.goal_inference.design import (
    MEAN_DURATION,
    SETTINGS,
    SIZES,
    TIMED_SETTING,
    TRIALS_PER_SIZE,
    Setting,
    make_trials,
    steps_for,
)
from supportive.experiments.goal_inference.findings import findings
from supportive.experiments.goal_inference.measure import (
    measure_setting,
    measure_task,
    operator_entries,
    run_trial,
    task_for,
)
from supportive.experiments.goal_inference.plots import plots, timing_report
from supportive.experiments.goal_inference.report import headline, report, timing_markdown
from supportive.experiments.goal_inference.summary import summarize
from supportive.experiments.goal_inference.thesis import THESIS
from supportive.experiments.goal_inference.timing import TIMING_PLOT, TIMING_REPORT, timing_summary
from supportive.experiments.registry import Experiment, register

__all__ = [
    "GOAL_INFERENCE",
    "MEAN_DURATION",
    "SETTINGS",
    "SIZES",
    "THESIS",
    "TIMED_SETTING",
    "TIMING_PLOT",
    "TIMING_REPORT",
    "TRIALS_PER_SIZE",
    "Setting",
    "headline",
    "make_trials",
    "measure_setting",
    "measure_task",
    "operator_entries",
    "plots",
    "report",
    "run_trial",
    "steps_for",
    "summarize",
    "task_for",
    "timing_markdown",
    "timing_report",
    "timing_summary",
]

GOAL_INFERENCE = register(
    Experiment(
        name="goal-inference",
        title="Goal inference: flat HMM vs CC-HTN hierarchical HMM",
        reference="§2.1.7.1–2.1.7.3, Figure 2.4",
        thesis=THESIS,
        default_trials=TRIALS_PER_SIZE * len(SIZES),
        make_trials=make_trials,
        run_trial=run_trial,
        summarize=summarize,
        report=report,
        plots=plots,
        headline=headline,
        timing_report=timing_report,
        findings=findings,
    )
)
"""The registered experiment."""
