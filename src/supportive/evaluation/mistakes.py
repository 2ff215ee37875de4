"""Online mistake detection, scored: leave one labelled recording out, detect its mistakes step by step.

Each held-out demonstration's steps are judged one by one by a :class:`~supportive.inference.mistakes.MistakeDetector`
over the progress-aware model of the hierarchy learned from the other demonstrations (by default the
``general`` reading, whose orders all rest on evidence: a robot must not call a habit it has seen a rule),
and by two baselines learned from the same demonstrations. Which of the others every method learns from is
``learn_from``: ``all`` of them (labels play no part in learning: the robot learns from what it saw, mistakes
and all, as it would at a workbench), or the ``correct`` ones, those with no label a step sequence can show
(:data:`VISIBLE`, or a skipped step; the usual protocol of supervised mistake detection, where the training
split's labels say which recordings are correct executions, and the one the generated tasks of ``reproduce
mistake-detection`` follow). The baselines are:

* **precondition**: a step is a mistake when a step that precedes it in every training demonstration that
  performs both, and that every training demonstration performing it performs, has not been done;
* **unseen bigram**: a step is a mistake when no training demonstration goes from the previous step (or the
  start) to it.

When the task's true orders are known, a reference is scored beside them: the precondition check on those
orders, learned from nothing — **published graph** for CaptainCook4D's published task graphs, **given
structure** for a task file's ``structure:`` (``supportive evaluate FILE --mistakes``). It is not a baseline
(no robot knows them) but a reference for the labels: how a detector that knew every rule of the task, and
flagged each step done before a step it needs, would score against them.

What counts (the labels of the task file, ``Step.mistake`` and ``Demonstration.skipped``):

* a **positive** is a performed step labelled with one of ``positives`` (by default ``order``, ``repeated``,
  ``unknown`` and ``true``: the kinds a step sequence can show), or a skipped step (``missing``, if among
  ``positives``) at its place;
* a flagged step is **right** when it is a positive, or when a step it names (as skipped, or as needed
  first) is a positive of the demonstration: a step done later and labelled out of order, or a skipped one
  ("this needs that first" says which step is out of place as well as a flag on it would); a positive step is
  **found** when it is flagged or named by a flag before it is done; a skipped step is **found** when a flag
  at its place (the step done instead of it) or a later verdict names it — its **delay** is the number of
  steps from its place to that verdict (the task's end counts as one more step);
* labels a step sequence cannot show (technique, measurement, timing, temperature, preparation, other) are
  counted apart: how many there were, and how many of them a method flagged.

Precision, recall and F1 are reported for the mistake class overall and per kind (the detector's kinds
``out-of-order`` ↔ ``order``, ``repeated``, ``unknown-step`` ↔ ``unknown``, ``missing``), with the share of
steps flagged in demonstrations that carry no label at all. A rate that is not defined is None in the JSON and
"–" in the tables: precision when a method claimed nothing, recall when there was nothing to find, F1 when either
is, the share flagged when no demonstration was without labels.
"""

from __future__ import annotations

import itertools
from collections import Counter
from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from supportive.errors import TaskFileError
from supportive.inference.bigram import END, START
from supportive.inference.mistakes import MistakeDetector, StepVerdict
from supportive.inference.tracker import ProgressHMM
from supportive.learning.learner import HTNLearner
from supportive.tasks.htn import Leaf
from supportive.tasks.spec import Demonstration, TaskSpec

__all__ = [
    "DETECTOR",
    "KIND_HEADERS",
    "LEARN_FROM",
    "METHODS",
    "REFERENCE",
    "STRUCTURE_REFERENCE",
    "VISIBLE",
    "MethodScores",
    "MistakeEvaluation",
    "detection_model",
    "evaluate_mistakes",
    "kind_rows",
    "shown",
    "shown_rates",
]

LEARN_FROM = ("all", "correct")
"""What each fold learns from (:func:`evaluate_mistakes`): every other demonstration, or those with no label a
step sequence can show."""

