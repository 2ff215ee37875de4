"""CaptainCook4D next-step prediction (issue #14): every recipe, all its recordings (with errors and
without), leave one out: the progress-aware predictor beside three simple baselines, and how often the
hierarchy learned from the other recordings admits the one left out. Not in the thesis.

One trial per recipe (24); :func:`~supportive.evaluation.crossval.evaluate_task` does the work.

>>> from supportive.experiments import get
>>> get("captaincook-prediction").default_trials
24
"""

from supportive.experiments.captaincook_prediction import measure, report
from supportive.experiments.registry import declare

__all__ = ["CAPTAINCOOK_PREDICTION"]

CAPTAINCOOK_PREDICTION = declare(
    name="captaincook-prediction",
    title="CaptainCook4D: next-step prediction, progress-aware vs simple baselines (leave one out)",
    reference="§2.1.7 (goal inference), on CaptainCook4D (issue #14); not in the thesis",
    parts=(measure, report),
)
"""The registered experiment."""
