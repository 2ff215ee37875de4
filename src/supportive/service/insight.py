"""What the robot thinks, for the board's page: the goal-inference belief (§2.1.7, when the task's actions
declare contact-event observations and it has demonstrations to learn from), the mistakes it noticed with the
help it offers (:class:`~supportive.inference.mistakes.MistakeDetector`, :mod:`supportive.language.help`) and
the supportive behaviors (§3.3) whose start condition holds in the board's current state and whose stop
condition does not."""

from __future__ import annotations

import time
from collections import deque
from dataclasses import dataclass, field
from functools import cached_property
from numbers import Real
from typing import Any

from supportive.errors import ServiceError
from supportive.inference import END_LABEL, Filter, ObservationModel, ProgressHMM
from supportive.inference.bags import belief_record
from supportive.inference.mistakes import DEFAULT_THRESHOLD, MistakeDetector, StepVerdict
from supportive.io.values import is_digits
from supportive.language.help import mistake_record
from supportive.language.states import TaskStates
from supportive.learning.learner import learn
from supportive.social.board import TaskBoard
from supportive.tasks.spec import TaskSpec

__all__ = ["Insight"]

RECENT = 6
"""How many of the latest observed steps the goal view lists."""
MISTAKES_KEPT = 20
"""How many of the latest mistakes ``/api/insight`` lists (the newest first)."""


@dataclass
class Insight:
    """The belief and the suggestions of one board's task (None / empty when the task cannot give them)."""

    spec: TaskSpec | None
    latest: dict[str, Any] | None = field(default=None, init=False)
    recent: deque[dict[str, Any]] = field(default_factory=lambda: deque(maxlen=RECENT), init=False)
    mistakes: deque[dict[str, Any]] = field(default_factory=lambda: deque(maxlen=MISTAKES_KEPT), init=False)
    raised: int = field(default=0, init=False)

    @cached_property
    def states(self) -> TaskStates | None:
        """The task's states, when it has a structure and supportive behaviors."""
        if self.spec is None or self.spec.structure is None or not self.spec.behaviors:
            return None
        return TaskStates.of(self.spec)

    @cached_property
    def model(self) -> ProgressHMM | None:
        """The progress-aware tracker's model, when every action declares observations and there are
        demonstrations."""
        spec = self.spec
        if spec is None or not spec.demonstrations or not all(a.observations for a in spec.actions):
            return None
        return ProgressHMM(learn(spec).htn_, ObservationModel.from_spec(spec)).fit()

    @cached_property
    def detector(self) -> MistakeDetector | None:
        """The mistake detector over the tracker's model (its tracker of contact events is the belief this
        view shows), when there is goal inference."""
        return None if self.model is None else MistakeDetector(self.model)

    @property
    def inference(self) -> bool:
        """Whether goal inference is configured."""
        return self.model is not None

    def update(self, events: list[str], board: TaskBoard | None = None) -> dict[str, Any]:
        """Feed one moment's contact events to the tracker; the belief after it. A step the detector judges
        a mistake is kept (:attr:`mistakes`, :meth:`latest_mistake`) with the help it calls for and, given
        the ``board``, the nodes that help concerns which are not done yet.

        Raises:
            ServiceError: when the task has no goal inference.
        """
        detector = self.detector
        if detector is None:
            raise ServiceError(
                "this board's task has no goal inference (no observations or no demonstrations)"
            )
        verdict = detector.update(set(events))
        running: Filter = detector.events
        self.latest = belief_record(running, running.last, 3, None)  # with surprise, when the filter has it
        goal = self.goal()
        if goal is not None and goal["current"]:
            top = goal["current"][0]
            self.recent.append(
                {"step": goal["step"], "action": top["action"], "text": top["text"], "off_script": goal["off_script"]}
            )
        if verdict is not None and verdict.mistake:
            self._raise(verdict, board)
        return self.latest

    def latest_mistake(self) -> dict[str, Any] | None:
        """The mistake raised last, None before any."""
        return self.mistakes[0] if self.mistakes else None

    def _raise(self, verdict: StepVerdict, board: TaskBoard | None) -> None:
        """Keep a mistake: the verdict, the help (:func:`~supportive.language.help.mistake_record`), when it
        was raised (Unix seconds) and the board nodes of the steps it names that are not done yet (what the
        robot can take on to help: fetch for a prerequisite, a reminder for a skipped step)."""
        texts = self.spec.texts() if self.spec is not None else {}
        self.raised += 1
        record: dict[str, Any] = {"id": self.raised, "raised": time.time(), **mistake_record(verdict, texts)}
        record["text"] = texts.get(verdict.action, verdict.action)
        named = set(verdict.prerequisites) | set(verdict.skipped)
        record["nodes"] = (
            [n.id for n in board.nodes if n.action in named and not n.done and not n.lead_only] if board else []
        )
        self.mistakes.appendleft(record)

    def suggestions(self, board: TaskBoard) -> list[dict[str, str]]:
        """The behaviors that may run now: their start condition holds, their stop condition does not, and
        (when tied to subtasks) one of those subtasks is under way or about to begin."""
        states = self.states
        if states is None or self.spec is None:
            return []
        state = board.done_leaves
        if state not in states.table.state_index:
            return []
        out = []
        for behavior in self.spec.behaviors:
            scope = [s for s in behavior.subtasks if s in states.subtasks]
            during = not scope or any(state in states.during(s) for s in scope)
            if (
                during
                and state in states.region(behavior.initiation)
                and state not in states.region(behavior.termination)
            ):
                out.append(
                    {"name": behavior.name, "text": behavior.text, "category": behavior.category.value}
                )
        return out

    def goal(self) -> dict[str, Any] | None:
        """The latest belief for people: the likely enclosing subtasks, current and next actions with their
        text, the filter's ``surprise`` (None when the model does not report one) and whether the step was
        off-script (the tracker's probability that it was, ``off_script``, at least the mistake detector's
        default threshold, :data:`~supportive.inference.mistakes.DEFAULT_THRESHOLD`; None when the model
        does not say), and the latest steps' most likely actions; None before any observation."""
        latest = self.latest
        if latest is None:
            return None
        texts = self.spec.texts() if self.spec is not None else {}

        def actions(pairs: list[list[Any]]) -> list[dict[str, Any]]:
            out = []
            for label, p in pairs:
                action, _, occurrence = str(label).rpartition("#")
                if not (action and is_digits(occurrence)):
                    action, occurrence = str(label), ""
                text = "finish the task" if label == END_LABEL else texts.get(action, action)
                text += f" (#{occurrence})" if occurrence else ""
                out.append({"action": str(label), "text": text, "probability": float(p)})
            return out

        surprise = latest.get("surprise")
        if isinstance(surprise, Real) and not isinstance(surprise, bool):
            surprise = float(surprise)  # plain JSON, whatever number type the filter gives
        chance = latest.get("off_script")
        flagged = None if chance is None else float(chance) >= DEFAULT_THRESHOLD
        return {
            "step": latest.get("step"),
            "subtasks": [{"name": str(n), "probability": float(p)} for n, p in latest.get("subtasks", [])],
            "current": actions(latest.get("subgoals", [])),
            "next": actions(latest.get("next", [])),
            "surprise": surprise,
            "off_script": None if flagged is None else bool(flagged),
            "recent": list(self.recent),
        }

    def belief(self) -> list[dict[str, Any]] | None:
        """The latest belief's most likely subgoals as ``{"name", "probability"}``, None before any observation
        (or without goal inference)."""
        if self.latest is None:
            return None
        return [{"name": str(name), "probability": float(p)} for name, p in self.latest["subgoals"]]
