"""CaptainCook4D learning curves (issue #4): passive vs active learning on real cooking recordings.

For each of the 24 recipes, the learned hierarchy's "must come before" pairs are scored against the published
task graph after each demonstration, passive (the real recordings) vs each query strategy (a simulated
instructor following the published graph); see :mod:`.measure`.

>>> from supportive.experiments import get
>>> get("captaincook").default_trials
10
"""

from supportive.experiments.captaincook.measure import (
    CONDITIONS,
    DEFAULT_TRIALS,
    HORIZON,
    METRICS,
    SCHEDULE,
    make_trials,
    partial_order,
    recipe_rng,
    run_recipe,
    run_trial,
    summarize,
)
from supportive.experiments.captaincook.report import CURVES_PLOT, THESIS, findings, headline, plots, report
from supportive.experiments.registry import Experiment, register

__all__ = [
    "CAPTAINCOOK",
    "CONDITIONS",
    "CURVES_PLOT",
    "DEFAULT_TRIALS",
    "HORIZON",
    "METRICS",
    "SCHEDULE",
    "THESIS",
    "findings",
    "headline",
    "make_trials",
    "partial_order",
    "plots",
    "recipe_rng",
    "report",
    "run_recipe",
    "run_trial",
    "summarize",
]

CAPTAINCOOK = register(
    Experiment(
        name="captaincook",
        title="CaptainCook4D: learning curves, passive vs active, against published task graphs",
        reference="§2.2 (active learning), on CaptainCook4D (issue #4)",
        thesis=THESIS,
        default_trials=DEFAULT_TRIALS,
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
