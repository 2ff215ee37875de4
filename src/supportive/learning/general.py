"""The ``general`` learner: a CC-HTN from what real demonstrations show, step by step.

1. Which performance of a repeated action each step is, by context (:mod:`.labelling`).
2. Slips set aside, within a bounded share (:mod:`.deviations`).
3. Chains and cliques the evidence supports (:mod:`.decomposition`), from ``subtask_demonstrations``
   demonstrations on. Fewer rarely tell a subtask from a coincidence (on CaptainCook4D, trees learned from
   two or three recordings admit far fewer of the other recordings than the established orders alone;
   docs/learning.md): then every step is a root of its own, in those orders (the ``strict`` learner, which
   commits to what it has seen in full, is the thesis's reading for such cases). A single demonstration,
   with nothing to compare it with, is one chain.
4. Repeated subtasks recognised as instances of one (:mod:`.repeats`).
5. Optional flags, counts and support (:mod:`.annotate`).
6. The top level, when several roots remain, as the partial order the evidence establishes (:mod:`.top_order`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from supportive.learning.annotate import annotate
from supportive.learning.decomposition import decompose
from supportive.learning.deviations import Deviation, set_aside
from supportive.learning.labelling import label_performances
from supportive.learning.repeats import fold_repeats
from supportive.learning.top_order import precedence_top_level
from supportive.tasks.htn import Leaf, Node, TopLevel

__all__ = ["GeneralResult", "GeneralSettings", "learn_general"]


@dataclass(frozen=True)
class GeneralSettings:
    """Knobs of the ``general`` learner (see :class:`~supportive.learning.learner.HTNLearner`)."""

    deviations: float = 0.1
    evidence: float = 0.05
    order_support: int | None = None
    subtask_demonstrations: int = 4

    @property
    def support_needed(self) -> int:
        """``order_support``, or by default the fewest demonstrations in which two steps of free relative
        order all keep one order with chance ``2^(1-m)`` below ``evidence`` (6 for 0.05)."""
        if self.order_support is not None:
            return self.order_support
        return 1 + math.ceil(math.log2(1.0 / self.evidence) - 1e-12)


@dataclass(frozen=True)
class GeneralResult:
    """Roots, top level (None when one root is left), the slips set aside and the labelled demonstrations."""

    roots: tuple[Node, ...]
    top_level: TopLevel | None
    deviations: tuple[Deviation, ...]
    labelled: tuple[tuple[Leaf, ...], ...]


def learn_general(demonstrations: Sequence[Sequence[str]], settings: GeneralSettings) -> GeneralResult:
    """Learn a hierarchy from action sequences with the ``general`` learner (see the module docstring)."""
    labelled = label_performances(demonstrations)
    cleaned, deviations = set_aside(labelled, settings.deviations, settings.evidence)
    few = 1 < len(cleaned) < settings.subtask_demonstrations
    decomposition = fold_repeats(
        decompose(cleaned, evidence=settings.evidence, order_support=settings.support_needed, modules=not few)
    )
    leaf_id = {leaf: i for i, leaf in enumerate(decomposition.leaves)}
    excused: dict[int, set[int]] = {}
    for deviation in deviations:
        if deviation.kind == "missing" or deviation.kind == "out of order":
            node = leaf_id.get(deviation.leaf)
            if node is not None:
                excused.setdefault(node, set()).add(deviation.demonstration)
    annotated = annotate(
        decomposition, {n: frozenset(d) for n, d in excused.items()}, len(cleaned)
    )
    roots = annotated.root_nodes()
    top: TopLevel | None = None
    if len(roots) > 1:
        required = frozenset(r for r, node in zip(decomposition.roots, roots, strict=True) if not node.optional)
        top = precedence_top_level(
            decomposition.roots, decomposition.sequences, required, order_support=settings.support_needed
        )
        top = TopLevel(top.initial, top.terminal, top.edges, annotated.top_counts())
    return GeneralResult(roots, top, deviations, tuple(labelled))



