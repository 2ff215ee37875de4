"""``supportive teach``: a person teaches a task at the terminal while the learner asks for actions (§2.2).

The person types the actions they perform, one per line (an id or its number in the list). At scheduled moments
the learner asks in words ("Can you place the purple block next?"); performing that action honours the query,
performing another refuses it. After every demonstration the learner is updated and the task file is saved with
the new demonstration, so nothing is lost if the person stops.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path

from supportive.io.task_edit import update_task_file
from supportive.io.taskfile import parse_task_file
from supportive.learning.active import QuerySchedule, TeachingSession
from supportive.learning.learner import HTNLearner
from supportive.learning.naming import known_names
from supportive.tasks.spec import Demonstration, TaskSpec

__all__ = ["TeachingConsole", "ask_in_words"]

DONE, QUIT = "done", "quit"


def ask_in_words(action: str, texts: dict[str, str]) -> str:
    """The question for a queried action: its text as a request.

    >>> ask_in_words("purple", {"purple": "place the purple block"})
    'Can you place the purple block next?'
    >>> ask_in_words("purple", {})
    'Can you do purple next?'
    """
    text = texts.get(action)
    return f"Can you {text} next?" if text and text != action else f"Can you do {action} next?"


@dataclass
class TeachingConsole:
    """The teaching loop, with its input and output injectable (tests drive it with a script).

    Args:
        path: The task file; new demonstrations are appended to it.
        read: Returns the next line typed by the person (raises EOFError at the end of input).
        write: Shows one line to the person.
        strategy: Query strategy name.
        schedule: When to ask.
        seed: Seeds the learner's choices among equally good questions.
    """

    path: Path
    read: Callable[[], str]
    write: Callable[[str], None]
    strategy: str = "distance"
    schedule: QuerySchedule = field(
        default_factory=lambda: QuerySchedule(after_steps=(1, 3, 5), max_per_demonstration=3)
    )
    seed: int | None = 0

    def run(self, demonstrations: int | None = None) -> TaskSpec:
        """Teach until the person quits, input ends, or ``demonstrations`` new ones are recorded.

        Returns:
            The task as saved.
        """
        spec = parse_task_file(self.path)
        actions = spec.action_ids()
        texts = spec.texts()
        learner = HTNLearner(names=known_names(spec.structure))
        if spec.demonstrations:
            learner.fit(spec)
        session = TeachingSession(actions, self.strategy, self.schedule, self.seed, learner)
        self.write(
            f"Teaching {spec.name}: {len(actions)} actions, {len(spec.demonstrations)} demonstrations so far."
        )
        for number, action in enumerate(actions, start=1):
            self.write(
                f"  {number:2d}. {action}"
                + (f" — {texts[action]}" if texts.get(action, action) != action else "")
            )
        self.write(
            f"Type each action you perform (id or number); '{DONE}' ends a demonstration, '{QUIT}' stops."
        )
        recorded = 0
        while demonstrations is None or recorded < demonstrations:
            finished = self._demonstration(session, actions, texts)
            if finished is None:
                break

            def append(current: TaskSpec, finished: Demonstration = finished) -> TaskSpec:
                """The file's task now (another session may have saved to it) with the new demonstration."""
                taken = {d.id for d in current.demonstrations}
                number = len(current.demonstrations) + 1
                while f"d{number}" in taken:
                    number += 1
                return current.with_demonstrations([*current.demonstrations, replace(finished, id=f"d{number}")])

            spec = update_task_file(self.path, append)
            finished = spec.demonstrations[-1]
            recorded += 1
            graph = session.learner.task_graph_
            shape = (
                "complete"
                if session.learner.htn_.complete
                else f"{len(session.learner.htn_.roots)} parts so far"
            )
            self.write(
                f"Saved demonstration {finished.id} to {self.path}. Known valid orders: {graph.path_count()}; "
                f"hierarchy: {shape}."
            )
        return spec

    def _demonstration(
        self, session: TeachingSession, actions: tuple[str, ...], texts: dict[str, str]
    ) -> Demonstration | None:
        """One demonstration; None when the person quits (an unfinished demonstration is dropped: a partial
        execution is not a valid demonstration)."""
        session.begin()
        self.write(f"Demonstration {len(session.demonstrations) + 1}:")
        asked_at = -1
        while True:
            question = session.query()
            if question is not None and asked_at != len(session.done):
                asked_at = len(session.done)
                self.write("  robot: " + ask_in_words(question, texts))
            try:
                line = self.read().strip()
            except EOFError:
                line = QUIT
            if line == QUIT:
                if session.done:
                    self.write(f"  dropped the unfinished demonstration ({len(session.done)} steps)")
                return None
            if line == DONE:
                if not session.done:
                    self.write("  nothing performed yet: type an action first")
                    continue
                return session.end()
            if not line:
                self.write(f"  (empty line) type an action id or number, '{DONE}' or '{QUIT}'")
                continue
            action = actions[int(line) - 1] if line.isdigit() and 1 <= int(line) <= len(actions) else line
            if action not in actions:
                self.write(f"  unknown action {line!r}; choose one of: {', '.join(actions)}")
                continue
            session.observe(action)
            if len(session.done) == len(actions):
                return session.end()
