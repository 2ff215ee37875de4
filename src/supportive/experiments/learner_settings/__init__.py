"""Learner settings (issue #23): the slip search's defaults, chosen by a procedure on generated tasks.

Generated tasks (:mod:`supportive.generate.mistakes`) with a tenth of their demonstrations given one mistake
(a step moved, repeated or dropped), or none, are learned under every setting of a grid; the report gives the
precision and recall of the slips found per kind and number of demonstrations, the reports on clean data, and
the setting the documented procedure picks (:func:`~supportive.experiments.learner_settings.measure.choose`).
:class:`~supportive.learning.learner.HTNLearner`'s defaults are that setting; CaptainCook4D plays no part.

>>> from supportive.experiments import get
>>> get("learner-settings").default_trials
462
"""

from supportive.experiments.learner_settings.measure import (
    CLEAN_TASKS,
    DEMONSTRATIONS,
    GRID,
    TASKS,
    choose,
    make_trials,
    run_trial,
    settings_name,
    summarize,
)
from supportive.experiments.learner_settings.report import findings, headline, plots, report
from supportive.experiments.registry import Experiment, register
from supportive.generate.mistakes import KINDS, PROFILES

__all__ = [
    "GRID",
    "LEARNER_SETTINGS",
    "choose",
    "findings",
    "headline",
    "make_trials",
    "plots",
    "report",
    "run_trial",
    "settings_name",
    "summarize",
]

LEARNER_SETTINGS = register(
    Experiment(
        name="learner-settings",
        title="Learner settings: the slip search's defaults, chosen on generated tasks",
        reference="issue #23 (not in the thesis): slips judged against the model, on generated tasks",
        thesis={},
        default_trials=TASKS * len(PROFILES) * len(DEMONSTRATIONS) * len(KINDS) + CLEAN_TASKS,
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
