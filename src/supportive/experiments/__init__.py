"""Reproduce the thesis's experiments: a registry by name, a runner (in process, on a dask LocalCluster or
on an existing dask cluster), and for each run ``metrics.json`` + ``report.md`` + PNG plots with the thesis's
numbers side by side. A trial's wall-clock measurements, under its reserved ``"timing"`` key, go to
``timing.json`` instead of the metrics.

>>> from supportive.experiments import names, run_experiment
>>> names()
('active-learning', 'active-learning-blocks', 'captaincook', 'captaincook-prediction', 'caregiver', 'edge-reduction', 'generalisation', 'goal-inference', 'learner-settings', 'mistake-detection', 'selection-settings', 'support-tamp', 'transfer')
>>> result = run_experiment("edge-reduction", trials=2, progress=False)
>>> "1.99" in result.report and "2.84" in result.report
True
"""

from supportive.experiments.readings import Finding, Reading, findings_table
from supportive.experiments.registry import (
    ALL,
    TIMING_KEY,
    Experiment,
    HeadlineRow,
    Metrics,
    TrialResult,
    declare,
    get,
    names,
    register,
    unregister,
)
from supportive.experiments.runner import (
    DEFAULT_OUTPUT,
    SUMMARY_FILE,
    RunResult,
    default_output,
    reproduce,
    run_all,
    run_experiment,
)
from supportive.experiments.trials import Trial, spawn_trials, trial_seeds

__all__ = [
    "ALL",
    "DEFAULT_OUTPUT",
    "SUMMARY_FILE",
    "TIMING_KEY",
    "Experiment",
    "Finding",
    "HeadlineRow",
    "Metrics",
    "Reading",
    "RunResult",
    "Trial",
    "TrialResult",
    "declare",
    "default_output",
    "findings_table",
    "get",
    "names",
    "register",
    "reproduce",
    "run_all",
    "run_experiment",
    "spawn_trials",
    "trial_seeds",
    "unregister",
]
