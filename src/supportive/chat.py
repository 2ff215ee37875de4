"""``supportive chat``: tell the robot how to help, and ask it to explain itself (§3.3).

The person types sentences; the robot answers:

* a preference ("When I am screwing the seat, I want you to give me screws until the seat is attached to the
  left frame") is grounded (Algorithm 6) and, when the robot is unsure which subtask was meant, confirmed
  ("Do you mean Screw seat? …" — answer yes, no, or the number of another candidate); the robot then says back
  what it will do (Algorithm 7, so implied constraints become explicit) and saves the task file;
* "How will you help me …?" and "When will you …?" are answered with Algorithm 7;
* ``behaviors`` lists the behaviors, ``quit`` (or the end of input) stops.

Anything it cannot read is answered with what it understood and the form to use, never with a crash.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path

from supportive.io.taskfile import parse_task_file, write_task_file
from supportive.language.explain import explain_behavior, explain_subtask
from supportive.language.grammar import (
    ExplainBehavior,
    ExplainSubtask,
    Preference,
    UnderstandingError,
    parse_utterance,
)
from supportive.language.grounding import Candidate, is_confident
from supportive.language.states import TaskStates
from supportive.language.understand import Understanding
from supportive.tasks.behaviors import SupportiveBehavior
from supportive.tasks.spec import TaskSpec

__all__ = ["ChatConsole"]

QUIT = {"quit", "exit", "bye", "done"}
YES = {"yes", "y", "yeah", "yep", "correct", "right", "ok"}


@dataclass
class ChatConsole:
    """The dialogue loop, with input and output injectable (tests drive it with a script).

    Args:
        path: The task file (it needs a structure); changed behaviors are saved to it.
        read: Returns the next line typed by the person (raises EOFError at the end of input).
        write: Shows one line to the person.
        matcher: ``"bow"`` or ``"embeddings"`` (see :class:`~supportive.language.understand.Understanding`).
    """

    path: Path
    read: Callable[[], str]
    write: Callable[[str], None]
    matcher: str = "bow"
    spec: TaskSpec = field(init=False)
    states: TaskStates = field(init=False)

    def __post_init__(self) -> None:
        self.spec = parse_task_file(self.path)
        self.states = TaskStates.of(self.spec)

    def run(self) -> TaskSpec:
        """Talk until ``quit`` or the end of input; return the task as saved."""
        self.write(
            f"{self.spec.name}: {len(self.states.subtasks)} subtasks, {len(self.spec.behaviors)} supportive "
            "behaviors. Tell me how to help (\"When I am …, I want you to …\"), ask \"How will you help me …?\" "
            "or \"When will you …?\"; 'behaviors' lists them, 'quit' ends."
        )
        while True:
            try:
                line = self.read().strip()
            except EOFError:
                break
            if not line:
                self.write("Say something, or 'quit'.")
                continue
            if line.lower() in QUIT:
                break
            if line.lower() == "behaviors":
                self._list()
                continue
            self.respond(line)
        return self.spec

    def _list(self) -> None:
        for behavior in self.spec.behaviors:
            during = ", ".join(behavior.subtasks) or "any subtask"
            self.write(f"- {behavior.name}: {behavior.text} ({behavior.category.value}; during {during})")

    def respond(self, line: str) -> None:
        """Answer one utterance."""
        try:
            utterance = parse_utterance(line)
        except UnderstandingError as exc:
            self.write(str(exc))
            return
        if isinstance(utterance, Preference):
            self._prefer(utterance)
        elif isinstance(utterance, ExplainSubtask):
            self._explain_subtask(utterance)
        elif isinstance(utterance, ExplainBehavior):
            self._explain_behavior(utterance)

    def _confirm(self, ranked: tuple[Candidate, ...], question: str) -> str | None:
        """Ask which candidate was meant; None when the person declines."""
        options = "; ".join(f"{i + 1}. {c.key} ({c.probability:.0%})" for i, c in enumerate(ranked))
        self.write(f"{question} (I considered: {options}) Answer yes, no or a number.")
        try:
            answer = self.read().strip().lower()
        except EOFError:
            return None
        if answer in YES:
            return ranked[0].key
        if answer.isdigit() and 1 <= int(answer) <= len(ranked):
            return ranked[int(answer) - 1].key
        self.write("All right, I changed nothing.")
        return None

    def _prefer(self, preference: Preference) -> None:
        understanding = Understanding(self.states, matcher=self.matcher)
        for phrase in preference.behavior_phrases:
            try:
                understood = understanding.apply(preference, phrase)
            except UnderstandingError as exc:
                self.write(str(exc))
                return
            behavior = understood.behavior
            if not understood.confident:
                chosen = []
                for ranked, said in zip(understood.subtasks, preference.subtask_phrases, strict=True):
                    if is_confident(list(ranked)):
                        chosen.append(ranked[0].key)
                        continue
                    key = self._confirm(ranked, f"By '{said}', do you mean {ranked[0].key}?")
                    if key is None:
                        return
                    chosen.append(key)
                before = understanding.behavior_for(phrase)
                prior = before.subtasks if before is not None else ()
                behavior = replace(behavior, subtasks=tuple(dict.fromkeys([*prior, *chosen])))
            self._save(behavior)
            verb = "I will now" if understood.created else "I updated how I"
            self.write(f"OK. {verb} {behavior.text}. {explain_behavior(self.states, behavior).text}")

    def _save(self, behavior: SupportiveBehavior) -> None:
        others = [b for b in self.spec.behaviors if b.name != behavior.name]
        position = next((i for i, b in enumerate(self.spec.behaviors) if b.name == behavior.name), len(others))
        others.insert(position, behavior)
        self.spec = self.spec.with_behaviors(others)
        self.states = TaskStates.of(self.spec, self.states.structure)
        write_task_file(self.spec, self.path)

    def _explain_subtask(self, request: ExplainSubtask) -> None:
        ranked = tuple(Understanding(self.states, matcher=self.matcher).subtask_matcher.candidates(request.subtask_phrase))
        key = ranked[0].key if is_confident(list(ranked)) else self._confirm(
            ranked, f"By '{request.subtask_phrase}', do you mean {ranked[0].key}?"
        )
        if key is not None:
            self.write(explain_subtask(self.states, key).text)

    def _explain_behavior(self, request: ExplainBehavior) -> None:
        behavior = Understanding(self.states, matcher=self.matcher).behavior_for(request.behavior_phrase)
        if behavior is None:
            known = ", ".join(b.text for b in self.spec.behaviors) or "nothing yet"
            self.write(f"I have no behavior like '{request.behavior_phrase}'. I know how to: {known}.")
            return
        self.write(explain_behavior(self.states, behavior).text)

