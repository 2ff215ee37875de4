"""The ``general`` learner's hierarchy from demonstrations whose slips are known, and its likelihood.

From labelled demonstrations with their slips taken out (:mod:`.noise`): chains and cliques the evidence
supports (:mod:`.decomposition`), from ``subtask_demonstrations`` demonstrations on; repeated subtasks as
instances of one (:mod:`.repeats`); optional flags, counts and support (:mod:`.annotate`; a step someone
slipped on counts as performed there, so it does not become optional); and the top level, when several roots
remain, as the partial order the evidence establishes (:mod:`.top_order`).

:func:`log_likelihood` reads the result as a distribution over executions
(:class:`~supportive.learning.distribution.ProgressModel`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from supportive.learning.distribution import ProgressModel
from supportive.learning.general.annotate import annotate
from supportive.learning.general.decomposition import decompose
from supportive.learning.general.repeats import fold_repeats
from supportive.learning.general.top_order import precedence_top_level
from supportive.tasks.htn import HTN, Leaf, Node, TopLevel

__all__ = ["FittedStructure", "StructureSettings", "fit_structure", "log_likelihood"]


@dataclass(frozen=True)
class StructureSettings:
    """What :func:`fit_structure` needs of the learner's settings (see
    :class:`~supportive.learning.learner.HTNLearner`)."""

    evidence: float
    order_support: int | None
    subtask_demonstrations: int
    order_penalty: float | None = None

    @property
    def support_needed(self) -> int:
        """``order_support``, or by default the fewest demonstrations in which two steps of free relative
        order all keep one order with chance ``2^(1-m)`` below ``evidence`` (6 for 0.05)."""
        if self.order_support is not None:
            return self.order_support
        return 1 + math.ceil(math.log2(1.0 / self.evidence) - 1e-12)


@dataclass(frozen=True)
class FittedStructure:
    """Roots and top level (None when one root is left) of a learned hierarchy."""

    roots: tuple[Node, ...]
    top_level: TopLevel | None

    def htn(self, task: str = "") -> HTN:
        """The hierarchy as an :class:`~supportive.tasks.htn.HTN`."""
        return HTN(task, self.roots, self.top_level)


def fit_structure(
    cleaned: Sequence[Sequence[Leaf]],
    excused: Iterable[tuple[int, Leaf]],
    settings: StructureSettings,
    *,
    modules: bool = True,
) -> FittedStructure:
    """The hierarchy of ``cleaned`` demonstrations (see the module docstring).

    Args:
        cleaned: Labelled demonstrations, slips taken out.
        excused: ``(demonstration, leaf)`` pairs of steps performed there but set aside (out of place) or
            forgotten by mistake: they count as performed for the optional flags.
        settings: Evidence thresholds and from how many demonstrations subtasks are made.
        modules: False keeps every step a root, in the orders the evidence establishes (the partial-order
            reading, :mod:`.selection`).
    """
    few = 1 < len(cleaned) < settings.subtask_demonstrations
    decomposition = fold_repeats(
        decompose(
            cleaned, evidence=settings.evidence, order_support=settings.support_needed, modules=modules and not few
        )
    )
    leaf_id = {leaf: i for i, leaf in enumerate(decomposition.leaves)}
    by_node: dict[int, set[int]] = {}
    for demonstration, leaf in excused:
        node = leaf_id.get(leaf)
        if node is not None:
            by_node.setdefault(node, set()).add(demonstration)
    annotated = annotate(decomposition, {n: frozenset(d) for n, d in by_node.items()}, len(cleaned))
    roots = annotated.root_nodes()
    top: TopLevel | None = None
    if len(roots) > 1:
        required = frozenset(r for r, node in zip(decomposition.roots, roots, strict=True) if not node.optional)
        top = precedence_top_level(
            decomposition.roots,
            decomposition.sequences,
            required,
            order_support=settings.support_needed,
            order_penalty=settings.order_penalty,
        )
        top = top.with_counts(annotated.top_counts())
    return FittedStructure(roots, top)


def log_likelihood(model: ProgressModel, executions: Iterable[Sequence[str]]) -> float:
    """Natural log of the probability of ``executions`` (action ids), each independent, under ``model``."""
    return sum(model.log_probability(execution) for execution in executions)
