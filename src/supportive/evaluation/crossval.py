"""Cross-validation of one task's demonstrations: learn from the training folds, test on the held-out one.

For every held-out demonstration:

* **learning**: does the hierarchy learned from the others admit it; where the task has a ground-truth
  ``structure``, the recall (share of its valid orderings admitted) and precision (share of admitted
  orderings that are valid) of the learned hierarchy, when both languages are small enough to list;
* **prediction**: at each step (and after the last, where the truth is ``<end>``), the next-step predictor's
  and each baseline's probability of what was done next: top-1 and top-3 hits, probability 0, ``log2`` of it,
  and for the predictor whether its top-1 is an action already done as often as any training demonstration
  does it.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from supportive.evaluation.baselines import BASELINES, END
from supportive.inference.predictor import StepPredictor
from supportive.seeding import Seed, rng_from
from supportive.tasks.executions import Executions, Progress
from supportive.tasks.htn import HTN, Leaf, Node, count_orderings, iter_orderings
from supportive.tasks.spec import TaskSpec

__all__ = ["ENUMERATION_LIMIT", "RELIABILITY_BINS", "Evaluation", "StepScores", "evaluate_task", "folds"]

RELIABILITY_BINS = 10
"""The reliability table splits the top-1 probability into this many equal bins."""

ENUMERATION_LIMIT = 20_000
"""Recall and precision of orderings are computed when both languages have at most this many sequences."""

PREDICTOR = "progress-aware"


@dataclass
class StepScores:
    """Next-step scores of one predictor, summed over steps (see :meth:`as_dict` for the rates).

    ``bins`` is the reliability table's raw sums: for each tenth of the top-1 probability (``[0, 0.1)``, …,
    ``[0.9, 1]``), how many predictions fell in it, the sum of their top-1 probabilities and how many of
    their top-1s were right."""

    steps: int = 0
    top1: int = 0
    top3: int = 0
    zero: int = 0
    log2: float = 0.0
    done_top1: int = 0
    bins: list[list[float]] = field(default_factory=lambda: [[0, 0.0, 0] for _ in range(RELIABILITY_BINS)])

    def add(self, predicted: dict[str, float], truth: str, already_done: set[str]) -> None:
        """Score one prediction against what was done next."""
        ranked = sorted(predicted, key=lambda a: (-predicted[a], a))
        p = predicted.get(truth, 0.0)
        self.steps += 1
        self.top1 += ranked[:1] == [truth]
        self.top3 += truth in ranked[:3]
        self.zero += p <= 0.0
        self.log2 += math.log2(p) if p > 0 else 0.0
        self.done_top1 += bool(ranked) and ranked[0] in already_done
        if ranked:
            confidence = predicted[ranked[0]]
            row = self.bins[min(int(confidence * RELIABILITY_BINS), RELIABILITY_BINS - 1)]
            row[0] += 1
            row[1] += confidence
            row[2] += ranked[0] == truth

    def merge(self, other: StepScores) -> None:
        """Add another's sums to these."""
        self.steps += other.steps
        self.top1 += other.top1
        self.top3 += other.top3
        self.zero += other.zero
        self.log2 += other.log2
        self.done_top1 += other.done_top1
        for mine, theirs in zip(self.bins, other.bins, strict=True):
            for i in range(3):
                mine[i] += theirs[i]

    def reliability(self) -> list[dict[str, float | int]]:
        """The reliability table: for each tenth of the top-1 probability that holds predictions, how many,
        their mean top-1 probability (confidence) and the share whose top-1 was right (accuracy)."""
        return [
            {
                "from": i / RELIABILITY_BINS,
                "to": (i + 1) / RELIABILITY_BINS,
                "predictions": int(n),
                "confidence": round(total / n, 4),
                "accuracy": round(right / n, 4),
            }
            for i, (n, total, right) in enumerate(self.bins)
            if n
        ]

    def calibration_error(self) -> float:
        """Expected calibration error of the top-1 probability: the mean over predictions of
        ``|accuracy - confidence|`` of their tenth (0 for a perfectly calibrated predictor)."""
        n = sum(row[0] for row in self.bins)
        return sum(abs(right - total) for _, total, right in self.bins) / n if n else 0.0

    def as_dict(self) -> dict[str, object]:
        """Rates: ``top1``, ``top3``, ``zero`` (share of steps given probability 0), ``log2`` (mean over the
        steps given a probability above 0, so models that zero some steps can still be compared),
        ``done_top1`` (share whose top-1 was already done), ``ece`` (:meth:`calibration_error`) and
        ``reliability`` (:meth:`reliability`)."""
        n = max(self.steps, 1)
        scored = max(self.steps - self.zero, 1)
        return {
            "steps": self.steps,
            "top1": round(self.top1 / n, 4),
            "top3": round(self.top3 / n, 4),
            "zero": round(self.zero / n, 4),
            "log2": round(self.log2 / scored, 4),
            "done_top1": round(self.done_top1 / n, 4),
            "ece": round(self.calibration_error(), 4),
            "reliability": self.reliability(),
        }


