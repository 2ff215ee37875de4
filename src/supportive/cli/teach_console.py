"""``supportive teach``: a person teaches a task at the terminal while the learner asks for actions (§2.2).

The person types the actions they perform, one per line: an id, its text or its number in the list, in any
case; a typo is answered with what it is close to ("did you mean 'green'?"). At scheduled moments the learner
asks in words ("Can you place the purple block next?"); "yes" performs that action, "no" (then another action)
or performing another refuses it. A demonstration is a whole execution: an action is performed as often as
the task has it (once, unless its structure or demonstrations repeat it), never more, and ``done`` before every
action is in says what is still to do. After every demonstration the learner is updated and the task file is
saved with the new demonstration, so nothing is lost if the person stops.
"""

from __future__ import annotations

import difflib
from collections import Counter
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path

from supportive.io.task_edit import update_task_file
from supportive.io.taskfile import parse_task_file
from supportive.io.working_copy import WorkingCopy
from supportive.learning.active import QuerySchedule, TeachingSession
from supportive.learning.learner import HTNLearner
from supportive.tasks.executions import Executions
from supportive.tasks.htn import HTN, leaf_actions
from supportive.tasks.naming import known_names
from supportive.tasks.spec import Demonstration, TaskSpec

__all__ = ["Repertoire", "TeachingConsole", "ask_in_words"]

DONE, QUIT = "done", "quit"
YES = frozenset({"yes", "y", "yeah", "yep", "ok", "okay", "sure"})
NO = frozenset({"no", "n", "nope", "nah"})
HELP = frozenset({"help", "?"})
CLOSE = 0.6
"""How alike (difflib's ratio) a typo must be to an action's id or text to be suggested."""


