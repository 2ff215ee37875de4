"""Transfer (thesis §2.1.7.4, Figure 2.6): task exploration with Q-function and CC-HTN macro transfer.

25 food-preparation tasks (6–14 steps, 39 shared primitives), leave-one-out: an ε-greedy Q-learning agent
explores each task's SMDP until it has observed every valid ordering (:mod:`.explore`), (a) without transfer,
(b) with the other tasks' Q-functions as a prior and (c) with, in addition, the macro actions of their
CC-HTNs (:mod:`.sources`). One trial = one (task, seed), every condition (:mod:`.measure`).

>>> from supportive.experiments import get
>>> get("transfer").default_trials
100
"""

from supportive.experiments.registry import Experiment, register
from supportive.experiments.transfer.explore import TaskModel, execute, explore
from supportive.experiments.transfer.measure import (
    CONDITIONS,
    MACRO_CONDITIONS,
    MAX_EPISODES,
    READINGS,
    SEEDS,
    STEP_CAP,
    make_trials,
    run_condition,
    run_trial,
)
from supportive.experiments.transfer.plots import plots
from supportive.experiments.transfer.report import CLAIM, THESIS, findings, headline, report, summarize

__all__ = [
    "CLAIM",
    "CONDITIONS",
    "MACRO_CONDITIONS",
    "MAX_EPISODES",
    "READINGS",
    "SEEDS",
    "STEP_CAP",
    "THESIS",
    "TRANSFER",
    "TaskModel",
    "execute",
    "explore",
    "findings",
    "headline",
    "make_trials",
    "plots",
    "report",
    "run_condition",
    "run_trial",
    "summarize",
]

TRANSFER = register(
    Experiment(
        name="transfer",
        title="Transfer: task exploration with Q-function and CC-HTN macro transfer",
        reference="§2.1.7.4, Figure 2.6",
        thesis=THESIS,
        default_trials=THESIS["tasks"] * SEEDS,
        make_trials=make_trials,
        run_trial=run_trial,
        summarize=summarize,
        report=report,
        plots=plots,
        headline=headline,
        readings=READINGS,
        findings=findings,
    )
)
"""The registered experiment."""
