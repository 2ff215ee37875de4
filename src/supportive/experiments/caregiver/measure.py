"""Running the caregiver experiment: one trial = one episode of every novice type without the caregiver and,
from the same seed, with it under each reading of P(safe | τ) (common random numbers).

**Readings** (:data:`READINGS`): how much of the novice's trajectory the caregiver's P(safe | τ) weighs, the
memory γ of :class:`~supportive.safety.safe_probability.SafetyEstimate` (each step the log-odds' distance
from the prior's is multiplied by γ before the new move is added, so roughly the last 1/(1 − γ) moves count).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from supportive.experiments.readings import Reading, reading_names
from supportive.experiments.trials import Trial, spawn_trials
from supportive.safety.episode import EPISODE_STEPS, THRESHOLD, run_episode
from supportive.worlds.household.grid_map import load_map
from supportive.worlds.household.novice import NOVICE_TYPES

__all__ = ["CONDITIONS", "DEFAULT_TRIALS", "MAP", "MEMORIES", "READINGS", "make_trials", "run_trial"]

MAP = "house"
"""The shipped map the experiment runs on (modelled on Figure 3.13)."""
CONDITIONS = ("without", "with")
"""Without and with the caregiver."""
DEFAULT_TRIALS = 100
"""Episodes per novice type and condition in a full run. The thesis ran 20; at about one damage point per
episode for the most goal-directed novice, 20 episodes leave its reduction to chance (§ docs/caregiver.md)."""

READINGS = (
    Reading(
        "trajectory",
        "γ 1: P(safe | τ) is Eq. 3.2 over the whole trajectory",
        "Eq. 3.2 as printed: the product of θ over every step k = 1 … t of the trajectory \"taken by the "
        "novice thus far\", \"the probability that the trajectory followed by the novice was drawn from a "
        "model of normal motion\". The equation is the most specific text, so this is the default.",
    ),
    Reading(
        "memory",
        "γ 0.9: roughly the last ten moves count",
        "Not in the thesis: this project's earlier choice (and the library's default, "
        "`supportive.safety.caregiver.MEMORY`), made because Eq. 3.2 over 200 steps saturates and a mostly "
        "goal-directed novice is then judged safe for good.",
    ),
    Reading(
        "per-step",
        "γ 0.5: a short-memory estimate of whether this step's action is safe",
        "§3.5.3: \"P(safe) is the prior belief that the agent is choosing a safe action at each timestep\" — "
        "read as a belief about the current step, which only the last few moves inform.",
    ),
)
"""How much of the trajectory P(safe | τ) weighs, as named readings; the first (``trajectory``) is the default."""
MEMORIES = {"trajectory": 1.0, "memory": 0.9, "per-step": 0.5}
"""Each reading's γ."""


def make_trials(trials: int, seed: int, readings: Sequence[str] | None = None) -> Sequence[Trial]:
    """``trials`` episodes per novice type, each trial with its own seed, the caregiver under ``readings``
    (default: all of :data:`READINGS`)."""
    chosen = list(readings if readings is not None else reading_names(READINGS))
    params = {"map": MAP, "steps": EPISODE_STEPS, "threshold": THRESHOLD, "readings": chosen}
    return spawn_trials(seed, [dict(params) for _ in range(trials)])


def run_trial(trial: Trial) -> dict[str, Any]:
    """One episode per novice type without the caregiver and one with it per reading, all from the novice
    type's seed; damage, steps until the threshold, cells explored."""
    grid = load_map(str(trial.params.get("map", MAP)))
    steps = int(trial.params.get("steps", EPISODE_STEPS))
    threshold = int(trial.params.get("threshold", THRESHOLD))
    readings = trial.params.get("readings", reading_names(READINGS))
    seeds = trial.children(len(NOVICE_TYPES))

    def episode(epsilon: float, seed: np.random.SeedSequence, memory: float | None) -> dict[str, Any]:
        # A fresh copy of the novice type's seed for every episode: a SeedSequence counts the children it
        # spawned, so reusing one object would give each episode other streams (no common random numbers).
        rng = np.random.default_rng(
            np.random.SeedSequence(seed.entropy, spawn_key=seed.spawn_key, pool_size=seed.pool_size)
        )
        result = (
            run_episode(grid, epsilon, caregiver=False, steps=steps, threshold=threshold, seed=rng)
            if memory is None
            else run_episode(grid, epsilon, steps=steps, threshold=threshold, seed=rng, memory=memory)
        )
        return {
            "damage": result.damage,
            "steps": result.steps,
            "reached_threshold": result.reached_threshold,
            "cells": result.cells_explored,
            "collisions": result.collisions,
        }

    out: dict[str, Any] = {}
    for (label, epsilon), seed in zip(NOVICE_TYPES.items(), seeds, strict=True):
        out[label] = {
            "without": episode(epsilon, seed, None),
            "with": {name: episode(epsilon, seed, MEMORIES[name]) for name in readings},
        }
    return {"index": trial.index, "map": grid.name, "novices": out}
