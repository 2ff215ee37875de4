"""Online mistake detection: after each step a person takes, is it a mistake, of which kind, and how sure.

A :class:`MistakeDetector` runs beside the progress-aware tracker
(:class:`~supportive.inference.tracker.ProgressFilter`). After each observed step (a known action, or the
start of a new subgoal read from contact events) it returns a :class:`StepVerdict`: the probability that the
step was off-script (the tracker's posterior ``off_script``: the steps so far, the learned hierarchy and its
frequencies, and a slip rate), and — when that reaches ``threshold`` and the step is one the hierarchy
refuses — what kind of mistake it is:

* ``unknown-step``: an action the task does not have;
* ``repeated``: an action done again, already done as often as the task has it;
* ``missing``: the step needs others that were due just before it and were not done, or it leaves a subtask
  under way unfinished (subtasks are done without interruption): the person skipped them (named as
  ``skipped``);
* ``out-of-order``: the step needs others that were not yet due: it came too early (its unmet
  ``prerequisites`` are named).

A step the tracker finds unlikely but that misses nothing it needs (an order nobody showed among steps that
may come in any order) is not a mistake: a robot that names no reason would only nag.

A step's prerequisites are the steps that come before it in every execution the hierarchy admits and that
every execution performs (:func:`~supportive.learning.pair_orders.required_orders`). Decisions use only
the past. A step already named as skipped or as a prerequisite is not flagged again when it is done late (the
robot has said it once). :meth:`MistakeDetector.finish` names the required steps never done when the task
ends (``missing``, raised at the end).

>>> from supportive.inference import StepPredictor
>>> demos = [["knife", "carrots", "celery", "bowl"], ["knife", "celery", "carrots", "bowl"]] * 3
>>> detector = MistakeDetector.from_predictor(StepPredictor().fit(demos))
>>> [(v.action, v.mistake) for v in map(detector.observe, ["knife", "carrots"])]
[('knife', False), ('carrots', False)]
>>> verdict = detector.observe("bowl")
>>> verdict.mistake, verdict.kind, verdict.skipped
(True, 'missing', ('celery',))
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from supportive.errors import LearningError
from supportive.inference.tracker import ProgressFilter, ProgressHMM
from supportive.learning.distribution import END
from supportive.learning.pair_orders import required_orders
from supportive.tasks.executions import Progress
from supportive.tasks.htn import HTN, ActionNode, Leaf, Node

__all__ = ["DEFAULT_THRESHOLD", "MISTAKE_KINDS", "MistakeDetector", "MistakeKind", "StepVerdict"]

MistakeKind = Literal["out-of-order", "missing", "repeated", "unknown-step"]
MISTAKE_KINDS: tuple[MistakeKind, ...] = ("out-of-order", "missing", "repeated", "unknown-step")
"""The kinds of mistake a verdict names, in the order reports list them."""

DEFAULT_THRESHOLD = 0.5
"""The detector's default threshold: the one ``supportive reproduce mistake-detection`` chooses on generated
tasks (docs/inference.md)."""


@dataclass(frozen=True)
class StepVerdict:
    """What the detector says of one step.

    Attributes:
        step: The step's number among those observed (1 for the first); for the task's end, one more than
            their number.
        action: The action done (``"<end>"`` for the task's end).
        probability: Probability that the step was off-script, given only the steps so far.
        mistake: True when it is a mistake (``probability`` reached the threshold and the step is unknown,
            repeated or misses steps it needs, or the task ended with ``skipped`` steps never done).
        kind: The kind of mistake (None when it is not one).
        prerequisites: ``out-of-order``: the steps it needs that are not done, in task order.
        skipped: ``missing``: the steps skipped, in task order.
    """

    step: int
    action: str
    probability: float
    mistake: bool = False
    kind: MistakeKind | None = None
    prerequisites: tuple[str, ...] = ()
    skipped: tuple[str, ...] = ()

    def as_dict(self) -> dict[str, object]:
        """Plain-data form (the ``mistake`` field of ``infer``'s JSON lines)."""
        data: dict[str, object] = {
            "step": self.step,
            "action": self.action,
            "mistake": self.mistake,
            "probability": round(self.probability, 6),
        }
        if self.kind is not None:
            data["kind"] = self.kind
        if self.prerequisites:
            data["prerequisites"] = list(self.prerequisites)
        if self.skipped:
            data["skipped"] = list(self.skipped)
        return data


@dataclass
class _Requirements:
    """What the hierarchy requires: each leaf's prerequisites (leaf indices) and which leaves every
    execution performs."""

    leaves: tuple[Leaf, ...]
    prerequisites: list[list[int]]
    required: list[bool]
    actions: frozenset[str] = field(default_factory=frozenset)
    subtasks: list[frozenset[int]] = field(default_factory=list)

    @classmethod
    def of(cls, htn: HTN) -> _Requirements:
        leaves, always = required_orders(htn)
        index = {leaf: i for i, leaf in enumerate(leaves)}
        required = set(htn.required_leaves)
        need = [leaf in required for leaf in leaves]
        prerequisites = [[int(i) for i in np.flatnonzero(always[:, j]) if need[int(i)]] for j in range(len(leaves))]
        subtasks = sorted(
            (frozenset(index[leaf] for leaf in node.leaves) for node in _subtasks(htn)), key=len
        )
        return cls(leaves, prerequisites, need, frozenset(a for a, _ in leaves), subtasks)

    def interrupted(self, leaf: int, done: list[bool]) -> tuple[int, ...]:
        """The required steps left undone in the smallest subtask that is under way (some of it done) and
        that ``leaf`` does not belong to: a subtask is done without interruption, so leaving it skips them."""
        for members in self.subtasks:
            if leaf in members or not any(done[i] for i in members):
                continue
            left = tuple(sorted(i for i in members if self.required[i] and not done[i]))
            if left:
                return left
        return ()


def _subtasks(htn: HTN) -> list[Node]:
    """Every chain and clique of the hierarchy, its roots included."""
    out: list[Node] = []
    stack: list[Node] = list(htn.roots)
    while stack:
        node = stack.pop()
        if not isinstance(node, ActionNode):
            out.append(node)
            stack.extend(node.children)
    return out


class MistakeDetector:
    """Online mistake detection over a progress-aware tracker (see the module docstring).

    Args:
        hmm: A fitted :class:`~supportive.inference.tracker.ProgressHMM` (its hierarchy, frequencies and slip
            rate; contact events need its observation model).
        threshold: A step is a mistake when the probability that it was off-script reaches this; in (0, 1].
            The default was chosen on generated tasks by ``supportive reproduce mistake-detection`` (the most
            recall at no more than 1 % false alarms on clean executions; docs/inference.md).
    """

    def __init__(self, hmm: ProgressHMM, *, threshold: float = DEFAULT_THRESHOLD) -> None:
        if not 0.0 < threshold <= 1.0:
            raise LearningError(f"threshold must be in (0, 1], got {threshold}")
        self.hmm = hmm
        self.threshold = threshold
        self._requirements = _Requirements.of(hmm.htn_)
        self._index = {leaf: i for i, leaf in enumerate(self._requirements.leaves)}
        self.reset()

    @classmethod
    def from_predictor(cls, predictor: object, *, threshold: float = DEFAULT_THRESHOLD) -> MistakeDetector:
        """A detector over a fitted :class:`~supportive.inference.predictor.StepPredictor`'s model."""
        model = getattr(predictor, "model_", None)
        if not isinstance(model, ProgressHMM):
            raise LearningError("from_predictor needs a fitted StepPredictor")
        return cls(model, threshold=threshold)

    def reset(self) -> None:
        """Forget everything observed: the task has not started."""
        self.tracker: ProgressFilter = self.hmm.filter()
        self.events: ProgressFilter = self.hmm.filter()
        self._current: int | None = None
        self.history: list[str] = []
        self._done: Counter[str] = Counter()
        self._said: set[str] = set()

    # ------------------------------------------------------------------ evidence
    def observe(self, action: str) -> StepVerdict:
        """Take one completed action into account and judge it."""
        before = self.tracker.belief  # what was due is worked out only for a step judged a mistake
        belief = self.tracker.observe(action)
        verdict = self._judge(action, before, belief.off_script)
        self.history.append(action)
        self._done[action] += 1
        return verdict

    def update(self, events: Iterable[str]) -> StepVerdict | None:
        """Take one moment's contact events into account (``events.last`` is then the belief); when the most
        probable subgoal under way changes to a new one, judge its action as the step just started (None
        otherwise).

        Contacts cannot tell a step from a *twin* that touches the same things (two pegs pushed into the same
        frame): when the person moves on from a step, its twins that the new step needs (its prerequisites,
        and the rest of a subtask it would interrupt) and that are not done yet are taken as done, in task
        order, before the new step is judged (a twin truly skipped is not seen; docs/inference.md). The most
        probable subgoal going back to a step already done is taken for the contacts flickering, not for a
        repeat (a repeated step is seen from known actions)."""
        belief = self.events.update(events)
        subgoal = int(np.argmax(belief.subgoals)) if belief.subgoals.size and belief.subgoals.max() > 0 else None
        if subgoal is None or subgoal == self._current:
            return None
        if self._done_leaves()[subgoal]:  # back to a step already done: the contacts flicker, not a repeat
            return None
        previous, self._current = self._current, subgoal
        if previous is not None:
            for twin in self._twins(previous, subgoal):
                self.observe(self._requirements.leaves[twin][0])
        return self.observe(self._requirements.leaves[subgoal][0])

    def _twins(self, left: int, entered: int) -> list[int]:
        """The leaves not done yet that the ``entered`` leaf needs (its prerequisites, and the rest of a
        subtask it would interrupt) and whose contacts are those of the leaf just ``left``, in task order."""
        observations = self.hmm.observations
        if observations is None:
            return []
        rows = observations.action_index
        leaves = self._requirements.leaves

        def contacts(leaf: int) -> np.ndarray | None:
            row = rows.get(leaves[leaf][0])
            return None if row is None else observations.table[row]

        mine = contacts(left)
        done = self._done_leaves()
        done[left] = True  # the step just left counts as done while its twins are sought
        needed = {i for i in self._requirements.prerequisites[entered] if not done[i]}
        needed |= set(self._requirements.interrupted(entered, done))
        if mine is None:
            return []
        return [i for i in sorted(needed) if (other := contacts(i)) is not None and np.array_equal(other, mine)]

    def finish(self) -> StepVerdict:
        """The task has ended: the required steps never done are missing."""
        done = self._done_leaves()
        never = [i for i, need in enumerate(self._requirements.required) if need and not done[i]]
        skipped = tuple(self._requirements.leaves[i][0] for i in never if self._requirements.leaves[i][0] not in self._said)
        probability = 1.0 if skipped else 0.0
        return StepVerdict(len(self.history) + 1, "<end>", probability, bool(skipped), "missing" if skipped else None, (), skipped)

    # ------------------------------------------------------------------ judging
    def _judge(self, action: str, before: Mapping[Progress | None, float], probability: float) -> StepVerdict:
        step = len(self.history) + 1
        if probability < self.threshold:
            return StepVerdict(step, action, probability)
        requirements = self._requirements
        if action not in requirements.actions:
            return StepVerdict(step, action, probability, True, "unknown-step")
        occurrence = self._done[action] + 1
        leaf = self._index.get((action, occurrence))
        if leaf is None:
            return StepVerdict(step, action, probability, True, "repeated")
        done = self._done_leaves()
        unmet = [i for i in requirements.prerequisites[leaf] if not done[i]]
        names = self._names(unmet)
        if action in self._said and not names:  # done late after the robot named it: said once already
            return StepVerdict(step, action, probability)
        if names and set(names) <= self._due(before):
            self._said.update(names)
            return StepVerdict(step, action, probability, True, "missing", (), names)
        if names:
            self._said.update(names)
            return StepVerdict(step, action, probability, True, "out-of-order", names)
        left = self._names(list(requirements.interrupted(leaf, done)))
        self._said.update(left)
        if left:
            return StepVerdict(step, action, probability, True, "missing", (), left)
        return StepVerdict(step, action, probability)  # unusual, but nothing it needs is missing: no nagging

    def _due(self, belief: Mapping[Progress | None, float]) -> set[str]:
        """The actions the hierarchy allows next in the most probable state of ``belief``."""
        state = max(belief, key=lambda s: belief[s]) if belief else None
        if state is None:
            return set()
        leaves = self.tracker.model.leaves
        return {leaves[i][0] for i in self.tracker.model.outcomes(state) if i != END}

    def _names(self, leaves: list[int]) -> tuple[str, ...]:
        """The actions of ``leaves``, each once, in task order, leaving out those already named."""
        names = dict.fromkeys(self._requirements.leaves[i][0] for i in leaves)
        return tuple(name for name in names if name not in self._said)

    def _done_leaves(self) -> list[bool]:
        """Whether each leaf is done, by how often its action was done so far."""
        return [self._done[a] >= k for a, k in self._requirements.leaves]
