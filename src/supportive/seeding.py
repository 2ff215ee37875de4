"""One seed convention for everything random: ``seed: int | numpy.random.Generator | None``."""

from __future__ import annotations

import random
from typing import TypeAlias

import numpy as np

__all__ = ["Seed", "rng_from", "stdlib_random"]

Seed: TypeAlias = int | np.random.Generator | None


def rng_from(seed: Seed) -> np.random.Generator:
    """A generator for ``seed``: a given Generator is used as is, an int or None seeds a new PCG64.

    >>> bool(rng_from(7).integers(100) == rng_from(7).integers(100))
    True
    """
    if isinstance(seed, np.random.Generator):
        return seed
    return np.random.default_rng(seed)


def stdlib_random(seed: Seed) -> random.Random:
    """A :class:`random.Random` for ``seed``, for code whose published numbers come from the standard library's
    generator (the transfer experiment's Q-learning): an int gives ``random.Random(seed)`` (the same numbers as
    ever), a Generator seeds one from its next draw, None a fresh one.

    >>> stdlib_random(3).random() == random.Random(3).random()
    True
    """
    if isinstance(seed, np.random.Generator):
        return random.Random(int(seed.integers(2**63)))
    return random.Random(seed)
