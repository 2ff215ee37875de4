"""``supportive chat``: tell the robot how to help, and ask it to explain itself (§3.3).

The person types sentences; the robot answers:

* a preference ("When I am screwing the seat, I want you to give me screws until the seat is attached to the
  left frame", or "Don't give me screws when I'm fastening the bolts") is grounded (Algorithm 6) and, when the
  robot is unsure which subtask was meant, confirmed once per subtask phrase ("Do you mean Screw seat? …" —
  answer yes, no, or the number of another candidate; anything else is taken as a new utterance); a phrase
  that names no subtask it knows is answered with some it does. The rule of
  :mod:`supportive.language.preferences` changes the behavior; the robot says truthfully what changed, then
  what it will do (Algorithm 7, so implied constraints become explicit), and saves the task file;
* "How will you help me …?" and "When will you …?" are answered with Algorithm 7;
* ``behaviors`` lists the behaviors, ``help`` says what one can say (with the task's own subtasks and
  behaviors), ``quit`` (or the end of input) stops.

Anything it cannot read is answered with the form to use (and the part it understood, when it understood
more than a word or two), never with a crash; a request for help it has no verb for ("juggle") is refused,
not made up as a new behavior.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from supportive.errors import UnderstandingError
from supportive.io.task_edit import update_task_file
from supportive.io.taskfile import parse_task_file
from supportive.io.working_copy import WorkingCopy
from supportive.language.explain import explain_behavior, explain_subtask
from supportive.language.grammar import ExplainBehavior, ExplainSubtask, Preference, parse_utterance
from supportive.language.grounding import Candidate, is_confident
from supportive.language.states import TaskStates
from supportive.language.understand import Understanding
from supportive.tasks.behaviors import SupportiveBehavior
from supportive.tasks.htn import ChainNode, CliqueNode, Node
from supportive.tasks.spec import TaskSpec

__all__ = ["ChatConsole"]

QUIT = {"quit", "exit", "bye", "done"}
HELP = {"help", "?", "what can you do", "what can i say", "what can i do"}
YES = {"yes", "y", "yeah", "yep", "correct", "right", "ok"}
NO = {"no", "n", "nope", "nah", "wrong", "neither", "none", "cancel", ""}
SHORT_ANSWER = 3
"""An answer of at most this many words is read by its first ("yes please", "no, thanks", "2.")."""
KNOWN_SHOWN = 5
"""Subtasks named, outermost first, when a phrase names none the robot knows."""


@dataclass
class ChatConsole:
    """The dialogue loop, with input and output injectable (tests drive it with a script).

    Args:
        path: The task file (it needs a structure); changed behaviors are saved to it.
        read: Returns the next line typed by the person (raises EOFError at the end of input).
        write: Shows one line to the person.
        matcher: ``"bow"`` or ``"embeddings"`` (see :class:`~supportive.language.understand.Understanding`).
        copy: The working copy to save to (made at the first change); None saves to ``path``.

    Raises:
        TaskFileError: for a task file that cannot be read.
        MissingExtraError: when the matcher's extra (scikit-learn for ``bow``) is not installed: before the
            dialogue starts.
    """

    path: Path
    read: Callable[[], str]
    write: Callable[[str], None]
    matcher: str = "bow"
    copy: WorkingCopy | None = None
    spec: TaskSpec = field(init=False)
    states: TaskStates = field(init=False)
    understanding: Understanding = field(init=False)
    _next: str | None = field(init=False, default=None)
    saved: int = field(init=False, default=0)
    """Changes saved (and acknowledged) by this session."""

    def __post_init__(self) -> None:
        self.spec = parse_task_file(self.path)
        self.states = TaskStates.of(self.spec)
        self.understanding = Understanding(self.states, matcher=self.matcher)
        self.understanding.subtask_matcher  # noqa: B018 - built now: a missing extra fails before the dialogue

    def run(self) -> TaskSpec:
        """Talk until ``quit`` or the end of input; return the task as saved."""
        self.write(
            f"{self.spec.name}: {len(self.states.subtasks)} subtasks, {len(self.spec.behaviors)} supportive "
            "behaviors. Tell me how to help (\"When I am …, I want you to …\"), ask \"How will you help me …?\" "
            "or \"When will you …?\"; 'behaviors' lists them, 'help' says more, 'quit' ends."
        )
        while True:
            try:
                line, self._next = (self._next if self._next is not None else self.read()).strip(), None
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
            if line.lower().strip("?!. ") in HELP:
                self._help()
                continue
            if line.lower().strip("?!. ") == "stop":
                self.write(
                    "Stop what? To stop one of my behaviors, say \"Don't …, when I am …\" "
                    "('behaviors' lists them); 'quit' ends the conversation."
                )
                continue
            self.respond(line)
        return self.spec

    def _help(self) -> None:
        """What the person can say, with this task's own subtasks and behaviors as examples."""
        subtasks = _outermost_first(self.states)
        first = self.spec.behaviors[0] if self.spec.behaviors else None
        during = [s for s in (first.subtasks if first else ()) if s in subtasks] or subtasks[-1:] or ["…"]
        doing = self.states.activity(during[0]) if subtasks else "…"
        asked = " ".join({"you": "me", "your": "my"}.get(w, w) for w in (first.text if first else "hold it").split())
        self.write("You can tell me how to help, or ask what I will do:")
        self.write(f'- "When I am {doing}, I want you to {asked}" (add "until …" to say when to stop)')
        self.write(f'- "Don\'t {asked} when I am {doing}"')
        self.write(f'- "How will you help me {during[0].lower()}?" or "When will you {asked}?"')
        self.write("- 'behaviors' lists what I do, 'help' shows this, 'quit' ends.")
        self.write(f"Parts of the task I know: {', '.join(subtasks[:KNOWN_SHOWN])}.")

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

    def _subtask(self, ranked: Sequence[Candidate], said: str) -> str | None:
        """The subtask a phrase means: the best candidate when the robot is sure, the one the person confirms
        otherwise; None (after saying why) when the phrase names no subtask it knows or the person declines."""
        if not self.understanding.subtask_matcher.recognises(ranked):
            known = ", ".join(_outermost_first(self.states)[:KNOWN_SHOWN])
            self.write(f"I don't know a part of the task like '{said}'. I know, for example: {known}.")
            return None
        if is_confident(list(ranked)):
            return ranked[0].key
        return self._confirm(ranked, f"By '{said}', do you mean {ranked[0].key}?")

    def _confirm(self, ranked: Sequence[Candidate], question: str) -> str | None:
        """Ask which candidate was meant; None when the person declines. Anything but yes, no or a candidate's
        number is taken as a new utterance: the question is dropped and the line answered next."""
        options = "; ".join(f"{i + 1}. {c.key} ({c.probability:.0%})" for i, c in enumerate(ranked))
        self.write(f"{question} (I considered: {options}) Answer yes, no or a number.")
        try:
            answer = self.read().strip()
        except EOFError:
            return None
        words = re.findall(r"\w+", answer.lower())
        word = words[0] if words and len(words) <= SHORT_ANSWER else " ".join(words)
        if word in YES:
            return ranked[0].key
        if word.isdigit() and 1 <= int(word) <= len(ranked):
            return ranked[int(word) - 1].key
        if word in NO:
            self.write("All right, I changed nothing.")
        else:
            self.write("I take that as something new, so I changed nothing for the question I asked.")
            self._next = answer
        return None

    def _prefer(self, preference: Preference) -> None:
        chosen = []
        for ranked, said in zip(self.understanding.ground(preference), preference.subtask_phrases, strict=True):
            key = self._subtask(ranked, said)
            if key is None:
                return
            chosen.append(key)
        for phrase in preference.behavior_phrases:
            try:
                understood = self.understanding.apply(preference, phrase, subtasks=chosen)
            except UnderstandingError as exc:
                self.write(str(exc))
                continue
            if understood.behavior != understood.before:
                self._save(understood.behavior)
            explanation = explain_behavior(self.states, understood.behavior).text
            self.write(f"{understood.acknowledgement} {explanation}")

    def _save(self, behavior: SupportiveBehavior) -> None:
        def put(current: TaskSpec) -> TaskSpec:
            """The file's task now (another session may have saved to it) with ``behavior`` in its place."""
            others = [b for b in current.behaviors if b.name != behavior.name]
            position = next((i for i, b in enumerate(current.behaviors) if b.name == behavior.name), len(others))
            others.insert(position, behavior)
            return current.with_behaviors(others)

        self.spec = self.copy.update(put) if self.copy is not None else update_task_file(self.path, put)
        self.saved += 1
        self.states = TaskStates.of(self.spec, self.states.structure)
        self.understanding = self.understanding.with_states(self.states)

    def _explain_subtask(self, request: ExplainSubtask) -> None:
        ranked = self.understanding.subtask_matcher.candidates(request.subtask_phrase)
        key = self._subtask(ranked, request.subtask_phrase)
        if key is not None:
            self.write(explain_subtask(self.states, key).text)

    def _explain_behavior(self, request: ExplainBehavior) -> None:
        behavior = self.understanding.behavior_for(request.behavior_phrase)
        if behavior is None:
            known = ", ".join(b.text for b in self.spec.behaviors) or "nothing yet"
            self.write(f"I have no behavior like '{request.behavior_phrase}'. I know how to: {known}.")
            return
        self.write(explain_behavior(self.states, behavior).text)


def _outermost_first(states: TaskStates) -> list[str]:
    """The task's named subtasks, breadth first from the root."""
    names: list[str] = []
    level: list[Node] = [states.structure]
    while level:
        names += [n.name for n in level if isinstance(n, ChainNode | CliqueNode) and n.name]
        level = [c for n in level if isinstance(n, ChainNode | CliqueNode) for c in n.children]
    return names
