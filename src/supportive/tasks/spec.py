"""What a task file holds: actions, an optional ground-truth structure, demonstrations."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field, replace

from supportive.tasks.behaviors import PredicateSpec, SupportiveBehavior
from supportive.tasks.htn import Node, leaf_actions

__all__ = ["Action", "Demonstration", "Keyframe", "Step", "TaskSpec"]


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
    """One performed action, with optional timing and the environment state it produced.

    ``state`` is the set of fluents true after the step, when the file gives explicit states; otherwise states
    are derived from the completed actions (commutativity assumption, §2.1.2).
    """

    action: str
    start: float | None = None
    end: float | None = None
    state: frozenset[str] | None = None


@dataclass(frozen=True)
class Demonstration:
    """One successful execution of the task (a path through the environment-space graph, §2.1.1)."""

    steps: tuple[Step, ...]
    id: str = ""
    agent: str | None = None
    initial_state: frozenset[str] | None = None

    @property
    def actions(self) -> tuple[str, ...]:
        """The action ids in the order performed."""
        return tuple(step.action for step in self.steps)

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
