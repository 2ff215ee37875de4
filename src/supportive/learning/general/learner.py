"""The ``general`` learner: a CC-HTN from what real demonstrations show, step by step.

1. Which performance of a repeated action each step is, by context (:mod:`.labelling`).
2. Slips found as noise, with rates estimated from the demonstrations (:mod:`.noise`).
3. The hierarchy of the demonstrations with their slips taken out (:mod:`.structure`): chains and cliques the
   evidence supports from ``subtask_demonstrations`` demonstrations on (with fewer, every step is a root of
   its own, in the orders the evidence establishes; a single demonstration, with nothing to compare it with,
   is one chain), repeated subtasks, optional flags, counts,
   and a partial-order top level when several roots remain.
4. When several roots remain, its alternative: one complete hierarchy that admits every execution the partial
   one admits (:mod:`.alternatives`).

It builds no task graph, CTG or compaction: those are the ``strict`` learner's (:mod:`supportive.learning.strict`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from supportive.learning.general.alternatives import complete_alternative
from supportive.learning.general.labelling import label_performances
from supportive.learning.general.noise import (
    Deviation,
    NoiseEstimate,
    NoiseSettings,
    SlipSearchCache,
    find_slips,
)
from supportive.learning.general.structure import FittedStructure, StructureSettings, fit_structure
from supportive.tasks.htn import Leaf, Node, TopLevel

__all__ = ["GeneralResult", "alternatives_of", "learn_general", "refit"]


@dataclass(frozen=True)
class GeneralResult:
    """Roots, top level (None when one root is left), the slips set aside, the noise model, the labelled
    demonstrations and the same with their slips taken out (``cleaned``) and undone (``restored``: steps out of
    order or missing put back, :class:`~supportive.learning.general.noise.SlipResult`)."""

    roots: tuple[Node, ...]
    top_level: TopLevel | None
    deviations: tuple[Deviation, ...]
    noise: NoiseEstimate
    labelled: tuple[tuple[Leaf, ...], ...]
    cleaned: tuple[tuple[Leaf, ...], ...]
    restored: tuple[tuple[Leaf, ...], ...]


def learn_general(
    demonstrations: Sequence[Sequence[str]],
    structure: StructureSettings,
    noise: NoiseSettings,
    *,
    modules: bool = True,
    cache: SlipSearchCache | None = None,
) -> GeneralResult:
    """Learn a hierarchy from action sequences with the ``general`` learner (see the module docstring);
    ``modules`` False learns the partial order of the steps only; ``cache`` shares the slip search's work with
    other fits of the same demonstrations (:class:`~supportive.learning.general.noise.SlipSearchCache`)."""
    labelled = label_performances(demonstrations)
    found = find_slips(labelled, structure, noise, modules=modules, cache=cache)
    return GeneralResult(
        found.structure.roots,
        found.structure.top_level,
        found.deviations,
        found.noise,
        tuple(labelled),
        tuple(tuple(demo) for demo in found.cleaned),
        tuple(tuple(demo) for demo in found.restored),
    )


def refit(
    found: GeneralResult, indices: Sequence[int], structure: StructureSettings, *, modules: bool = True
) -> FittedStructure:
    """The hierarchy of the demonstrations ``indices`` with the slips ``found`` taken out, learned with
    ``structure`` (another reading of the same cleaned demonstrations, :mod:`supportive.learning.selection`);
    a step slipped on counts as performed there."""
    position = {d: i for i, d in enumerate(indices)}
    excused = [
        (position[d.demonstration], d.leaf)
        for d in found.deviations
        if d.kind in ("out of order", "missing") and d.demonstration in position
    ]
    return fit_structure([found.cleaned[i] for i in indices], excused, structure, modules=modules)


def alternatives_of(fitted: FittedStructure, *, limit: int, max_roots: int) -> tuple[Node, ...]:
    """The general learner's alternatives to ``fitted``: none when it is complete, has more than
    ``max_roots`` roots or ``limit`` is 0; else its complete alternative (:mod:`.alternatives`), which
    admits every execution ``fitted`` admits."""
    if fitted.top_level is None or not limit or len(fitted.roots) > max_roots:
        return ()
    return (complete_alternative(fitted.roots, fitted.top_level),)
