"""Selection settings (issue #23): when and with how many folds the default learner compares its readings,
chosen by a procedure on generated tasks.

Generated tasks, done by people drawing uniformly among their valid executions and by people with habits,
are learned from 2–20 demonstrations by the ``general`` reading and by ``auto`` (the readings compared by
cross-validated held-out likelihood, :mod:`~supportive.learning.selection`) with each number of folds; both
are scored on fresh executions of the task by the same people. The report gives what comparing gains per
number of demonstrations and folds, and the policy the documented procedure picks
(:func:`~supportive.experiments.selection_settings.measure.choose`).
:class:`~supportive.learning.learner.HTNLearner`'s ``selection_folds`` and ``selection_demonstrations`` are
that policy; CaptainCook4D plays no part.

>>> from supportive.experiments import get
>>> get("selection-settings").default_trials
6000
"""

from supportive.experiments.registry import declare
from supportive.experiments.selection_settings import measure, report

__all__ = ["SELECTION_SETTINGS"]

SELECTION_SETTINGS = declare(
    name="selection-settings",
    title="Selection settings: when the default learner compares its readings, chosen on generated tasks",
    reference="issue #23 (not in the thesis): the structure chosen by held-out likelihood, on generated tasks",
    parts=(measure, report),
)
"""The registered experiment."""
