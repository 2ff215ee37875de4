"""One seed convention for everything random: ``seed: int | numpy.random.Generator | None``."""

from __future__ import annotations

from typing import TypeAlias

import numpy as np

__all__ = ["Seed", "rng_from"]

Seed: TypeAlias = int | np.random.Generator | None


def rng_from(seed: Seed) -> np.random.Generator:
    """A generator for ``seed``: a given Generator is used as is, an int or None seeds a new PCG64.

    >>> bool(rng_from(7).integers(100) == rng_from(7).integers(100))
    True
    """
    if isinstance(seed, np.random.Generator):
        return seed
    return np.random.default_rng(seed)
