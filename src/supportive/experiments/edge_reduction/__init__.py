"""Edge reduction (thesis §2.1.7.2–2.1.7.3, Figure 2.5): edges of the flat task model vs the CC-HTN.

76 generated IKEA-like tasks of 10–100 subgoals, 4 random execution paths each; one trial per task. Each
task is measured three ways (learned from its paths, its ground-truth structure, learned from every valid
ordering when there are few enough), see :mod:`.measure`.

>>> from supportive.experiments import get
>>> get("edge-reduction").default_trials
76
"""

from supportive.experiments.edge_reduction.measure import (
    DEMONSTRATIONS,
    ORDERINGS_LIMIT,
    SIZES,
    make_trials,
    measure_task,
    model_sizes,
    run_trial,
    task_for,
)
from supportive.experiments.edge_reduction.plots import plots
from supportive.experiments.edge_reduction.report import THESIS, findings, headline, report
from supportive.experiments.edge_reduction.summary import summarize
from supportive.experiments.registry import Experiment, register

__all__ = [
    "DEMONSTRATIONS",
    "EDGE_REDUCTION",
    "ORDERINGS_LIMIT",
    "SIZES",
    "THESIS",
    "findings",
    "headline",
    "make_trials",
    "measure_task",
    "model_sizes",
    "plots",
    "report",
    "run_trial",
    "summarize",
    "task_for",
]

EDGE_REDUCTION = register(
    Experiment(
        name="edge-reduction",
        title="Edge reduction: flat task model vs CC-HTN",
        reference="§2.1.7.2–2.1.7.3, Figure 2.5",
        thesis=THESIS,
        default_trials=THESIS["tasks"],
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