@dataclass(frozen=True)
class Repertoire:
    """The actions a person may type and how often each belongs in one demonstration.

    Attributes:
        actions: The action ids, in the task's order.
        texts: Each action's text.
        required: How often each action is performed in a whole demonstration (its count in the structure,
            else the fewest times a recorded demonstration has it, else once).
        allowed: How often it may be performed (at least ``required``; more when a demonstration repeats it).
        structure: The executions the task file's structure admits (None without a structure).
    """

    actions: tuple[str, ...]
    texts: Mapping[str, str]
    required: Mapping[str, int]
    allowed: Mapping[str, int]
    structure: Executions | None = None

    @classmethod
    def of(cls, spec: TaskSpec) -> Repertoire:
        """The repertoire of a task file."""
        actions = spec.action_ids()
        counts = [Counter(steps) for steps in spec.action_sequences()]
        if spec.structure is not None:
            required = Counter(leaf_actions(spec.structure))
        elif counts:
            required = Counter({a: min(c[a] for c in counts) for a in actions})
        else:
            required = Counter(dict.fromkeys(actions, 1))
        allowed = {a: max([required[a], 1, *(c[a] for c in counts)]) for a in actions}
        structure = None if spec.structure is None else HTN(spec.name, (spec.structure,)).executions
        return cls(actions, spec.texts(), {a: required[a] for a in actions}, allowed, structure)

    def next_by_structure(self, done: tuple[str, ...]) -> frozenset[str] | None:
        """The actions the task's structure allows after ``done``; None without a structure, or when ``done``
        already left it (the person showed an order it does not have: it says nothing more)."""
        if self.structure is None:
            return None
        states = self.structure.run(done)
        if not states:
            return None
        return frozenset(action for state in states for action, _ in self.structure.allowed(state))

    def named(self, line: str) -> str | None:
        """The action a typed line names (id, text or number, any case), or None."""
        if line.isdigit():
            number = int(line)
            return self.actions[number - 1] if 1 <= number <= len(self.actions) else None
        wanted = line.casefold()
        for action in self.actions:
            if wanted in (action.casefold(), self.texts.get(action, action).casefold()):
                return action
        return None

    def close_to(self, line: str) -> list[str]:
        """The actions whose id or text a mistyped line is close to, closest first."""
        names = {action.casefold(): action for action in self.actions}
        names |= {self.texts.get(a, a).casefold(): a for a in self.actions}
        close = difflib.get_close_matches(line.casefold(), list(names), n=3, cutoff=CLOSE)
        return list(dict.fromkeys(names[c] for c in close))

    def missing(self, done: tuple[str, ...]) -> list[str]:
        """The actions a demonstration still needs before it is whole."""
        counts = Counter(done)
        return [a for a in self.actions if counts[a] < self.required[a]]

    def exhausted(self, done: tuple[str, ...]) -> bool:
        """True when every action has been performed as often as it may be: nothing more can come."""
        counts = Counter(done)
        return all(counts[a] >= self.allowed[a] for a in self.actions)


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
        copy: The working copy to save to (made at the first demonstration saved); None saves to ``path``.
    """

    path: Path
    read: Callable[[], str]
    write: Callable[[str], None]
    strategy: str = "distance"
    schedule: QuerySchedule = field(
        default_factory=lambda: QuerySchedule(after_steps=(1, 3, 5), max_per_demonstration=3)
    )
    seed: int | None = 0
    copy: WorkingCopy | None = None

    recorded: int = field(default=0, init=False)
    """Demonstrations saved by this session (each reported as saved)."""
    in_progress: int = field(default=0, init=False)
    """Steps of the demonstration under way, not saved yet (0 between demonstrations)."""
    saving: bool = field(default=False, init=False)
    """Whether a finished demonstration is being saved now."""
    _ready: tuple[TaskSpec, Repertoire, TeachingSession] | None = field(default=None, init=False, repr=False)

    def prepare(self) -> TaskSpec:
        """Read the task and set up the learner and the session: every check the task must pass, with nothing
        written (``teach`` calls it before it makes the working copy, so a task it refuses leaves no copy).
        Returns the task.

        Raises:
            SupportiveError: for a task a session cannot start on (no action, demonstrations that contradict
                each other, …).
        """
        self._ready = self._set_up()
        return self._ready[0]

    def _set_up(self) -> tuple[TaskSpec, Repertoire, TeachingSession]:
        spec = parse_task_file(self.path)
        repertoire = Repertoire.of(spec)
        learner = HTNLearner(names=known_names(spec.structure))
        if spec.demonstrations:
            learner.fit(spec)
        session = TeachingSession(spec.action_ids(), self.strategy, self.schedule, self.seed, learner)
        return spec, repertoire, session

    def run(self, demonstrations: int | None = None) -> TaskSpec:
        """Teach until the person quits, input ends, or ``demonstrations`` new ones are recorded (after
        :meth:`prepare`, which it calls when not called yet).

        Returns:
            The task as saved.
        """
        spec, repertoire, session = self._ready if self._ready is not None else self._set_up()
        actions = spec.action_ids()
        texts = spec.texts()
        self.write(
            f"Teaching {spec.name}: {len(actions)} actions, {len(spec.demonstrations)} demonstrations so far."
        )
        for number, action in enumerate(actions, start=1):
            self.write(f"  {number:2d}. {action}" + _text_of(action, texts))
        self.write(
            f"Type each action you perform (id, text or number); '{DONE}' ends a demonstration, '{QUIT}' stops, "
            "'help' shows the actions again."
        )
        while demonstrations is None or self.recorded < demonstrations:
            finished = self._demonstration(session, repertoire, _next_id(spec))
            if finished is None:
                break

            def append(current: TaskSpec, finished: Demonstration = finished) -> TaskSpec:
                """The file's task now (another session may have saved to it) with the new demonstration."""
                return current.with_demonstrations([*current.demonstrations, replace(finished, id=_next_id(current))])

            self.saving = True
            spec = self.copy.update(append) if self.copy is not None else update_task_file(self.path, append)
            finished = spec.demonstrations[-1]
            self.recorded += 1
            self.saving = False
            graph = session.learner.task_graph_
            shape = (
                "complete"
                if session.learner.htn_.complete
                else f"{len(session.learner.htn_.roots)} parts so far"
            )
            self.write(f"  recorded: {', '.join(finished.actions)}")
            saved_to = self.copy.path if self.copy is not None else self.path
            self.write(
                f"Saved demonstration {finished.id} to {saved_to}. Known valid orders: {graph.path_count()}; "
                f"hierarchy: {shape}."
            )
        return spec

    def _demonstration(self, session: TeachingSession, repertoire: Repertoire, label: str) -> Demonstration | None:
        """One demonstration, to be saved as ``label``; None when the person quits (an unfinished
        demonstration is dropped: a partial execution is not a valid demonstration)."""
        session.begin()
        self.write(f"Demonstration {label}:")
        asked_at = -1
        while True:
            self.in_progress = len(session.done)
            _rule_out(session, repertoire)
            question = session.query()
            if question is not None and asked_at != len(session.done):
                asked_at = len(session.done)
                self.write("  robot: " + ask_in_words(question, dict(repertoire.texts)))
            try:
                line = self.read().strip()
            except EOFError:
                line = QUIT
            word = line.casefold().strip(".!")
            if word == QUIT:
                self.in_progress = 0
                if session.done:
                    steps = len(session.done)
                    self.write(f"  dropped the unfinished demonstration ({steps} step{'s' if steps > 1 else ''})")
                return None
            if word == DONE:
                missing = repertoire.missing(session.done)
                if not session.done:
                    self.write("  nothing performed yet: type an action first")
                elif missing:
                    self.write(
                        f"  not finished: still to do {', '.join(missing)}; type them, or '{QUIT}' to drop it"
                    )
                else:
                    return self._end(session)
                continue
            action = self._action(line, word, question, session, repertoire)
            if action is None:
                continue
            allowed = repertoire.next_by_structure(session.done)
            if allowed is not None and action not in allowed:
                self.write(
                    f"  note: the task's structure has no order with {action} here (next it allows "
                    f"{', '.join(sorted(allowed))}); recorded as you did it"
                )
            session.observe(action)
            self.in_progress = len(session.done)
            if repertoire.exhausted(session.done):
                return self._end(session)

    def _end(self, session: TeachingSession) -> Demonstration:
        """End the demonstration under way (it is no longer unfinished: it is saved next)."""
        finished = session.end()
        self.in_progress = 0
        return finished

    def _action(
        self, line: str, word: str, question: str | None, session: TeachingSession, repertoire: Repertoire
    ) -> str | None:
        """The action a typed line performs, or None after saying why it performs none."""
        if not line:
            self.write(f"  (empty line) type an action id, text or number, '{DONE}' or '{QUIT}'")
            return None
        if word in HELP:
            for number, known in enumerate(repertoire.actions, start=1):
                self.write(f"  {number:2d}. {known}" + _text_of(known, repertoire.texts))
            return None
        if word in YES | NO:
            if question is None:
                self.write(f"  no question is waiting: type the action you perform, '{DONE}' or '{QUIT}'")
                return None
            if word in YES:
                return question
            self.write("  all right: type the action you do instead")
            return None
        action = repertoire.named(line)
        if action is None:
            close = repertoire.close_to(line)
            hint = f"; did you mean {' or '.join(repr(c) for c in close)}?" if close else ""
            self.write(f"  unknown action {line!r}{hint} ('help' lists them)")
            return None
        performed = session.done.count(action)
        if performed >= repertoire.allowed[action]:
            times = "once" if performed == 1 else f"{performed} times"
            self.write(f"  {action} is already done ({times}) in this demonstration; type another action")
            return None
        return action


def _next_id(spec: TaskSpec) -> str:
    """The id the next demonstration saved to the task gets: ``d`` and the first free number from the count.

    >>> _next_id(TaskSpec("t", demonstrations=(Demonstration.of(["a"], id="d1"), Demonstration.of(["a"], id="d3"))))
    'd4'
    """
    taken = {d.id for d in spec.demonstrations}
    number = len(spec.demonstrations) + 1
    while f"d{number}" in taken:
        number += 1
    return f"d{number}"


def _rule_out(session: TeachingSession, repertoire: Repertoire) -> None:
    """Keep the learner from asking for what the task file's structure rules out next: each such action is
    recorded as refused at this state, as if the person had said no."""
    allowed = repertoire.next_by_structure(session.done)
    if allowed:
        for action in repertoire.actions:
            if action not in allowed:
                session.anti_edges.add(session.done, action)


def _text_of(action: str, texts: Mapping[str, str]) -> str:
    text = texts.get(action, action)
    return f" — {text}" if text != action else ""