@dataclass
class Evaluation:
    """One task's cross-validation.

    Attributes:
        task: The task's name.
        folds: How many held-out sets were tested.
        held_out: Held-out demonstrations.
        admitted: Held-out demonstrations the hierarchy learned from the rest admits.
        not_admitted: The ids of those it does not admit, in the file's order.
        recall, precision: Mean over folds of the orderings' recall and precision (None: no structure, or
            too many orderings to list).
        prediction: Predictor name -> its scores (the progress-aware predictor and every baseline).
    """

    task: str
    folds: int = 0
    held_out: int = 0
    admitted: int = 0
    not_admitted: list[str] = field(default_factory=list)
    recall: float | None = None
    precision: float | None = None
    prediction: dict[str, StepScores] = field(default_factory=dict)

    def as_dict(self) -> dict[str, object]:
        """Plain data (one entry of ``supportive evaluate --json``)."""
        return {
            "task": self.task,
            "folds": self.folds,
            "held_out": self.held_out,
            "admitted": self.admitted,
            "admission": round(self.admitted / self.held_out, 4) if self.held_out else None,
            "not_admitted": list(self.not_admitted),
            "recall": None if self.recall is None else round(self.recall, 4),
            "precision": None if self.precision is None else round(self.precision, 4),
            "prediction": {name: scores.as_dict() for name, scores in self.prediction.items()},
        }


LEAVE_ONE_OUT_UP_TO = 50
"""``evaluate``'s default: leave one out up to this many demonstrations, :data:`FOLDS_BEYOND` folds above it."""
FOLDS_BEYOND = 10
"""Folds of the default above :data:`LEAVE_ONE_OUT_UP_TO` demonstrations: ten fits, each on 90 % of them, so the
cost grows with the demonstrations rather than with their square (leave one out fits once per demonstration)."""


def default_folds(n: int) -> int | None:
    """The folds ``evaluate`` uses unless told: None (leave one out) for up to :data:`LEAVE_ONE_OUT_UP_TO`
    demonstrations, :data:`FOLDS_BEYOND` above.

    >>> default_folds(50), default_folds(51)
    (None, 10)
    """
    return None if n <= LEAVE_ONE_OUT_UP_TO else FOLDS_BEYOND


def folds(n: int, k: int | None, seed: Seed = 0) -> list[list[int]]:
    """Held-out index sets: one per demonstration (``k`` None: leave one out) or ``k`` shuffled folds.

    >>> folds(3, None)
    [[0], [1], [2]]
    >>> sorted(len(f) for f in folds(5, 2, seed=1))
    [2, 3]
    """
    if k is None or k >= n:
        return [[i] for i in range(n)]
    order = rng_from(seed).permutation(n)
    return [sorted(int(i) for i in part) for part in np.array_split(order, k)]


