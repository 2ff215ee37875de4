"""What comes next: a next-step predictor over action ids, learned from demonstrations.

``StepPredictor(**settings).fit(demonstrations)`` learns the hierarchy and its frequencies with the general
learner (:class:`~supportive.learning.learner.HTNLearner`), then ``next_step(prefix)`` runs the
progress-aware tracker (:class:`~supportive.inference.tracker.ProgressFilter`) over the known actions of
``prefix`` and returns the probability of each action id being done next, plus ``"<end>"`` for "the task is
finished"; the probabilities add up to one. Unknown actions in ``prefix`` are slips, not errors.

>>> predictor = StepPredictor().fit([["knife", "carrots", "celery"], ["knife", "celery", "carrots"]] * 2)
>>> {a: round(p, 2) for a, p in predictor.next_step(["knife", "carrots"]).items() if p > 0.1}
{'celery': 0.98}
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any, Self

from supportive.estimator import Estimator
from supportive.inference.tracker import END_LABEL, ProgressFilter, ProgressHMM
from supportive.learning.learner import DemonstrationLike, HTNLearner
from supportive.tasks.spec import TaskSpec

__all__ = ["END_LABEL", "StepPredictor"]

_LEARNER = (
    "mode", "slips", "slip_margin", "slip_rate", "slip_rate_weight", "max_slip_candidates", "evidence",
    "order_support", "subtask_demonstrations",
)
_TRACKER = ("smoothing", "slip", "restart", "max_states", "beam")


class StepPredictor(Estimator):
    """Next-step prediction (see the module docstring).

    Args:
        **settings: Learner settings (``mode``, ``slips``, ``slip_margin``, ``slip_rate``,
            ``slip_rate_weight``, ``max_slip_candidates``, ``evidence``, ``order_support``,
            ``subtask_demonstrations``; see :class:`HTNLearner`) and tracker settings (``smoothing``,
            ``slip``, ``restart``, ``max_states``, ``beam``; see :class:`ProgressHMM`).

    Attributes (after ``fit``):
        learner_: The fitted hierarchy learner.
        model_: The progress-aware model over its hierarchy.
    """

    def __init__(self, **settings: Any) -> None:
        unknown = sorted(set(settings) - set(_LEARNER) - set(_TRACKER))
        if unknown:
            raise TypeError(f"StepPredictor got unknown setting(s): {', '.join(unknown)}")
        self.settings = dict(settings)

    def fit(self, demonstrations: TaskSpec | Iterable[DemonstrationLike]) -> Self:
        """Learn the hierarchy, its frequencies and the tracker from demonstrations (a task spec or step
        sequences of action ids)."""
        learner_settings = {k: v for k, v in self.settings.items() if k in _LEARNER}
        tracker_settings = {k: v for k, v in self.settings.items() if k in _TRACKER}
        self._forget()
        self.learner_ = HTNLearner(alternatives=0, **learner_settings).fit(demonstrations)
        self.model_ = ProgressHMM(self.learner_.htn_, **tracker_settings).fit()
        return self

    def tracker(self) -> ProgressFilter:
        """A fresh tracker over the fitted model (for predictions step by step).

        Raises:
            NotFittedError: before ``fit``.
        """
        return self.model_.filter()

    def next_step(self, prefix: Sequence[str]) -> dict[str, float]:
        """Probability of each action id being done next after ``prefix``, and of ``"<end>"``."""
        running = self.tracker()
        for action in prefix:
            running.observe(action)
        return dict(running.last.next_actions)
