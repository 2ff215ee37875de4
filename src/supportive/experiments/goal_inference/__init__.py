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

from supportive.experiments.goal_inference import design, findings, measure, plots, report, summary, thesis
from supportive.experiments.registry import declare

__all__ = ["GOAL_INFERENCE"]

GOAL_INFERENCE = declare(
    name="goal-inference",
    title="Goal inference: flat HMM vs CC-HTN hierarchical HMM",
    reference="§2.1.7.1–2.1.7.3, Figure 2.4",
    parts=(design, findings, measure, plots, report, summary, thesis),
)
"""The registered experiment."""
