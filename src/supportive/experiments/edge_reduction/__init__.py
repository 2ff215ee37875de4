"""Edge reduction (thesis §2.1.7.2–2.1.7.3, Figure 2.5): edges of the flat task model vs the CC-HTN.

76 generated IKEA-like tasks of 10–100 subgoals, 4 random execution paths each; one trial per task. Each
task is measured three ways (learned from its paths, its ground-truth structure, learned from every valid
ordering when there are few enough), see :mod:`.measure`.

>>> from supportive.experiments import get
>>> get("edge-reduction").default_trials
76
"""

from supportive.experiments.edge_reduction import measure, plots, report, summary
from supportive.experiments.registry import declare

__all__ = ["EDGE_REDUCTION"]

EDGE_REDUCTION = declare(
    name="edge-reduction",
    title="Edge reduction: flat task model vs CC-HTN",
    reference="§2.1.7.2–2.1.7.3, Figure 2.5",
    parts=(measure, plots, report, summary),
)
"""The registered experiment."""
