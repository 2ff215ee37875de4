"""The model: actions, demonstrations, task specs, task graphs, CTGs and HTN nodes. No algorithms."""

from supportive.tasks.conjugate import ORIGIN, TERMINAL, ConjugateTaskGraph, CTGEdge
from supportive.tasks.htn import (
    HTN,
    ActionNode,
    ChainNode,
    CliqueNode,
    Leaf,
    Node,
    TopLevel,
    canonical,
    count_orderings,
    iter_orderings,
    sample_ordering,
    to_leaves,
)
from supportive.tasks.spec import MISTAKE_LABELS, Action, Demonstration, Step, TaskSpec
from supportive.tasks.task_graph import GraphUpdate, TaskGraph

__all__ = [
    "HTN",
    "MISTAKE_LABELS",
    "ORIGIN",
    "TERMINAL",
    "Action",
    "ActionNode",
    "CTGEdge",
    "ChainNode",
    "CliqueNode",
    "ConjugateTaskGraph",
    "Demonstration",
    "GraphUpdate",
    "Leaf",
    "Node",
    "Step",
    "TaskGraph",
    "TaskSpec",
    "TopLevel",
    "canonical",
    "count_orderings",
    "iter_orderings",
    "sample_ordering",
    "to_leaves",
]
