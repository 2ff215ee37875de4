"""One short household episode played twice from the same seed, with and without the caregiver, and the
moment the caregiver first made a difference."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from supportive.safety.episode import Frame, run_episode
from supportive.seeding import Seed
from supportive.worlds.household import Collision, load_map

__all__ = ["CaregiverContrast", "caregiver_contrast"]


@dataclass(frozen=True)
class CaregiverContrast:
    """One short household episode played twice from the same seed, with and without the caregiver.

    Attributes:
        map_name: The map played on.
        epsilon: The novice's share of random moves.
        steps: Novice steps per episode.
        with_caregiver: Damage with the caregiver; ``without``: damage alone.
        frames: The caregiver episode's frames around the first step where the two runs differ (or its first
            steps, when they never do).
        moment: That step, or None.
        bumps: What the novice bumped into at that step with and without the caregiver (None: nothing).
    """

    map_name: str
    epsilon: float
    steps: int
    with_caregiver: int
    without: int
    frames: tuple[Frame, ...]
    moment: int | None
    bumps: tuple[Collision | None, Collision | None] = (None, None)


def caregiver_contrast(
    map_name: str = "playroom", epsilon: float = 0.75, steps: int = 40, seed: Seed = 8
) -> CaregiverContrast:
    """Play a novice on ``map_name`` with and without the caregiver (common random numbers: the same seed gives
    the same start and first goal; a generator gives one seed for both), and pick the frames where the
    caregiver first made a difference."""
    if isinstance(seed, np.random.Generator):
        seed = int(seed.integers(2**63))
    grid = load_map(map_name)
    helped = run_episode(grid, epsilon, caregiver=True, steps=steps, seed=seed, record=True)
    alone = run_episode(grid, epsilon, caregiver=False, steps=steps, seed=seed, record=True)
    moment = next(
        (a.step for a, b in zip(helped.frames, alone.frames, strict=True) if a.collision != b.collision), None
    )
    end = moment if moment is not None else 2
    frames = helped.frames[max(0, end - 2) : end]
    bumps = (
        (helped.frames[moment - 1].collision, alone.frames[moment - 1].collision)
        if moment is not None
        else (None, None)
    )
    return CaregiverContrast(map_name, epsilon, steps, helped.damage, alone.damage, frames, moment, bumps)
