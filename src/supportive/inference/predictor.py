"""What comes next: a next-step predictor over action ids, learned from demonstrations.

``StepPredictor().fit(demonstrations)`` learns the hierarchy and its frequencies with
:class:`~supportive.learning.learner.HTNLearner`; ``next_step(prefix)`` runs the progress-aware tracker
(:class:`~supportive.inference.tracker.ProgressFilter`) over the known actions of ``prefix`` and returns the
probability of each action id being done next, plus ``"<end>"`` for "the task is finished"; the
probabilities add up to one. Unknown actions in ``prefix`` are slips, not errors.

**Calibrated, not only accurate.** What the hierarchy says is mixed with an add-one smoothed bigram whose
transition counts go only to actions still open (:class:`~supportive.inference.bigram.OpenBigram`), so a step it
did not expect still has a probability but a step already done is not pushed to the top by the transitions that
led to it the first time, and its choices are smoothed by ``smoothing`` pseudo-counts per option. How much the
bigram weighs depends on whether the tracker could follow the last step: ``backoff`` when it was on script,
``off_script_backoff`` when it was off script (a step the hierarchy did not admit there: after it the tracker's
reading of where the person is may be wrong, and what usually follows the step just done is the better guess),
mixed by the tracker's probability that it was off script (``ProgressBelief.off_script``). All three are fitted
inside ``fit`` by K-fold cross-validation over the demonstrations (``calibration_folds``; the combination of the
grids with the highest held-out log-likelihood of the next step), unless given; with fewer than three
demonstrations there is nothing to hold out and the first values of the grids apply (see :class:`StepPredictor`).

>>> predictor = StepPredictor().fit([["knife", "carrots", "celery"], ["knife", "celery", "carrots"]] * 2)
>>> {a: round(p, 2) for a, p in predictor.next_step(["knife", "carrots"]).items() if p > 0.1}
{'celery': 0.98}
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any, Self

import numpy as np
import numpy.typing as npt

from supportive.errors import LearningError
from supportive.estimator import Estimator
from supportive.inference.bigram import OpenBigram
from supportive.inference.tracker import END_LABEL, ProgressFilter, ProgressHMM
from supportive.learning.learner import DemonstrationLike, HTNLearner, Mode
from supportive.tasks.htn import HTN, ActionNode
from supportive.tasks.spec import Demonstration, TaskSpec

__all__ = ["END_LABEL", "Calibration", "PredictionSession", "StepPredictor"]

_LEARNER = (
    "mode", "slips", "slip_margin", "slip_rate", "slip_rate_weight", "order_concentration", "max_slip_candidates",
    "evidence",
    "order_support", "subtask_demonstrations", "selection_folds", "selection_demonstrations",
)
_TRACKER = ("slip", "restart", "max_states", "beam")


@dataclass(frozen=True)
class Calibration:
    """How ``smoothing``, ``backoff`` and ``off_script_backoff`` were chosen.

    Attributes:
        smoothing: The pseudo-counts kept.
        backoff: The bigram's weight kept after a step the tracker followed.
        off_script_backoff: The bigram's weight kept after a step the tracker read as off script.
        folds: Folds of the cross-validation (0: not fitted, the values given or the grids' first).
        steps: Held-out steps scored.
        log2: Mean held-out ``log2`` probability of the next step, ``log2[i][j][k]`` for the ``i``-th
            smoothing, ``j``-th back-off weight and ``k``-th off-script back-off weight tried, as the grids
            list them (a setting given: its value alone).
    """

    smoothing: float
    backoff: float
    off_script_backoff: float
    folds: int = 0
    steps: int = 0
    log2: tuple[tuple[tuple[float, ...], ...], ...] = ()

    def as_dict(self) -> dict[str, object]:
        """Plain-data form."""
        return {
            "smoothing": self.smoothing,
            "backoff": self.backoff,
            "off_script_backoff": self.off_script_backoff,
            "folds": self.folds,
            "held_out_steps": self.steps,
            "held_out_log2": [[[round(v, 4) for v in row] for row in table] for table in self.log2],
        }


class StepPredictor(Estimator):
    """Next-step prediction (see the module docstring).

    Args:
        mode, slips, slip_margin, slip_rate, slip_rate_weight, order_concentration, max_slip_candidates, evidence,
            order_support, order_penalty,
            subtask_demonstrations, selection_folds, selection_demonstrations: The hierarchy learner's settings
            (see :class:`HTNLearner`); None (the default) keeps the learner's own default — except
            ``order_penalty``, whose default is the learner's (1 nat; a test holds the two together) and whose
            None asks for the coin test, as in :class:`HTNLearner`.
        slip, restart, max_states, beam: The tracker's settings (see :class:`ProgressHMM`); None keeps its
            default.
        smoothing: Pseudo-counts per option of every choice, above 0; None: fitted.
        backoff: The bigram's weight after a step the tracker followed, in [0, 1); None: fitted.
        off_script_backoff: The bigram's weight after a step the tracker read as off script, in [0, 1); None:
            fitted. Between the two, the weight is mixed by the tracker's probability that the last step was
            off script.
        smoothing_grid: The smoothing values tried when fitting it (the first used when there is too little to
            fit on).
        backoff_grid: The weights tried for ``backoff`` and ``off_script_backoff`` (the first used for both
            when there is too little to fit on).
        calibration_folds: At most this many folds, at least 2.

    Raises:
        LearningError: for a setting the learner, the tracker or the predictor refuses (at once, not at
            ``fit``).

    Attributes (after ``fit``):
        learner_: The fitted hierarchy learner.
        model_: The progress-aware model over its hierarchy.
        bigram_: The back-off.
        calibration_: How ``smoothing`` and ``backoff`` were chosen.
    """

    def __init__(
        self,
        *,
        mode: Mode | None = None,
        slips: bool | None = None,
        slip_margin: float | None = None,
        slip_rate: float | None = None,
        slip_rate_weight: float | None = None,
        order_concentration: float | None = None,
        max_slip_candidates: int | None = None,
        evidence: float | None = None,
        order_support: int | None = None,
        order_penalty: float | None = 1.0,
        subtask_demonstrations: int | None = None,
        selection_folds: int | None = None,
        selection_demonstrations: int | None = None,
        slip: float | None = None,
        restart: bool | None = None,
        max_states: int | None = None,
        beam: int | None = None,
        smoothing: float | None = None,
        backoff: float | None = None,
        off_script_backoff: float | None = None,
        smoothing_grid: tuple[float, ...] = (1.0, 0.25, 4.0),
        backoff_grid: tuple[float, ...] = (0.1, 0.0, 0.01, 0.03, 0.2, 0.35, 0.5, 0.7, 0.9),
        calibration_folds: int = 5,
    ) -> None:
        if smoothing is not None and not smoothing > 0:
            raise LearningError(f"smoothing must be above 0, got {smoothing}")
        for name, weight in (("backoff", backoff), ("off_script_backoff", off_script_backoff)):
            if weight is not None and not 0.0 <= weight < 1.0:
                raise LearningError(f"{name} must be in [0, 1), got {weight}")
        if not smoothing_grid or not all(v > 0 for v in smoothing_grid):
            raise LearningError(f"smoothing_grid must hold values above 0, got {smoothing_grid}")
        if not backoff_grid or not all(0.0 <= v < 1.0 for v in backoff_grid):
            raise LearningError(f"backoff_grid must hold values in [0, 1), got {backoff_grid}")
        if calibration_folds < 2:
            raise LearningError("calibration_folds must be at least 2")
        self.mode = mode
        self.slips = slips
        self.slip_margin = slip_margin
        self.slip_rate = slip_rate
        self.slip_rate_weight = slip_rate_weight
        self.order_concentration = order_concentration
        self.max_slip_candidates = max_slip_candidates
        self.evidence = evidence
        self.order_support = order_support
        self.order_penalty = order_penalty
        self.subtask_demonstrations = subtask_demonstrations
        self.selection_folds = selection_folds
        self.selection_demonstrations = selection_demonstrations
        self.slip = slip
        self.restart = restart
        self.max_states = max_states
        self.beam = beam
        self.smoothing = smoothing
        self.backoff = backoff
        self.off_script_backoff = off_script_backoff
        self.smoothing_grid = smoothing_grid
        self.backoff_grid = backoff_grid
        self.calibration_folds = calibration_folds
        self._learner()  # the learner and the tracker check their settings now, not at fit
        self._hmm(HTN("", (ActionNode("a"),)), 1.0, build=False)

    def _given(self, names: tuple[str, ...]) -> dict[str, Any]:
        """The settings among ``names`` that were given (not None)."""
        return {name: getattr(self, name) for name in names if getattr(self, name) is not None}

    def fit(self, demonstrations: TaskSpec | Iterable[DemonstrationLike]) -> Self:
        """Learn the hierarchy, its frequencies, the back-off and the tracker from demonstrations (a task spec
        or step sequences of action ids), and fit ``smoothing``, ``backoff`` and ``off_script_backoff`` when
        not given."""
        self._forget()
        demos = list(demonstrations.demonstrations if isinstance(demonstrations, TaskSpec) else demonstrations)
        self.learner_ = self._learner().fit(demonstrations)
        self.bigram_ = OpenBigram().fit(demos)
        self.calibration_ = self._calibrate(demos)
        self.model_ = self._hmm(self.learner_.htn_, self.calibration_.smoothing)
        return self

    def tracker(self) -> ProgressFilter:
        """A fresh tracker over the fitted model (the hierarchy's own belief, without the back-off).

        Raises:
            NotFittedError: before ``fit``.
        """
        return self.model_.filter()

    def session(self) -> PredictionSession:
        """A fresh prediction, step by step (``observe`` each action, ``next_step`` for what comes next)."""
        calibration = self.calibration_
        return PredictionSession(self.tracker(), self.bigram_, calibration.backoff, calibration.off_script_backoff)

    def next_step(self, prefix: Sequence[str]) -> dict[str, float]:
        """Probability of each action id being done next after ``prefix``, and of ``"<end>"``."""
        running = self.session()
        for action in prefix:
            running.observe(action)
        return running.next_step()

    # ------------------------------------------------------------------ fitting
    def _learner(self, reading: str | None = None) -> HTNLearner:
        """The hierarchy learner; ``reading`` fixes its mode (the folds of the calibration keep the reading
        chosen on all the demonstrations rather than choosing again)."""
        settings = self._given(_LEARNER)
        if reading is not None:
            settings["mode"] = reading
        return HTNLearner(alternatives=0, order_penalty=self.order_penalty, **settings)

    def _hmm(self, htn: HTN, smoothing: float, *, build: bool = True) -> ProgressHMM:
        """The tracker's model over ``htn``, fitted unless ``build`` is False (then only its settings are
        checked)."""
        hmm = ProgressHMM(htn, smoothing=smoothing, **self._given(_TRACKER))
        return hmm.fit() if build else hmm

    def _calibrate(self, demos: Sequence[DemonstrationLike]) -> Calibration:
        """Choose ``smoothing``, ``backoff`` and ``off_script_backoff`` by the held-out log-likelihood of the
        next step."""
        smoothings = [self.smoothing] if self.smoothing is not None else list(self.smoothing_grid)
        on = np.asarray([self.backoff] if self.backoff is not None else self.backoff_grid, dtype=float)
        off = np.asarray([self.off_script_backoff] if self.off_script_backoff is not None else self.backoff_grid, dtype=float)
        if len(demos) < 3 or len(smoothings) * len(on) * len(off) == 1:
            return Calibration(float(smoothings[0]), float(on[0]), float(off[0]))
        k = min(self.calibration_folds, len(demos))
        totals = np.zeros((len(smoothings), len(on), len(off)))
        steps = 0
        for fold in range(k):
            train = [d for i, d in enumerate(demos) if i % k != fold]
            held = [_actions(d) for i, d in enumerate(demos) if i % k == fold]
            htn = self._learner(self.learner_.reading_).fit(train).htn_
            bigram = OpenBigram().fit(train)
            for row, smoothing in enumerate(smoothings):
                hmm = self._hmm(htn, float(smoothing))
                for actions in held:
                    model, back, lost = _truth_probabilities(hmm.filter(), bigram, actions)
                    weight = _weight(on[None, :, None], off[None, None, :], lost[:, None, None])
                    mixed = model[:, None, None] + weight * (back - model)[:, None, None]
                    totals[row] += np.log2(np.maximum(mixed, 1e-300)).sum(axis=0)
                    if row == 0:
                        steps += len(actions) + 1
        best = np.unravel_index(int(np.argmax(totals)), totals.shape)
        table = tuple(tuple(tuple(float(v) / steps for v in row) for row in grid) for grid in totals)
        return Calibration(float(smoothings[best[0]]), float(on[best[1]]), float(off[best[2]]), k, steps, table)


class PredictionSession:
    """One prediction step by step: the tracker's belief of what comes next, mixed with the back-off by how
    likely the tracker finds it that the last step was off script."""

    def __init__(self, tracker: ProgressFilter, bigram: OpenBigram, backoff: float, off_script_backoff: float) -> None:
        self.tracker = tracker
        self.bigram = bigram
        self.backoff = backoff
        self.off_script_backoff = off_script_backoff
        self.prefix: list[str] = []

    def observe(self, action: str) -> None:
        """One more completed action."""
        self.tracker.observe(action)
        self.prefix.append(action)

    def next_step(self) -> dict[str, float]:
        """Probability of each action id being done next, and of ``"<end>"``; sums to one."""
        last = self.tracker.last
        weight = float(_weight(self.backoff, self.off_script_backoff, last.off_script))
        return _mixed(last.next_actions, self.bigram.next_step(self.prefix), weight)


def _weight(backoff: npt.ArrayLike, off_script_backoff: npt.ArrayLike, off_script: npt.ArrayLike) -> np.ndarray:
    """The back-off's weight when the last step was off script with probability ``off_script`` (numbers, or
    arrays that broadcast: the whole grid of the cross-validation at once)."""
    lost = np.asarray(off_script, dtype=float)
    weight: np.ndarray = (1.0 - lost) * np.asarray(backoff, dtype=float) + lost * np.asarray(off_script_backoff, dtype=float)
    return weight


def _mixed(model: dict[str, float], back: dict[str, float], weight: float) -> dict[str, float]:
    if weight == 0.0:
        return dict(model)
    keys = dict.fromkeys([*model, *back])
    return {a: (1.0 - weight) * model.get(a, 0.0) + weight * back.get(a, 0.0) for a in keys}


def _truth_probabilities(
    running: ProgressFilter, bigram: OpenBigram, actions: Sequence[str]
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The probability the tracker and the bigram gave each next step of ``actions`` (and its end), and the
    tracker's probability that the step before was off script (0 before the first)."""
    model, back, lost = [], [], []
    for position in range(len(actions) + 1):
        truth = actions[position] if position < len(actions) else END_LABEL
        model.append(running.last.next_actions.get(truth, 0.0))
        back.append(bigram.next_step(actions[:position]).get(truth, 0.0))
        lost.append(running.last.off_script)
        if position < len(actions):
            running.observe(truth)
    return np.asarray(model), np.asarray(back), np.asarray(lost)


def _actions(demo: DemonstrationLike) -> tuple[str, ...]:
    return demo.actions if isinstance(demo, Demonstration) else tuple(demo)

