"""Online mistake detection (issue #24): the threshold chosen on generated tasks, then CaptainCook4D.

Generated tasks with mistakes put into held-out executions (a step moved early, skipped, repeated) choose the
detector's default threshold by a documented procedure
(:func:`~supportive.experiments.mistake_detection.measure.choose`); CaptainCook4D's labelled recordings are
then scored leaving one out, beside two baselines (a precondition check and an unseen-bigram rule), with a
precision-recall plot.

>>> from supportive.experiments import get
>>> get("mistake-detection").default_trials
54
"""

from supportive.experiments.mistake_detection.measure import (
    GENERATED,
    RECIPES,
    choose,
    make_trials,
    run_trial,
    summarize,
)
from supportive.experiments.mistake_detection.report import findings, headline, plots, report
from supportive.experiments.registry import Experiment, register

__all__ = ["MISTAKE_DETECTION", "choose", "findings", "headline", "make_trials", "plots", "report", "run_trial", "summarize"]

MISTAKE_DETECTION = register(
    Experiment(
        name="mistake-detection",
        title="Online mistake detection: generated tasks, then CaptainCook4D",
        reference="§3.1 (supportive behaviours), on generated tasks and CaptainCook4D (issue #24); not in the thesis",
        thesis={},
        default_trials=GENERATED + RECIPES,
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