def evaluate_task(
    spec: TaskSpec,
    *,
    k: int | None = None,
    seed: Seed = 0,
    predictor: StepPredictor | None = None,
    progress: Callable[[], None] | None = None,
) -> Evaluation:
    """Cross-validate ``spec``'s demonstrations (see the module docstring).

    Args:
        spec: A task with at least two demonstrations.
        k: Folds (None: leave one out).
        seed: Seeds the folds.
        predictor: An unfitted :class:`~supportive.inference.predictor.StepPredictor` whose settings every fold
            uses (each fits a copy); None: the defaults.
        progress: Called once per held-out demonstration.
    """
    demos = list(spec.demonstrations)
    result = Evaluation(spec.name)
    result.prediction = {PREDICTOR: StepScores(), **{name: StepScores() for name in BASELINES}}
    truth = HTN(spec.name, (spec.structure,)) if spec.structure is not None else None
    valid = _listed(truth.roots[0]) if truth is not None else None
    recalls: list[float] = []
    precisions: list[float] = []
    for held in folds(len(demos), k, seed):
        training = [d for i, d in enumerate(demos) if i not in held]
        if not training:
            continue
        result.folds += 1
        fitted = StepPredictor(**(predictor or StepPredictor()).get_params()).fit(spec.with_demonstrations(training))
        htn = fitted.learner_.htn_
        baselines = {name: cls().fit(training) for name, cls in BASELINES.items()}
        most: Counter[str] = Counter()
        for demo in training:
            for action, n in Counter(demo.actions).items():
                most[action] = max(most[action], n)
        for index in held:
            actions = demos[index].actions
            result.held_out += 1
            if htn.admits(actions):
                result.admitted += 1
            else:
                result.not_admitted.append(demos[index].id or f"#{index + 1}")
            _score_demo(actions, fitted, baselines, most, result.prediction)
            if progress is not None:
                progress()
        if truth is not None and valid is not None:
            learned = _learned(htn)
            if learned is not None:
                recalls.append(sum(htn.admits_leaves(s) for s in valid) / len(valid))
                precisions.append(
                    sum(truth.admits_leaves(s) for s in learned) / len(learned) if learned else 1.0
                )
    order = {d.id or f"#{i + 1}": i for i, d in enumerate(demos)}
    result.not_admitted.sort(key=order.__getitem__)
    if recalls:
        result.recall = float(np.mean(recalls))
        result.precision = float(np.mean(precisions))
    return result


def _score_demo(
    actions: Sequence[str],
    predictor: StepPredictor,
    baselines: Mapping[str, Any],
    most: Counter[str],
    scores: dict[str, StepScores],
) -> None:
    running = predictor.session()
    done: Counter[str] = Counter()
    for position in range(len(actions) + 1):
        truth = actions[position] if position < len(actions) else END
        prefix = actions[:position]
        already = {a for a, n in done.items() if n >= most.get(a, 0)}
        scores[PREDICTOR].add(running.next_step(), truth, already)
        for name, model in baselines.items():
            scores[name].add(model.next_step(prefix), truth, already)
        if position < len(actions):
            running.observe(truth)
            done[truth] += 1


def _listed(node: Node) -> list[tuple[Leaf, ...]] | None:
    if count_orderings(node) > ENUMERATION_LIMIT:
        return None
    return list(iter_orderings(node))


def _learned(htn: HTN) -> list[tuple[Leaf, ...]] | None:
    """Every leaf sequence ``htn`` admits, or None when there are more than the limit."""
    if htn.count_orderings() > ENUMERATION_LIMIT:
        return None
    return list(_executions(Executions(htn)))


def _executions(machine: Executions) -> Iterator[tuple[Leaf, ...]]:
    stack: list[tuple[Progress, tuple[Leaf, ...]]] = [(state, ()) for state in machine.initial()]
    seen: set[tuple[Leaf, ...]] = set()
    while stack:
        state, prefix = stack.pop()
        if machine.can_finish(state) and prefix not in seen:
            seen.add(prefix)
            yield prefix
        for leaf, nxt in machine.moves(state).items():
            stack.append((nxt, (*prefix, machine.leaves[leaf])))
