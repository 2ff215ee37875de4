"""Learner settings (issue #23): the slip search's defaults, chosen by a procedure on generated tasks.

Generated tasks (:mod:`supportive.generate.mistakes`) with a tenth of their demonstrations given one mistake
(a step moved, repeated or dropped), or none, are learned under every setting of a grid; the report gives the
precision and recall of the slips found per kind and number of demonstrations, the reports on clean data, and
the setting the documented procedure picks (:func:`~supportive.experiments.learner_settings.measure.choose`).
:class:`~supportive.learning.learner.HTNLearner`'s defaults are that setting; CaptainCook4D plays no part.

>>> from supportive.experiments import get
>>> get("learner-settings").default_trials
3486
"""

from supportive.experiments.learner_settings import measure, report
from supportive.experiments.registry import declare

__all__ = ["LEARNER_SETTINGS"]

LEARNER_SETTINGS = declare(
    name="learner-settings",
    title="Learner settings: the slip search's defaults, chosen on generated tasks",
    reference="issue #23 (not in the thesis): slips judged against the model, on generated tasks",
    parts=(measure, report),
)
"""The registered experiment."""
