"""CaptainCook4D learning curves (issue #4): passive vs active learning on real cooking recordings.

For each of the 24 recipes, the learned hierarchy's "must come before" pairs are scored against the published
task graph after each demonstration, passive (the real recordings) vs each query strategy (a simulated
instructor following the published graph); see :mod:`.measure`.

>>> from supportive.experiments import get
>>> get("captaincook").default_trials
10
"""

from supportive.experiments.captaincook import measure, report
from supportive.experiments.registry import declare

__all__ = ["CAPTAINCOOK"]

CAPTAINCOOK = declare(
    name="captaincook",
    title="CaptainCook4D: learning curves, passive vs active, against published task graphs",
    reference="§2.2 (active learning), on CaptainCook4D (issue #4)",
    parts=(measure, report),
)
"""The registered experiment."""
