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

from supportive.experiments.mistake_detection import measure, report
from supportive.experiments.registry import declare

__all__ = ["MISTAKE_DETECTION"]

MISTAKE_DETECTION = declare(
    name="mistake-detection",
    title="Online mistake detection: generated tasks, then CaptainCook4D",
    reference="§3.1 (supportive behaviours), on generated tasks and CaptainCook4D (issue #24); not in the thesis",
    parts=(measure, report),
)
"""The registered experiment."""
