"""CaptainCook4D next-step prediction: one recipe per trial, leave one out over all its recordings."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from supportive.errors import ExperimentError
from supportive.evaluation import StepScores, evaluate_task
from supportive.evaluation.baselines import BASELINES
from supportive.evaluation.crossval import PREDICTOR
from supportive.experiments.trials import Trial, spawn_trials
from supportive.io.captaincook import load_captaincook

__all__ = ["DEFAULT_TRIALS", "MODELS", "RECIPES", "make_trials", "run_trial", "summarize"]

RECIPES = 24
"""Recipes of the dataset: one trial each."""
DEFAULT_TRIALS = RECIPES
"""Trials of a full run: every recipe."""
MODELS = (PREDICTOR, *BASELINES)
"""The predictors compared, the progress-aware one first."""


def make_trials(trials: int, seed: int) -> tuple[Trial, ...]:
    """Trial ``i`` is the ``i``-th recipe (by name); fewer trials take the first ones."""
    if not 1 <= trials <= RECIPES:
        raise ExperimentError(f"captaincook-prediction: trials must be 1..{RECIPES}, got {trials}")
    return spawn_trials(seed, [{"recipe": i} for i in range(trials)])


def run_trial(trial: Trial) -> dict[str, Any]:
    """Leave one out over every recording of the trial's recipe (errors included)."""
    recipe = load_captaincook(errors=True)[int(trial.params["recipe"])]
    evaluation = evaluate_task(recipe.spec, seed=trial.rng())
    result = evaluation.as_dict()
    result["sums"] = {name: vars(scores) for name, scores in evaluation.prediction.items()}
    return {"index": trial.index, **result}


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Every model's scores over all steps of all recipes, held-out admission, and each recipe's row."""
    if not results:
        raise ExperimentError("captaincook-prediction: no trial results to summarise")
    totals = {name: StepScores() for name in MODELS}
    for result in results:
        for name in MODELS:
            totals[name].merge(StepScores(**result["sums"][name]))
    held = sum(int(r["held_out"]) for r in results)
    admitted = sum(int(r["admitted"]) for r in results)
    return {
        "models": {name: scores.as_dict() for name, scores in totals.items()},
        "admission": {"held_out": held, "admitted": admitted, "share": round(admitted / held, 4)},
        "recipes": [{k: v for k, v in r.items() if k != "sums"} for r in results],
    }
