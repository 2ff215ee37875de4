"""Transfer (thesis §2.1.7.4, Figure 2.6): task exploration with Q-function and CC-HTN macro transfer.

25 food-preparation tasks (6–14 steps, 39 shared primitives), leave-one-out: an ε-greedy Q-learning agent
explores each task's SMDP until it has observed every valid ordering (:mod:`.explore`), (a) without transfer,
(b) with the other tasks' Q-functions as a prior and (c) with, in addition, the macro actions of their
CC-HTNs (:mod:`.sources`). One trial = one (task, seed), every condition (:mod:`.measure`).

>>> from supportive.experiments import get
>>> get("transfer").default_trials
100
"""

from supportive.experiments.registry import declare
from supportive.experiments.transfer import measure, plots, report

__all__ = ["TRANSFER"]

TRANSFER = declare(
    name="transfer",
    title="Transfer: task exploration with Q-function and CC-HTN macro transfer",
    reference="§2.1.7.4, Figure 2.6",
    parts=(measure, plots, report),
)
"""The registered experiment."""