DETECTOR = "progress-aware"
METHODS = (DETECTOR, "precondition", "unseen bigram")
"""The methods compared, the detector first."""
REFERENCE = "published graph"
"""The reference scored when the task's true orders are given (:func:`evaluate_mistakes`'s ``truth``), under
this name unless another is given: CaptainCook4D's published graphs."""
STRUCTURE_REFERENCE = "given structure"
"""The name the reference is scored under when the true orders are a task file's ``structure``."""
VISIBLE = ("order", "missing", "repeated", "unknown", "true")
"""Labels a step sequence can show (``true``: a mistake of unknown kind)."""
_KIND_OF_LABEL = {"out-of-order": "order", "missing": "missing", "repeated": "repeated", "unknown-step": "unknown"}

Flag = tuple[bool, str | None, tuple[str, ...]]
"""One method's judgement of a step: flagged, the label kind it claims (None: any), the steps it names."""


@dataclass
class MethodScores:
    """One method's counts over all held-out demonstrations (see :meth:`as_dict` for the rates)."""

    flagged: int = 0
    right: int = 0
    positives: int = 0
    found: int = 0
    kinds: dict[str, list[int]] = field(default_factory=dict)  # label -> [claimed, claimed right, positives, found]
    delays: list[int] = field(default_factory=list)
    clean_steps: int = 0
    clean_flagged: int = 0
    invisible: int = 0
    invisible_flagged: int = 0

    def _kind(self, label: str) -> list[int]:
        return self.kinds.setdefault(label, [0, 0, 0, 0])

    def merge(self, other: MethodScores) -> None:
        """Add another's counts to these (scores over several tasks)."""
        for name in ("flagged", "right", "positives", "found", "clean_steps", "clean_flagged", "invisible", "invisible_flagged"):
            setattr(self, name, getattr(self, name) + getattr(other, name))
        self.delays += other.delays
        for label, counts in other.kinds.items():
            mine = self._kind(label)
            for i, value in enumerate(counts):
                mine[i] += value

    def as_dict(self) -> dict[str, object]:
        """Precision, recall and F1 overall and per kind (None where not defined); missing-step delays; clean
        and invisible counts."""
        kinds = {
            label: _rates(claimed, right, positives, found)
            for label, (claimed, right, positives, found) in sorted(self.kinds.items())
        }
        delays = sorted(self.delays)
        return {
            **_rates(self.flagged, self.right, self.positives, self.found),
            "kinds": kinds,
            "missing_delay": {
                "found": len(delays),
                "mean": round(sum(delays) / len(delays), 4) if delays else None,
                "median": delays[len(delays) // 2] if delays else None,
            },
            "clean_steps": self.clean_steps,
            "clean_flagged": round(self.clean_flagged / self.clean_steps, 6) if self.clean_steps else None,
            "not_visible": {"labels": self.invisible, "flagged": self.invisible_flagged},
        }


def _rates(claimed: int, right: int, positives: int, found: int) -> dict[str, float | int | None]:
    """Counts and rates; a rate that is not defined is None: precision when nothing was claimed, recall when
    there was nothing to find, F1 when either is."""
    precision = right / claimed if claimed else None
    recall = found / positives if positives else None
    f1 = None
    if precision is not None and recall is not None:
        f1 = 2 * precision * recall / (precision + recall) if precision + recall else 0.0
    return {
        "claimed": claimed,
        "positives": positives,
        "precision": _rounded(precision),
        "recall": _rounded(recall),
        "f1": _rounded(f1),
    }


def _rounded(rate: float | None) -> float | None:
    return None if rate is None else round(rate, 4)


@dataclass
class MistakeEvaluation:
    """A task's leave-one-out mistake detection: held-out demonstrations, each method's scores (the detector
    at the first threshold), and the detector at every threshold asked for."""

    task: str
    thresholds: tuple[float, ...]
    learned_from: str = "all"
    held_out: int = 0
    steps: int = 0
    methods: dict[str, MethodScores] = field(default_factory=lambda: {m: MethodScores() for m in METHODS[1:]})
    detector: dict[float, MethodScores] = field(default_factory=dict)

    def __post_init__(self) -> None:
        for threshold in self.thresholds:
            self.detector.setdefault(threshold, MethodScores())

    def merge(self, other: MistakeEvaluation) -> None:
        """Add another task's held-out demonstrations and counts (same thresholds) to these (the reference's
        too, when either has it)."""
        if other.thresholds != self.thresholds:
            raise TaskFileError("evaluations at different thresholds cannot be merged")
        if other.learned_from != self.learned_from:
            raise TaskFileError("evaluations learned from different demonstrations cannot be merged")
        self.held_out += other.held_out
        self.steps += other.steps
        for name, scores in other.methods.items():
            self.methods.setdefault(name, MethodScores()).merge(scores)
        for threshold, scores in other.detector.items():
            self.detector[threshold].merge(scores)

    def method(self, name: str) -> MethodScores:
        """A method's scores (the detector's at the first threshold)."""
        return self.detector[self.thresholds[0]] if name == DETECTOR else self.methods[name]

    def as_dict(self) -> dict[str, object]:
        """Plain data (``supportive evaluate --mistakes --json``)."""
        return {
            "task": self.task,
            "threshold": self.thresholds[0],
            "learned_from": self.learned_from,
            "held_out": self.held_out,
            "steps": self.steps,
            "methods": {name: self.method(name).as_dict() for name in (DETECTOR, *self.methods)},
            "thresholds": {str(t): scores.as_dict() for t, scores in self.detector.items()},
        }


def evaluate_mistakes(
    spec: TaskSpec,
    *,
    thresholds: Sequence[float] = (0.5,),
    positives: Sequence[str] = VISIBLE,
    settings: Mapping[str, Any] | None = None,
    learn_from: str = "all",
    truth: Collection[tuple[Leaf, Leaf]] | None = None,
    reference: str = REFERENCE,
    progress: Callable[[], None] | None = None,
) -> MistakeEvaluation:
    """Leave each demonstration out in turn and score every method's flags on it (see the module docstring).

    Args:
        spec: A task whose demonstrations carry mistake labels.
        thresholds: The detector's thresholds (the first is the one :meth:`MistakeEvaluation.method` reports;
            the others give a precision-recall curve without learning again).
        positives: The labels that count as mistakes to find (the rest of :data:`VISIBLE` and the invisible
            kinds are counted apart).
        settings: :class:`~supportive.learning.learner.HTNLearner` settings (default: the ``general``
            reading) and :class:`~supportive.inference.tracker.ProgressHMM` ones (``smoothing``, ``slip``).
        learn_from: ``all`` (every other demonstration) or ``correct`` (the others with no label a step sequence
            can show); see the module docstring.
        truth: The task's true orders, when known: pairs ``(a, b)`` of leaves ``(action, occurrence)``, ``a``
            a step ``b`` needs done first; the precondition check on them is then scored as well.
        reference: The name that check is reported under (:data:`REFERENCE`, or :data:`STRUCTURE_REFERENCE`
            for a task file's structure); not one of the methods' names.
        progress: Called once per held-out demonstration.

    Raises:
        TaskFileError: when no demonstration carries a label, or there are fewer than two; with ``correct``,
            when fewer than two demonstrations are correct (a fold would learn from none); when ``truth``
            names an action the task does not have.
    """
    demos = list(spec.demonstrations)
    if len(demos) < 2:
        raise TaskFileError("mistake detection is scored leaving one demonstration out: give at least two")
    if not any(d.labelled for d in demos):
        raise TaskFileError("no step carries a mistake label (see docs/task-files.md: 'mistake: order', …)")
    if not thresholds:
        raise TaskFileError("give at least one threshold")
    if learn_from not in LEARN_FROM:
        raise TaskFileError(f"learn from {' or '.join(LEARN_FROM)}, not {learn_from!r}")
    if reference in METHODS:
        raise TaskFileError(f"the reference cannot be called {reference!r}: a method has that name")
    correct = [not _shows_mistake(d) for d in demos]
    if learn_from == "correct" and sum(correct) < 2:
        raise TaskFileError(
            f"learning from the correct demonstrations needs at least two of them (each is held out in turn): "
            f"{sum(correct)} of the {len(demos)} show no skipped step and no mistake a step sequence can show"
        )
    result = MistakeEvaluation(spec.name, tuple(thresholds), learn_from)
    checked = None if truth is None else _true_precondition(truth, spec)
    if checked is not None:
        result.methods[reference] = MethodScores()
    wanted = frozenset(positives)
    for held in range(len(demos)):
        training = [d for i, d in enumerate(demos) if i != held and (learn_from == "all" or correct[i])]
        hmm = detection_model(spec.with_demonstrations(training), settings)
        demo = demos[held]
        result.held_out += 1
        result.steps += len(demo.steps)
        for threshold, scores in result.detector.items():
            _score(demo, _detector(MistakeDetector(hmm, threshold=threshold))(demo), scores, wanted)
        _score(demo, _precondition([d.actions for d in training])(demo), result.methods["precondition"], wanted)
        _score(demo, _unseen_bigram([d.actions for d in training])(demo), result.methods["unseen bigram"], wanted)
        if checked is not None:
            _score(demo, checked(demo), result.methods[reference], wanted)
        if progress is not None:
            progress()
    return result


_TRACKER = ("smoothing", "slip")


def detection_model(training: TaskSpec | Sequence[Sequence[str]], settings: Mapping[str, Any] | None = None) -> ProgressHMM:
    """The progress-aware model a detector runs on: the hierarchy learned from ``training`` (the ``general``
    reading unless ``settings`` say otherwise; see :func:`evaluate_mistakes`)."""
    settings = settings or {}
    learner = {"mode": "general", **{k: v for k, v in settings.items() if k not in _TRACKER}}
    htn = HTNLearner(alternatives=0, **learner).fit(training).htn_
    return ProgressHMM(htn, **{k: v for k, v in settings.items() if k in _TRACKER}).fit()


def _shows_mistake(demo: Demonstration) -> bool:
    """Whether the demonstration has a mistake its step sequence shows (a skipped step, or a step labelled with
    one of :data:`VISIBLE`): not a correct execution to learn the order from."""
    return bool(demo.skipped) or any(step.mistake in VISIBLE for step in demo.steps)


def _detector(detector: MistakeDetector) -> Callable[[Demonstration], list[Flag]]:
    def judge(demo: Demonstration) -> list[Flag]:
        detector.reset()
        verdicts: list[StepVerdict] = [detector.observe(action) for action in demo.actions]
        verdicts.append(detector.finish())
        return [
            (v.mistake, _KIND_OF_LABEL[v.kind] if v.kind is not None else None, v.skipped + v.prerequisites)
            for v in verdicts
        ]

    return judge


def _precondition(training: Sequence[Sequence[str]]) -> Callable[[Demonstration], list[Flag]]:
    """Flag a step when a step that precedes it in every training demonstration doing both (and that every
    training demonstration doing it does) is not done."""
    actions = sorted({a for demo in training for a in demo})
    needs: dict[str, list[Leaf]] = {a: [] for a in actions}
    for a, b in itertools.permutations(actions, 2):
        doing_b = [d for d in training if b in d]
        if doing_b and all(a in d and d.index(a) < d.index(b) for d in doing_b):
            needs[b].append((a, 1))
    return _preconditions_checked(lambda action, _: needs.get(action, ()))


def _true_precondition(truth: Collection[tuple[Leaf, Leaf]], spec: TaskSpec) -> Callable[[Demonstration], list[Flag]]:
    """The reference: flag a step when a step it needs by ``truth`` is not done (as often)."""
    known = set(spec.action_ids())
    needs: dict[Leaf, list[Leaf]] = {}
    for first, then in sorted(truth):
        for leaf in (first, then):
            if leaf[0] not in known:
                raise TaskFileError(f"the true orders name {leaf[0]!r}, an action the task does not have")
        needs.setdefault(then, []).append(first)
    return _preconditions_checked(lambda action, occurrence: needs.get((action, occurrence), ()))


def _preconditions_checked(needs: Callable[[str, int], Sequence[Leaf]]) -> Callable[[Demonstration], list[Flag]]:
    """Flag a step (its action and how many times it was done, with it) when a leaf ``needs`` gives it was not
    done yet (its action done fewer times than its occurrence), naming those leaves' actions."""

    def judge(demo: Demonstration) -> list[Flag]:
        done: Counter[str] = Counter()
        flags: list[Flag] = []
        for action in demo.actions:
            done[action] += 1
            unmet = tuple(dict.fromkeys(a for a, k in needs(action, done[action]) if done[a] < k))
            flags.append((bool(unmet), "order", unmet))
        flags.append((False, None, ()))
        return flags

    return judge


def _unseen_bigram(training: Sequence[Sequence[str]]) -> Callable[[Demonstration], list[Flag]]:
    """Flag a step when no training demonstration goes from the previous step to it."""
    seen = {pair for demo in training for pair in itertools.pairwise((START, *demo, END))}

    def judge(demo: Demonstration) -> list[Flag]:
        sequence = (START, *demo.actions, END)
        return [((sequence[i], sequence[i + 1]) not in seen, None, ()) for i in range(len(sequence) - 1)]

    return judge


def _score(demo: Demonstration, flags: list[Flag], scores: MethodScores, positives: frozenset[str]) -> None:
    """Add one demonstration's flags (one per step and one for the end) to a method's counts."""
    labels = [step.mistake for step in demo.steps]
    positive = [label is not None and label in positives for label in labels]
    skipped = list(demo.skipped) if "missing" in positives else []
    clean = not demo.labelled
    pending = set(range(len(skipped)))
    found = [False] * len(labels)
    named_before: set[str] = set()
    for step, (flagged, kind, named) in enumerate(flags):
        performed = step < len(labels)
        label = labels[step] if performed else None
        if performed:
            found[step] = positive[step] and (flagged or demo.actions[step] in named_before)
        if label is not None and label not in VISIBLE:
            scores.invisible += 1
            scores.invisible_flagged += flagged
        if clean and performed:
            scores.clean_steps += 1
            scores.clean_flagged += flagged
        if not flagged:
            continue
        hits = [
            i for i in sorted(pending)
            if skipped[i][0] <= step and (skipped[i][1] in named or (not named and skipped[i][0] == step))
        ]
        late = {demo.actions[j] for j in range(step + 1, len(labels)) if positive[j]}
        right = (performed and positive[step]) or bool(hits) or bool(late & set(named))
        scores.flagged += 1
        scores.right += right
        claim = kind  # a method that names no kind claims none (its recall per kind still counts)
        if claim is not None:
            record = scores._kind(claim)
            record[0] += 1
            record[1] += right
        named_before.update(named)
        for i in hits:
            pending.discard(i)
            scores.delays.append(step - skipped[i][0])
    for step, label in enumerate(labels):
        if positive[step]:
            assert label is not None
            scores.positives += 1
            scores.found += found[step]
            record = scores._kind(label)
            record[2] += 1
            record[3] += found[step]
    if skipped:
        missing = scores._kind("missing")
        scores.positives += len(skipped)
        scores.found += len(skipped) - len(pending)
        missing[2] += len(skipped)
        missing[3] += len(skipped) - len(pending)


KIND_HEADERS = ("method", "kind", "claimed", "precision", "positives", "recall", "F1")
"""The columns of :func:`kind_rows`."""


def shown_rates(rates: Mapping[str, Any]) -> tuple[str, str, str]:
    """Precision, recall and F1 of one method or kind (:meth:`MethodScores.as_dict`) as the tables show them:
    "–" where a rate is not defined (None in the JSON) — precision when nothing was claimed, recall when there
    was nothing to find (a kind no label has, such as one claimed where the labels say only that a step was a
    mistake), F1 where either is."""
    return shown(rates["precision"]), shown(rates["recall"]), shown(rates["f1"])


def shown(value: float | None, form: str = ".3f") -> str:
    """A number as the tables show it (in ``form``): "–" when it is not defined (None) — a rate nothing
    defines, or a figure a run did not measure.

    >>> shown(0.5), shown(None), shown(-0.25, "+.2f")
    ('0.500', '–', '-0.25')
    """
    return "–" if value is None else format(value, form)


def kind_rows(methods: Mapping[str, Mapping[str, Any]]) -> list[list[str]]:
    """The per-kind table of :meth:`MistakeEvaluation.as_dict`'s ``methods``, one row per method and kind (rates
    as :func:`shown_rates` shows them)."""
    rows = []
    for name, method in methods.items():
        for kind, k in method["kinds"].items():
            precision, recall, f1 = shown_rates(k)
            rows.append([name, kind, str(k["claimed"]), precision, str(k["positives"]), recall, f1])
    return rows
