"""The "uniform" profile: a structure made by recursive random splits, with no domain in mind."""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Literal

import numpy as np

from supportive.errors import GenerationError
from supportive.generate.normalise import normalise
from supportive.seeding import Seed, rng_from
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, Node

__all__ = ["UniformParams", "uniform_structure"]


@dataclass(frozen=True)
class UniformParams:
    """Knobs of :func:`uniform_structure`.

    Attributes:
        max_children: Most parts a node is split into (at least 2).
        kinds: ``"random"``: every node is a clique with ``clique_probability``; ``"alternate"``: the root is
            drawn so, and kinds alternate chain/clique level by level below it.
        clique_probability: Chance that a node (the root, under ``"alternate"``) is a clique.
    """

    max_children: int = 4
    kinds: Literal["random", "alternate"] = "random"
    clique_probability: float = 0.5

    def __post_init__(self) -> None:
        if self.max_children < 2:
            raise GenerationError(f"max_children must be at least 2, got {self.max_children}")
        if not 0.0 <= self.clique_probability <= 1.0:
            raise GenerationError(f"clique_probability must be in [0, 1], got {self.clique_probability}")
        if self.kinds not in ("random", "alternate"):
            raise GenerationError(f"kinds must be 'random' or 'alternate', got {self.kinds!r}")


def uniform_structure(n_actions: int, seed: Seed = None, params: UniformParams | None = None) -> Node:
    """A random normalised structure of ``n_actions`` leaves ``step_1 … step_n`` (numbered depth first).

    Each node splits its leaves into 2 to ``max_children`` non-empty runs, cut at uniformly drawn points;
    runs of one leaf become actions. Chains drawn inside chains are merged into them (normal form), so chains
    tend to be longer than ``max_children``.

    Args:
        n_actions: Number of leaves (at least 1).
        seed: Seed or generator (see :mod:`supportive.seeding`).
        params: Knobs; defaults when omitted.

    Raises:
        GenerationError: when ``n_actions`` is below 1.
    """
    if n_actions < 1:
        raise GenerationError(f"n_actions must be at least 1, got {n_actions}")
    params = params or UniformParams()
    rng = rng_from(seed)
    names = (f"step_{i}" for i in itertools.count(1))
    clique = bool(rng.random() < params.clique_probability)
    return normalise(_split(n_actions, clique, rng, params, names))


def _split(
    n: int, clique: bool, rng: np.random.Generator, params: UniformParams, names: Iterator[str]
) -> Node:
    if n == 1:
        return ActionNode(next(names))
    k = int(rng.integers(2, min(params.max_children, n) + 1))
    cuts = np.sort(rng.choice(n - 1, size=k - 1, replace=False) + 1)
    sizes = np.diff(np.concatenate(([0], cuts, [n])))
    children = []
    for size in sizes:
        if params.kinds == "alternate":
            child_clique = not clique
        else:
            child_clique = bool(rng.random() < params.clique_probability)
        children.append(_split(int(size), child_clique, rng, params, names))
    return CliqueNode(tuple(children)) if clique else ChainNode(tuple(children))
