"""Role policies (§3.4.3, §3.4.5): how a robot picks its next subtask from other agents' social force.

A policy is a pure decision object: given the *candidate subtasks* (those the task tree offers now, each with
the keyframes its skill passes through, whether another agent has claimed it and whether it is the robot's own
current one) and a force source (the other agents' :class:`~supportive.social.field.ForceField`, say), it
returns a :class:`RoleDecision` and changes nothing. Each subtask is read with
:func:`~supportive.social.reading.reading`, the largest force at its keyframes.

* :class:`StudentPolicy` treats the force as **attractive**: it starts the subtask an instructor is gesturing
  towards, once the cue reaches ``min_force``, and otherwise waits (§3.4.5.1).
* :class:`PeerPolicy` treats it as **repulsive**: desirability is ``−reading``; it starts the least
  conflicting subtask, abandons its own for a free one that is better by more than ``switch_margin``, and
  halts when nothing is free and its own is less desirable than ``halt_below`` (§3.4.3, §3.4.5.2).

Ties (readings within 1e-9 of each other, as when no one exerts any force) are broken at random, as the thesis
does, by the policy's seeded generator, drawn from only when a tie decides what to start or switch to: the same
seed and the same calls give the same decisions.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from enum import StrEnum

import numpy as np

from supportive.errors import SocialError
from supportive.seeding import Seed, rng_from
from supportive.social.checks import as_point, within
from supportive.social.force import ForceSource
from supportive.social.reading import reading
from supportive.tasks.spec import Action

__all__ = ["Candidate", "PeerPolicy", "RoleAction", "RoleDecision", "StudentPolicy"]

TIE_TOLERANCE = 1e-9
"""Readings closer than this are a tie."""


class RoleAction(StrEnum):
    """What a policy tells the robot to do."""

    START = "start"
    """Claim and begin ``subtask`` (the robot had none)."""
    CONTINUE = "continue"
    """Carry on with the current ``subtask`` (or resume it after a halt)."""
    SWITCH = "switch"
    """Abort the current subtask, release it and begin ``subtask`` instead."""
    HALT = "halt"
    """Stop moving but keep the current ``subtask``: it is contested and nothing else is free."""
    WAIT = "wait"
    """Do nothing yet: there are free subtasks but no cue to take one."""
    IDLE = "idle"
    """Do nothing: no subtask is free for the robot."""


@dataclass(frozen=True)
class Candidate:
    """A subtask the robot could do now.

    Attributes:
        id: The subtask's id (an action id of the task file, or a branch's name).
        keyframes: The ``(x, y)`` points its skill's end effector passes through; none: no force is read.
        claimed: Another agent owns it.
        current: It is the robot's own current subtask.

    Raises:
        SocialError: when the candidate is both claimed by another agent and the robot's current one, or a
            keyframe is not a finite ``(x, y)`` pair.
    """

    id: str
    keyframes: tuple[tuple[float, float], ...] = ()
    claimed: bool = False
    current: bool = False

    def __post_init__(self) -> None:
        if self.claimed and self.current:
            raise SocialError(f"subtask {self.id!r} cannot be claimed by another agent and be the robot's own")
        points = tuple(as_point(k, f"keyframe {i + 1} of {self.id!r}") for i, k in enumerate(self.keyframes))
        object.__setattr__(self, "keyframes", points)

    @classmethod
    def from_action(cls, action: Action, *, claimed: bool = False, current: bool = False) -> Candidate:
        """The candidate for a task file's action, with its keyframes.

        >>> from supportive.tasks.spec import Keyframe
        >>> Candidate.from_action(Action("pick_red", keyframes=(Keyframe(1.35, 0.3),))).keyframes
        ((1.35, 0.3),)
        """
        return cls(action.id, tuple(k.point for k in action.keyframes), claimed, current)


@dataclass(frozen=True)
class RoleDecision:
    """One decision of a role policy.

    Attributes:
        action: What to do.
        subtask: The subtask it concerns (the one to start, continue, switch to or halt), None for
            ``wait`` and ``idle``.
        readings: Every candidate's social-force reading, ``(id, reading)`` in the candidates' order.
        reason: Why, in a sentence people can read.
    """

    action: RoleAction
    subtask: str | None
    readings: tuple[tuple[str, float], ...]
    reason: str

    def reading(self, subtask: str) -> float:
        """The reading a candidate had.

        Raises:
            SocialError: for a subtask that was not a candidate.
        """
        for name, value in self.readings:
            if name == subtask:
                return value
        raise SocialError(f"{subtask!r} was not a candidate (candidates: {', '.join(n for n, _ in self.readings)})")


class _Policy:
    """What both policies share: reading the candidates and breaking ties with a seeded generator."""

    def __init__(self, seed: Seed) -> None:
        self._rng: np.random.Generator = rng_from(seed)

    @staticmethod
    def _read(
        candidates: Sequence[Candidate], force: ForceSource
    ) -> tuple[dict[str, float], Candidate | None, list[Candidate]]:
        """Each candidate's reading, the current candidate, and the free ones (neither claimed nor current).

        Raises:
            SocialError: for repeated ids or more than one current candidate.
        """
        ids = [c.id for c in candidates]
        if len(set(ids)) != len(ids):
            repeated = sorted({i for i in ids if ids.count(i) > 1})
            raise SocialError(f"candidate ids must be unique, repeated: {', '.join(repeated)}")
        current = [c for c in candidates if c.current]
        if len(current) > 1:
            raise SocialError(f"only one candidate can be current, got {', '.join(c.id for c in current)}")
        readings = {c.id: reading(force, c.keyframes) for c in candidates}
        free = [c for c in candidates if not c.claimed and not c.current]
        return readings, (current[0] if current else None), free

    @staticmethod
    def _top(scored: list[tuple[str, float]]) -> tuple[float, list[str]]:
        """The highest score and the ids tied at it."""
        top = max(score for _, score in scored)
        return top, [name for name, score in scored if score >= top - TIE_TOLERANCE]

    def _choose(self, tied: list[str]) -> str:
        """One of the tied ids, at random when there are several (the generator is drawn from only then)."""
        return tied[int(self._rng.integers(len(tied)))] if len(tied) > 1 else tied[0]


def _tie_note(tied: list[str]) -> str:
    return f", chosen at random among the tied {', '.join(tied)}" if len(tied) > 1 else ""


class StudentPolicy(_Policy):
    """The robot as a student: it does what the instructor's social force points at (§3.4.5.1).

    Args:
        min_force: The reading a free subtask needs before the robot takes it, in ``(0, 1]``; below it the
            robot waits, so it stays still until it is shown what to do.
        seed: Breaks ties between equally strong cues.

    Raises:
        SocialError: when ``min_force`` is not in ``(0, 1]``.

    >>> from supportive.social.force import SocialForce
    >>> hand = SocialForce()
    >>> StudentPolicy(0.3).decide([Candidate("a", ((0.2, 0.2),))], hand).action
    <RoleAction.WAIT: 'wait'>
    >>> hand.update(0.0, (0.2, 0.21))
    >>> StudentPolicy(0.3).decide([Candidate("a", ((0.2, 0.2),))], hand).action
    <RoleAction.START: 'start'>
    """

    def __init__(self, min_force: float, seed: Seed = None) -> None:
        super().__init__(seed)
        self.min_force = within(min_force, "min_force", 0.0, 1.0, low_included=False)

    def decide(self, candidates: Sequence[Candidate], force: ForceSource) -> RoleDecision:
        """Continue the current subtask; else start the free subtask with the strongest cue when it reaches
        ``min_force``; else wait (idle when nothing is free).

        Raises:
            SocialError: for repeated ids or more than one current candidate.
        """
        readings, current, free = self._read(candidates, force)
        used = tuple(readings.items())
        if current is not None:
            return RoleDecision(
                RoleAction.CONTINUE, current.id, used, f"finishing {current.id!r}, the subtask it was shown"
            )
        if not free:
            return RoleDecision(RoleAction.IDLE, None, used, "no subtask is free")
        top, tied = self._top([(c.id, readings[c.id]) for c in free])
        if top < self.min_force:
            return RoleDecision(
                RoleAction.WAIT,
                None,
                used,
                f"waiting for a cue: the strongest, {top:.2f} at {', '.join(tied)}, is below {self.min_force:.2f}",
            )
        chosen = self._choose(tied)
        return RoleDecision(
            RoleAction.START,
            chosen,
            used,
            f"starting {chosen!r}: the instructor's cue there is {top:.2f} (at least {self.min_force:.2f})"
            + _tie_note(tied),
        )


class PeerPolicy(_Policy):
    """The robot as a peer: it keeps out of other agents' way (§3.4.3, §3.4.5.2).

    Desirability is ``−reading``, in ``[−1, 0]``.

    Args:
        switch_margin: How much more desirable a free subtask must be than the current one (strictly more
            than this) for the robot to abort its own and switch, in ``[0, 1]``; 1 never switches.
        halt_below: With nothing free, the robot halts while its own subtask's desirability is below this, in
            ``[−1, 0]`` (−0.5: halt while the reading there is above 0.5; −1 never halts); it resumes once the
            desirability is back at or above it.
        seed: Breaks ties between equally desirable subtasks.

    Raises:
        SocialError: when a threshold is out of its range.

    >>> from supportive.social.force import SocialForce
    >>> person = SocialForce()
    >>> person.update(0.0, (0.2, 0.2))                # the person's hand is at subtask a
    >>> peer = PeerPolicy(switch_margin=0.2, halt_below=-0.5)
    >>> peer.decide([Candidate("a", ((0.2, 0.2),)), Candidate("b", ((1.0, 0.2),))], person).subtask
    'b'
    """

    def __init__(self, switch_margin: float, halt_below: float, seed: Seed = None) -> None:
        super().__init__(seed)
        self.switch_margin = within(switch_margin, "switch_margin", 0.0, 1.0)
        self.halt_below = within(halt_below, "halt_below", -1.0, 0.0)

    def decide(self, candidates: Sequence[Candidate], force: ForceSource) -> RoleDecision:
        """Start the least conflicting free subtask when the robot has none; otherwise switch to a free one
        that beats the current by more than ``switch_margin``, halt when nothing is free and the current one is
        below ``halt_below``, or continue.

        Raises:
            SocialError: for repeated ids or more than one current candidate.
        """
        readings, current, free = self._read(candidates, force)
        used = tuple(readings.items())
        best = self._top([(c.id, -readings[c.id]) for c in free]) if free else None
        if current is None:
            if best is None:
                return RoleDecision(RoleAction.IDLE, None, used, "no subtask is free")
            desirability, tied = best
            chosen = self._choose(tied)
            return RoleDecision(
                RoleAction.START,
                chosen,
                used,
                f"starting {chosen!r}, the least contested free subtask (force {-desirability:.2f})"
                + _tie_note(tied),
            )
        own = -readings[current.id]
        if best is not None:
            desirability, tied = best
            if desirability - own > self.switch_margin:
                chosen = self._choose(tied)
                return RoleDecision(
                    RoleAction.SWITCH,
                    chosen,
                    used,
                    f"switching from {current.id!r} (force {-own:.2f}) to {chosen!r} (force {-desirability:.2f}):"
                    f" better by more than {self.switch_margin:.2f}" + _tie_note(tied),
                )
            return RoleDecision(
                RoleAction.CONTINUE,
                current.id,
                used,
                f"continuing {current.id!r} (force {-own:.2f}): no free subtask is better by more than "
                f"{self.switch_margin:.2f}",
            )
        if own < self.halt_below:
            return RoleDecision(
                RoleAction.HALT,
                current.id,
                used,
                f"halting {current.id!r}: another agent is there (force {-own:.2f}, desirability below "
                f"{self.halt_below:.2f}) and no other subtask is free",
            )
        return RoleDecision(
            RoleAction.CONTINUE,
            current.id,
            used,
            f"continuing {current.id!r} (force {-own:.2f}, desirability at least {self.halt_below:.2f})",
        )
