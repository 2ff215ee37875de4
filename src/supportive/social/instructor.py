"""The robot as instructor (§3.4.5.3): staged keyframe demonstrations until the student takes the skill up.

For a skill with keyframes ``kf_1 … kf_n``, repetition ``r`` (1, 2, …) plays

    K = [kf_i : i ≤ r, kf_i not a goal state]

forward, ``kf_1 … kf_|K|``, then back, ``kf_|K| … kf_1`` (the thesis's sequence: the furthest keyframe is
listed twice, so the robot pauses there for one target before it turns back). ``r`` grows by one each cycle
until ``K`` holds every keyframe that is not a goal, so each repetition reveals more of the skill and none
completes it. The goal states are the keyframes marked ``goal`` in the task file, or the last keyframe when
none is marked.

Social force is the trigger: once the student's force at the skill's region (the largest at any of its
keyframes, as :func:`~supportive.social.reading.reading`) reaches ``trigger``, the student has begun the skill,
the demonstration stops, the skill is recorded as taken up, and the robot moves on to the next skill in its
preferred order.
"""

from __future__ import annotations

from collections.abc import Sequence

from supportive.errors import SocialError
from supportive.social.checks import within
from supportive.social.force import ForceSource
from supportive.social.reading import reading
from supportive.tasks.spec import Action, Keyframe

__all__ = ["InstructorPolicy", "demonstrable"]


def demonstrable(skill: Action) -> tuple[int, ...]:
    """The 1-based positions of ``skill``'s keyframes that are not goal states (the goal states: those
    marked ``goal``, or the last keyframe when none is marked).

    >>> from supportive.tasks.spec import Keyframe
    >>> demonstrable(Action("a", keyframes=(Keyframe(0, 0), Keyframe(1, 0), Keyframe(2, 0))))
    (1, 2)
    >>> demonstrable(Action("a", keyframes=(Keyframe(0, 0), Keyframe(1, 0, goal=True), Keyframe(2, 0))))
    (1, 3)
    """
    marked = any(k.goal for k in skill.keyframes)
    last = len(skill.keyframes)
    return tuple(
        i for i, k in enumerate(skill.keyframes, start=1) if not (k.goal if marked else i == last)
    )


class InstructorPolicy:
    """Teach skills in a preferred order by staged demonstration, driven one target at a time.

    Args:
        trigger: The student's force at the skill's region that means "the student has begun it", in
            ``(0, 1]``.
        skills: The skills to teach, in the robot's preferred order, each with keyframes and at least one
            keyframe that is not a goal state.

    Raises:
        SocialError: when ``trigger`` is out of range, a skill id repeats, or a skill has nothing to
            demonstrate (no keyframes, or only goal states).

    >>> from supportive.tasks.spec import Keyframe
    >>> pick = Action("pick_red", keyframes=tuple(Keyframe(x, 0.3) for x in (1.0, 1.1, 1.2)))
    >>> teacher = InstructorPolicy(0.5, [pick])
    >>> [teacher.next_target(0.0).x for _ in range(6)]    # repetition 1, then 2 (kf_3 is the goal)
    [1.0, 1.0, 1.0, 1.1, 1.1, 1.0]
    >>> teacher.next_target(0.8) is None, teacher.taken_up, teacher.done
    (True, ('pick_red',), True)
    """

    def __init__(self, trigger: float, skills: Sequence[Action]) -> None:
        self.trigger = within(trigger, "trigger", 0.0, 1.0, low_included=False)
        ids = [s.id for s in skills]
        if len(set(ids)) != len(ids):
            raise SocialError(f"each skill is taught once, repeated: {', '.join(sorted({i for i in ids if ids.count(i) > 1}))}")
        for skill in skills:
            if not demonstrable(skill):
                has = "only goal keyframes" if skill.keyframes else "no keyframes"
                raise SocialError(f"skill {skill.id!r} has {has}: there is nothing to demonstrate short of its goal")
        self.skills = tuple(skills)
        self._index = 0
        self._repetition = 1
        self._position = 0
        self._taken_up: list[str] = []

    @property
    def skill(self) -> Action | None:
        """The skill being taught, None once all are taken up."""
        return self.skills[self._index] if self._index < len(self.skills) else None

    @property
    def done(self) -> bool:
        """True once the student has taken up every skill."""
        return self._index >= len(self.skills)

    @property
    def repetition(self) -> int:
        """The current repetition of the current skill, from 1."""
        return self._repetition

    @property
    def position(self) -> int:
        """How many targets of the current repetition have been given."""
        return self._position

    @property
    def taken_up(self) -> tuple[str, ...]:
        """The skills the student has taken up, in order."""
        return tuple(self._taken_up)

    def cycle(self, repetition: int | None = None) -> tuple[Keyframe, ...]:
        """The targets of a repetition (default: the current one) of the current skill: ``K`` forward, then
        back; empty once every skill is taken up.

        Raises:
            SocialError: for a repetition below 1.
        """
        r = self._repetition if repetition is None else repetition
        if r < 1:
            raise SocialError(f"repetitions count from 1, got {r}")
        skill = self.skill
        if skill is None:
            return ()
        stage = tuple(skill.keyframes[i - 1] for i in demonstrable(skill) if i <= r)
        return stage + stage[::-1]

    def reading(self, force: ForceSource) -> float:
        """The student's force at the current skill's region (its keyframes, goal states included); 0 once
        every skill is taken up."""
        skill = self.skill
        return 0.0 if skill is None else reading(force, [k.point for k in skill.keyframes])

    def next_target(self, force_reading: float) -> Keyframe | None:
        """One tick: given the student's force at the current skill's region, the next keyframe to move to.

        None when the reading reaches ``trigger`` (the student has begun: the skill is taken up, the
        demonstration stops and the next call teaches the next skill) or when every skill is taken up.

        Raises:
            SocialError: when ``force_reading`` is not a number in ``[0, 1]``.
        """
        force_reading = within(force_reading, "force_reading", 0.0, 1.0)
        skill = self.skill
        if skill is None:
            return None
        if force_reading >= self.trigger:
            self._taken_up.append(skill.id)
            self._index += 1
            self._repetition, self._position = 1, 0
            return None
        targets = self.cycle()
        target = targets[self._position]
        self._position += 1
        if self._position == len(targets):
            self._position = 0
            self._repetition = min(self._repetition + 1, demonstrable(skill)[-1])
        return target
