"""The ``general`` learner: a CC-HTN from what real demonstrations show, step by step.

1. Which performance of a repeated action each step is, by context (:mod:`.labelling`).
2. Slips found as noise, with rates estimated from the demonstrations (:mod:`.noise`).
3. The hierarchy of the demonstrations with their slips taken out (:mod:`.structure`): chains and cliques the
   evidence supports from ``subtask_demonstrations`` demonstrations on (fewer rarely tell a subtask from a
   coincidence: every step is then a root of its own, in the orders the evidence establishes; a single
   demonstration, with nothing to compare it with, is one chain), repeated subtasks, optional flags, counts,
   and a partial-order top level when several roots remain.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from supportive.learning.labelling import label_performances
from supportive.learning.noise import Deviation, NoiseEstimate, NoiseSettings, find_slips
from supportive.learning.structure import StructureSettings
from supportive.tasks.htn import Leaf, Node, TopLevel

__all__ = ["GeneralResult", "learn_general"]


@dataclass(frozen=True)
class GeneralResult:
    """Roots, top level (None when one root is left), the slips set aside, the noise model, the labelled
    demonstrations and the same with their slips taken out (``cleaned``)."""

    roots: tuple[Node, ...]
    top_level: TopLevel | None
    deviations: tuple[Deviation, ...]
    noise: NoiseEstimate
    labelled: tuple[tuple[Leaf, ...], ...]
    cleaned: tuple[tuple[Leaf, ...], ...]


def learn_general(
    demonstrations: Sequence[Sequence[str]],
    structure: StructureSettings,
    noise: NoiseSettings,
    *,
    modules: bool = True,
) -> GeneralResult:
    """Learn a hierarchy from action sequences with the ``general`` learner (see the module docstring);
    ``modules`` False learns the partial order of the steps only."""
    labelled = label_performances(demonstrations)
    found = find_slips(labelled, structure, noise, modules=modules)
    return GeneralResult(
        found.structure.roots,
        found.structure.top_level,
        found.deviations,
        found.noise,
        tuple(labelled),
        tuple(tuple(demo) for demo in found.cleaned),
    )
