"""Running the caregiver experiment: one trial = one episode of every novice type, with and without the
caregiver, from the same seed (common random numbers)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from supportive.envs.household.grid_map import load_map
from supportive.envs.household.novice import NOVICE_TYPES
from supportive.experiments.trials import Trial, spawn_trials
from supportive.safety.episode import EPISODE_STEPS, THRESHOLD, run_episode

__all__ = ["CONDITIONS", "MAP", "make_trials", "run_trial"]

MAP = "house"
"""The shipped map the experiment runs on (modelled on Figure 3.13)."""
CONDITIONS = ("without", "with")
"""Without and with the caregiver."""


def make_trials(trials: int, seed: int) -> Sequence[Trial]:
    """``trials`` episodes per novice type (the thesis: 20), each trial with its own seed."""
    params = {"map": MAP, "steps": EPISODE_STEPS, "threshold": THRESHOLD}
    return spawn_trials(seed, [dict(params) for _ in range(trials)])


def run_trial(trial: Trial) -> dict[str, Any]:
    """One episode per novice type and condition; damage, steps until the threshold, cells explored."""
    grid = load_map(str(trial.params.get("map", MAP)))
    steps = int(trial.params.get("steps", EPISODE_STEPS))
    threshold = int(trial.params.get("threshold", THRESHOLD))
    seeds = trial.seed.spawn(len(NOVICE_TYPES))
    out: dict[str, Any] = {}
    for (label, epsilon), seed in zip(NOVICE_TYPES.items(), seeds, strict=True):
        out[label] = {}
        for condition in CONDITIONS:
            result = run_episode(
                grid, epsilon, caregiver=condition == "with", steps=steps, threshold=threshold,
                seed=np.random.default_rng(seed),
            )
            out[label][condition] = {
                "damage": result.damage,
                "steps": result.steps,
                "reached_threshold": result.reached_threshold,
                "cells": result.cells_explored,
                "collisions": result.collisions,
            }
    return {"index": trial.index, "map": grid.name, "novices": out}
