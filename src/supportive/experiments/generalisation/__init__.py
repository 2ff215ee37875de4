"""Generalisation of the learned hierarchy (issue #13): the general learner beside the strict one.

* Generated chain/clique tasks (``uniform`` and ``ikea`` profiles, 4–12 actions, at most 5,000 orderings), 4
  sampled demonstrations each: recall (share of the valid orderings admitted) and precision (share of the
  admitted orderings that are valid).
* CaptainCook4D: learned from the first half of each recipe's error-free recordings, how many of the other
  half are admitted; learned from all error-free recordings, and from all recordings with errors too, the
  precision and recall of the "must come before" pairs against the published graphs.
* The slip check: generated tasks of sizes the slip settings were not chosen on (3–5, 13–20 and 21–30 steps),
  a tenth of their demonstrations given one mistake (or none), learned by the default learner and scored as
  ``learner-settings`` scores its settings, by people drawn uniformly and people with habits.

>>> from supportive.experiments import get
>>> get("generalisation").default_trials
756
"""

from supportive.experiments.generalisation import measure, report
from supportive.experiments.registry import declare

__all__ = ["GENERALISATION"]

GENERALISATION = declare(
    name="generalisation",
    title="Generalisation: general vs strict learner on generated tasks and CaptainCook4D",
    reference="§2.1.4 (compaction), on generated tasks and CaptainCook4D (issue #13)",
    parts=(measure, report),
)
"""The registered experiment."""
