"""CaptainCook4D next-step prediction (issue #14): every recipe, all its recordings (with errors and
without), leave one out: the progress-aware predictor beside three simple baselines, and how often the
hierarchy learned from the other recordings admits the one left out. Not in the thesis.

One trial per recipe (24); :func:`~supportive.evaluation.crossval.evaluate_task` does the work.

>>> from supportive.experiments import get
>>> get("captaincook-prediction").default_trials
24
"""

from supportive.experiments.captaincook_prediction.measure import (
    MODELS,
    RECIPES,
    make_trials,
    run_trial,
    summarize,
)
from supportive.experiments.captaincook_prediction.report import findings, headline, plots, report
from supportive.experiments.registry import Experiment, register

__all__ = [
    "CAPTAINCOOK_PREDICTION",
    "MODELS",
    "RECIPES",
    "findings",
    "headline",
    "make_trials",
    "plots",
    "report",
    "run_trial",
    "summarize",
]

CAPTAINCOOK_PREDICTION = register(
    Experiment(
        name="captaincook-prediction",
        title="CaptainCook4D: next-step prediction, progress-aware vs simple baselines (leave one out)",
        reference="§2.1.7 (goal inference), on CaptainCook4D (issue #14); not in the thesis",
        thesis={},
        default_trials=RECIPES,
        make_trials=make_trials,
        run_trial=run_trial,
        summarize=summarize,
        report=report,
        plots=plots,
        headline=headline,
        findings=findings,
    )
)
"""The registered experiment."""
