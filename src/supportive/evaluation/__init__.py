"""Cross-validation a user runs on their own demonstrations: how well the learned hierarchy generalises to
recordings it has not seen, and how well the next-step predictor and simple baselines predict them."""

from supportive.evaluation.baselines import BASELINES, Bigram, MaskedBigram, MostFrequentNotDone
from supportive.evaluation.crossval import Evaluation, StepScores, evaluate_task, folds

__all__ = [
    "BASELINES",
    "Bigram",
    "Evaluation",
    "MaskedBigram",
    "MostFrequentNotDone",
    "StepScores",
    "evaluate_task",
    "folds",
]
