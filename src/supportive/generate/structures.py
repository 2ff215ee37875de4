"""Random chain/clique structures: one entry point over the generation profiles."""

from __future__ import annotations

from typing import Literal

from supportive.errors import GenerationError
from supportive.generate.ikea import IkeaParams, ikea_structure
from supportive.generate.uniform import UniformParams, uniform_structure
from supportive.seeding import Seed
from supportive.tasks.htn import Node

__all__ = ["Profile", "random_structure"]

Profile = Literal["ikea", "uniform"]
"""A generation profile: ``"ikea"`` (assembly-like, §2.1.7.2) or ``"uniform"`` (random splits)."""


def random_structure(
    n_actions: int,
    seed: Seed = None,
    *,
    profile: Profile = "ikea",
    params: IkeaParams | UniformParams | None = None,
) -> Node:
    """A random normalised chain/clique structure with exactly ``n_actions`` distinct leaves.

    Normalised means every chain and clique has at least two children and no chain is directly inside a
    chain (a clique directly inside a clique is allowed: it forbids interleaving). The same seed gives the
    same structure.

    Args:
        n_actions: Number of leaves (at least 1).
        seed: Seed or generator (see :mod:`supportive.seeding`).
        profile: ``"ikea"`` (:func:`~supportive.generate.ikea.ikea_structure`) or ``"uniform"``
            (:func:`~supportive.generate.uniform.uniform_structure`).
        params: The profile's knobs (:class:`IkeaParams` or :class:`UniformParams`); defaults when omitted.

    Raises:
        GenerationError: for an unknown profile, params of the other profile, or ``n_actions`` below 1.

    >>> from supportive.tasks.htn import leaf_actions
    >>> len(set(leaf_actions(random_structure(40, seed=1))))
    40
    """
    if profile == "ikea":
        if params is not None and not isinstance(params, IkeaParams):
            raise GenerationError(f"profile 'ikea' takes IkeaParams, got {type(params).__name__}")
        return ikea_structure(n_actions, seed, params)
    if profile == "uniform":
        if params is not None and not isinstance(params, UniformParams):
            raise GenerationError(f"profile 'uniform' takes UniformParams, got {type(params).__name__}")
        return uniform_structure(n_actions, seed, params)
    raise GenerationError(f"unknown profile {profile!r}: expected 'ikea' or 'uniform'")
