"""What the robot thinks, for the board's page: the goal-inference belief (§2.1.7, when the task's actions
declare contact-event observations and it has demonstrations to learn from) and the supportive behaviors
(§3.3) whose start condition holds in the board's current state and whose stop condition does not."""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field
from functools import cached_property
from numbers import Real
from typing import Any

from supportive.errors import ServiceError
from supportive.inference import END_LABEL, ObservationModel, ProgressFilter, ProgressHMM
from supportive.language.states import TaskStates
from supportive.learning.learner import learn
from supportive.social.board import TaskBoard
from supportive.tasks.spec import TaskSpec

__all__ = ["Insight"]

RECENT = 6
"""How many of the latest observed steps the goal view lists."""
OFF_SCRIPT = 0.5
"""A step is shown off-script when the tracker's probability that it was (``off_script``) is at least this."""


@dataclass
class Insight:
    """The belief and the suggestions of one board's task (None / empty when the task cannot give them)."""

    spec: TaskSpec | None
    filter: ProgressFilter | None = field(default=None, init=False)
    latest: dict[str, Any] | None = field(default=None, init=False)
    recent: deque[dict[str, Any]] = field(default_factory=lambda: deque(maxlen=RECENT), init=False)

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

    @property
    def inference(self) -> bool:
        """Whether goal inference is configured."""
        return self.model is not None

    def observe(self, events: list[str]) -> dict[str, Any]:
        """Feed one moment's contact events to the filter; the belief after it.

        Raises:
            ServiceError: when the task has no goal inference.
        """
        if self.model is None:
            raise ServiceError(
                "this board's task has no goal inference (no observations or no demonstrations)"
            )
        if self.filter is None:
            self.filter = self.model.filter()
        belief = self.filter.update(set(events))
        summary = self.filter.summary(belief)
        surprise = getattr(belief, "surprise", None)  # reported by filters that model off-script steps
        if "surprise" not in summary and surprise is not None:
            summary["surprise"] = surprise
        self.latest = summary
        goal = self.goal()
        if goal is not None and goal["current"]:
            top = goal["current"][0]
            self.recent.append(
                {"step": goal["step"], "action": top["action"], "text": top["text"], "off_script": goal["off_script"]}
            )
        return self.latest

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
        off-script (the model's own ``off_script`` flag, else a ``surprise`` of :data:`OFF_SCRIPT` or more),
        and the latest steps' most likely actions; None before any observation."""
        latest = self.latest
        if latest is None:
            return None
        texts = self.spec.texts() if self.spec is not None else {}

        def actions(pairs: list[list[Any]]) -> list[dict[str, Any]]:
            out = []
            for label, p in pairs:
                action, _, occurrence = str(label).rpartition("#")
                if not (action and occurrence.isdigit()):
                    action, occurrence = str(label), ""
                text = "finish the task" if label == END_LABEL else texts.get(action, action)
                text += f" (#{occurrence})" if occurrence else ""
                out.append({"action": str(label), "text": text, "probability": float(p)})
            return out

        surprise = latest.get("surprise")
        if isinstance(surprise, Real) and not isinstance(surprise, bool):
            surprise = float(surprise)  # plain JSON, whatever number type the filter gives
        chance = latest.get("off_script")
        flagged = None if chance is None else float(chance) >= OFF_SCRIPT
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
