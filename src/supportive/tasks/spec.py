"""What a task file holds: actions, an optional ground-truth structure, demonstrations."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field, replace

from supportive.errors import TaskModelError
from supportive.tasks.behaviors import PredicateSpec, SupportiveBehavior
from supportive.tasks.htn import Node, leaf_actions

__all__ = ["MISTAKE_LABELS", "Action", "Demonstration", "Keyframe", "Step", "TaskSpec", "mistake_label"]

MISTAKE_LABELS = (
    "order",
    "missing",
    "repeated",
    "unknown",
    "technique",
    "measurement",
    "timing",
    "temperature",
    "preparation",
    "other",
    "true",
)
"""The kinds of mistake a step may be labelled with, for evaluating mistake detection.

``order``: done too early or too late; ``missing``: not done at all (a placeholder marking where it should have
been, never a performed step); ``repeated``: done again when once was enough; ``unknown``: not a step of the
task; ``technique``, ``measurement``, ``timing``, ``temperature``, ``preparation``: done, in its place, but
badly (CaptainCook4D's kinds, not visible in the sequence of steps); ``other``: any other kind; ``true``: a
mistake whose kind is not given (``mistake: true`` in a file).
"""


def mistake_label(value: object) -> str | None:
    """A mistake label as a file may give it: one of :data:`MISTAKE_LABELS`, ``True`` (the label ``"true"``),
    or ``False`` / ``None`` (no label).

    >>> mistake_label(True), mistake_label("order"), mistake_label(False)
    ('true', 'order', None)

    Raises:
        TaskModelError: for anything else, listing the known labels.
    """
    if value is None or value is False:
        return None
    if value is True:
        return "true"
    if isinstance(value, str) and value in MISTAKE_LABELS:
        return value
    shown = repr(value) if isinstance(value, str) else f"{type(value).__name__} {value!r}"
    known = ", ".join(label for label in MISTAKE_LABELS if label != "true")
    raise TaskModelError(f"unknown mistake label {shown}; expected one of {known}, or true when the kind is not known")


@dataclass(frozen=True)
class Keyframe:
    """One keyframe of a skill (§3.4.2.1): where the end effector passes, projected onto the work surface.

    ``x`` and ``y`` are in the task's workspace units (metres on the workbench). ``text`` says what happens
    there (``open the gripper above the red block``). ``goal`` marks a goal state of the skill: an instructor
    demonstrating the skill in stages never performs it (§3.4.5.3); when no keyframe of a skill is marked, its
    last keyframe is the goal.
    """

    x: float
    y: float
    text: str | None = None
    goal: bool = False

    @property
    def point(self) -> tuple[float, float]:
        """The keyframe as an ``(x, y)`` pair."""
        return (self.x, self.y)


@dataclass(frozen=True)
class Action:
    """A primitive skill (an option, §2.0.0.2): an id used everywhere and a text for people.

    ``observations`` maps contact events (Semantic Event Chains, §2.1.7.1: e.g. ``"hand-peg"`` for the hand
    touching a peg) to the probability that the event holds at a moment while the action is performed.
    ``effects`` are the atoms doing it makes true (``attached(seat, left_frame)``) or, written ``not …``,
    false (§3.3: the predicates behaviors are described with). ``keyframes`` are the points its end effector
    passes through, in order (§3.4.5: where social force is read for the skill); empty when unknown.
    """

    id: str
    text: str | None = None
    observations: tuple[tuple[str, float], ...] = ()
    effects: tuple[str, ...] = ()
    keyframes: tuple[Keyframe, ...] = ()

    @property
    def label(self) -> str:
        """The text when there is one, else the id."""
        return self.text or self.id


@dataclass(frozen=True)
class Step:
    """One performed action, with optional timing, the environment state it produced and a mistake label.

    ``state`` is the set of fluents true after the step, when the file gives explicit states; otherwise states
    are derived from the completed actions (commutativity assumption, §2.1.2). ``mistake`` labels a step done
    wrongly (one of :data:`MISTAKE_LABELS`), for evaluating mistake detection. A step labelled ``missing`` is a
    *placeholder*, not a performed step: it marks where a skipped step should have been, as a task file writes it
    (see :meth:`Demonstration.entries`), and carries no timing or state.

    Raises:
        TaskModelError: for an unknown label, or a placeholder with timing or state.
    """

    action: str
    start: float | None = None
    end: float | None = None
    state: frozenset[str] | None = None
    mistake: str | None = None

    def __post_init__(self) -> None:
        if self.mistake is None:
            return
        mistake_label(self.mistake)
        if self.placeholder and (self.start is not None or self.end is not None or self.state is not None):
            raise TaskModelError(
                f"step {self.action!r} is labelled missing, so it was not performed: it takes no start, end or state"
            )

    @property
    def placeholder(self) -> bool:
        """True for a skipped step's placeholder (labelled ``missing``): not performed."""
        return self.mistake == "missing"


@dataclass(frozen=True)
class Demonstration:
    """One execution of the task (a path through the environment-space graph, §2.1.1).

    ``steps`` are the steps performed, in order. When the demonstration is labelled for evaluating mistake
    detection, steps may carry a ``mistake`` label, and ``skipped`` lists the steps that were left out as
    ``(position, action)`` pairs, ``position`` being how many performed steps came before the place where the
    skipped step should have been (non-decreasing; skipped steps at one place in the order they were due).
    Skipped steps are never part of :attr:`actions`: learning sees only what was performed.

    >>> demo = Demonstration.from_entries([Step("a"), Step("b", mistake="missing"), Step("c", mistake="order")])
    >>> demo.actions, demo.skipped, demo.labelled
    (('a', 'c'), ((1, 'b'),), True)

    Raises:
        TaskModelError: when a performed step is labelled ``missing``, or a skipped step's position is out of
            range or out of order.
    """

    steps: tuple[Step, ...]
    id: str = ""
    agent: str | None = None
    initial_state: frozenset[str] | None = None
    skipped: tuple[tuple[int, str], ...] = ()

    def __post_init__(self) -> None:
        if any(step.placeholder for step in self.steps):
            index = next(i for i, step in enumerate(self.steps) if step.placeholder)
            raise TaskModelError(
                f"demonstration {self.id!r}: step {index + 1} ({self.steps[index].action!r}) is labelled missing, "
                "so it was not performed; give it in 'skipped'"
            )
        last = 0
        for position, action in self.skipped:
            if not last <= position <= len(self.steps):
                raise TaskModelError(
                    f"demonstration {self.id!r}: skipped step {action!r} at position {position}; expected "
                    f"{last} to {len(self.steps)} (positions count the performed steps before it, in order)"
                )
            last = position

    @property
    def actions(self) -> tuple[str, ...]:
        """The action ids in the order performed (skipped steps left out)."""
        return tuple(step.action for step in self.steps)

    @property
    def labelled(self) -> bool:
        """True when a step carries a mistake label or a step was skipped."""
        return bool(self.skipped) or any(step.mistake is not None for step in self.steps)

    @property
    def entries(self) -> tuple[Step, ...]:
        """The steps as a task file lists them: the performed steps with each skipped step's placeholder
        (``Step(action, mistake="missing")``) where it should have been; the inverse of :meth:`from_entries`."""
        out: list[Step] = []
        skipped = iter(self.skipped)
        due = next(skipped, None)
        for index in range(len(self.steps) + 1):
            while due is not None and due[0] == index:
                out.append(Step(due[1], mistake="missing"))
                due = next(skipped, None)
            if index < len(self.steps):
                out.append(self.steps[index])
        return tuple(out)

    @classmethod
    def from_entries(
        cls,
        entries: Sequence[Step],
        id: str = "",
        agent: str | None = None,
        initial_state: frozenset[str] | None = None,
    ) -> Demonstration:
        """A demonstration from the steps as a task file lists them: placeholders (steps labelled ``missing``)
        become :attr:`skipped`, the other steps are the steps performed."""
        steps: list[Step] = []
        skipped: list[tuple[int, str]] = []
        for entry in entries:
            if entry.placeholder:
                skipped.append((len(steps), entry.action))
            else:
                steps.append(entry)
        return cls(tuple(steps), id, agent, initial_state, tuple(skipped))

    @property
    def has_states(self) -> bool:
        """True when the steps carry explicit environment states."""
        return any(step.state is not None for step in self.steps)

    @classmethod
    def of(cls, actions: Sequence[str], id: str = "", agent: str | None = None) -> Demonstration:
        """Build a demonstration from a plain sequence of action ids.

        >>> Demonstration.of(["a", "b"], id="d1").actions
        ('a', 'b')
        """
        return cls(steps=tuple(Step(a) for a in actions), id=id, agent=agent)


@dataclass(frozen=True)
class TaskSpec:
    """The contents of a task file.

    ``actions`` is the declared vocabulary (empty when the file declares none: then the vocabulary is whatever
    the structure and demonstrations use). ``structure`` is the ground-truth hierarchy when known.
    ``predicates`` and ``behaviors`` describe the supportive behaviors a person asked for (§3.3); ``objects``
    lists the task's objects by type, as ``(type, names)`` pairs (empty: the task declares none, and
    predicates' arguments are not checked against types).
    """

    name: str
    actions: tuple[Action, ...] = ()
    structure: Node | None = None
    demonstrations: tuple[Demonstration, ...] = field(default=())
    predicates: tuple[PredicateSpec, ...] = ()
    behaviors: tuple[SupportiveBehavior, ...] = ()
    objects: tuple[tuple[str, tuple[str, ...]], ...] = ()

    def action_ids(self) -> tuple[str, ...]:
        """Every action id: the declared ones, or those used by the structure and demonstrations."""
        if self.actions:
            return tuple(a.id for a in self.actions)
        seen: dict[str, None] = {}
        if self.structure is not None:
            seen.update((a, None) for a in leaf_actions(self.structure))
        for demo in self.demonstrations:
            seen.update((a, None) for a in demo.actions)
        return tuple(seen)

    def texts(self) -> dict[str, str]:
        """Map from action id to the text people read (the id itself when no text is given)."""
        return {a.id: a.label for a in self.actions}

    def action_sequences(self) -> Iterator[tuple[str, ...]]:
        """The demonstrations as plain action sequences."""
        for demo in self.demonstrations:
            yield demo.actions

    def with_demonstrations(self, demonstrations: Sequence[Demonstration]) -> TaskSpec:
        """A copy of this spec with other demonstrations."""
        return replace(self, demonstrations=tuple(demonstrations))

    def with_behaviors(self, behaviors: Sequence[SupportiveBehavior]) -> TaskSpec:
        """A copy of this spec with other supportive behaviors."""
        return replace(self, behaviors=tuple(behaviors))
