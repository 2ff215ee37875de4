"""Cross-validation a user runs on their own demonstrations: how well the learned hierarchy generalises to
recordings it has not seen, how well the next-step predictor and simple baselines predict them, and how well
the online mistake detector finds labelled mistakes (:func:`evaluate_mistakes`, on the hierarchy
:func:`detection_model` learns)."""

from supportive.evaluation.baselines import BASELINES, Bigram, MaskedBigram, MostFrequentNotDone
from supportive.evaluation.crossval import Evaluation, StepScores, evaluate_task, folds
from supportive.evaluation.mistakes import MistakeEvaluation, detection_model, evaluate_mistakes

__all__ = [
    "BASELINES",
    "Bigram",
    "Evaluation",
    "MaskedBigram",
    "MistakeEvaluation",
    "MostFrequentNotDone",
    "StepScores",
    "detection_model",
    "evaluate_mistakes",
    "evaluate_task",
    "folds",
]
