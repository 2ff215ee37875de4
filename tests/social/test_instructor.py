"""The robot as instructor (§3.4.5.3): staged keyframe demonstrations until the student takes the skill up."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from supportive.errors import SocialError
from supportive.social import InstructorPolicy, SocialForce, demonstrable
from supportive.tasks.spec import Action, Keyframe

Hands = Callable[[], Any]
THESIS_ORDER = ("locate_blue", "push_blue", "pick_red", "place_red")  # the order the robot was trained to teach


def texts(keyframes: tuple[Keyframe, ...] | list[Keyframe | None]) -> list[str | None]:
    return [None if k is None else k.text for k in keyframes]


def test_repetitions_reveal_growing_prefixes_and_never_the_goal(workbench: dict[str, Action]) -> None:
    pick = workbench["pick_red"]
    above, orient, lower, close = (k.text for k in pick.keyframes)
    assert pick.keyframes[-1].goal
    teacher = InstructorPolicy(0.5, [pick])
    assert texts(teacher.cycle(1)) == [above, above]
    assert texts(teacher.cycle(2)) == [above, orient, orient, above]
    assert texts(teacher.cycle(3)) == [above, orient, lower, lower, orient, above]
    assert teacher.cycle(4) == teacher.cycle(3)  # capped: everything short of the goal

    ticks = [teacher.next_target(0.0) for _ in range(2 + 4 + 6 + 6)]  # no response from the student
    assert texts(ticks) == [above, above, above, orient, orient, above, *texts(teacher.cycle(3)) * 2]
    assert close not in texts(ticks)
    assert teacher.repetition == 3 and teacher.position == 0 and teacher.taken_up == ()


def test_goals_marked_in_the_middle_are_skipped() -> None:
    kf = [Keyframe(float(i), 0.0, f"k{i}", goal=i == 2) for i in range(1, 5)]
    skill = Action("s", keyframes=tuple(kf))
    assert demonstrable(skill) == (1, 3, 4)  # marked goals replace the default (the last keyframe)
    teacher = InstructorPolicy(0.5, [skill])
    assert texts(teacher.cycle(2)) == ["k1", "k1"]  # kf_2 is a goal: repetition 2 shows what 1 did
    assert texts(teacher.cycle(3)) == ["k1", "k3", "k3", "k1"]
    assert texts(teacher.cycle(9)) == ["k1", "k3", "k4", "k4", "k3", "k1"]
    for _ in range(2 + 2 + 4 + 6):
        teacher.next_target(0.0)
    assert teacher.repetition == 4  # capped at the last keyframe that is not a goal


def test_the_demonstration_stops_when_the_student_starts(hand: Hands, workbench: dict[str, Action]) -> None:
    teacher = InstructorPolicy(0.4, [workbench["pick_red"], workbench["place_red"]])
    student = hand().hold(0.5)
    shown: list[Keyframe] = []
    for _ in range(8):  # the student watches for eight targets: repetitions 1 and 2, two targets of 3
        target = teacher.next_target(teacher.reading(student.force))
        assert target is not None
        shown.append(target)
        student.hold(0.1)
    assert teacher.repetition == 3 and teacher.skill == workbench["pick_red"]
    student.move((1.35, 0.30), seconds=0.5).hold(0.3)  # the student reaches for the red block
    reading = teacher.reading(student.force)
    assert reading >= 0.4
    assert teacher.next_target(reading) is None  # stop demonstrating: the student has taken it up
    assert teacher.taken_up == ("pick_red",) and teacher.skill == workbench["place_red"]
    assert (teacher.repetition, teacher.position) == (1, 0)
    student.move((0.9, 0.02), seconds=0.5).hold(1.0)  # and goes back to watching
    assert teacher.next_target(teacher.reading(student.force)) == workbench["place_red"].keyframes[0]


def test_the_thesis_ordering_is_taught_skill_by_skill(hand: Hands, workbench: dict[str, Action]) -> None:
    """The student takes each skill up after watching two repetitions of it (§3.4.5.3)."""
    teacher = InstructorPolicy(0.4, [workbench[s] for s in THESIS_ORDER])
    student = hand().hold(0.5)
    watched: dict[str, int] = {}
    for _ in range(400):
        skill = teacher.skill
        if skill is None:
            break
        if watched.get(skill.id, 0) == 2:  # seen twice: the student does the skill
            for k in skill.keyframes:
                student.move(k.point, seconds=0.3)
            student.hold(0.2)
            assert teacher.next_target(teacher.reading(student.force)) is None
            student.move((0.9, 0.02), seconds=0.6).hold(0.8)  # back to watching, out of the next region
            continue
        target = teacher.next_target(teacher.reading(student.force))
        assert target is not None and not target.goal
        if teacher.position == 0:
            watched[skill.id] = watched.get(skill.id, 0) + 1
        student.hold(0.1)
    assert teacher.done and teacher.taken_up == THESIS_ORDER
    assert watched == dict.fromkeys(THESIS_ORDER, 2)
    assert teacher.skill is None and teacher.cycle() == () and teacher.reading(student.force) == 0.0
    assert teacher.next_target(0.0) is None


def test_a_reading_at_another_skill_does_not_trigger(hand: Hands, workbench: dict[str, Action]) -> None:
    teacher = InstructorPolicy(0.4, [workbench["pick_red"]])
    student = hand().move((0.55, 0.30)).hold(0.5)  # busy at the blue block
    assert teacher.reading(student.force) == 0.0
    assert teacher.next_target(teacher.reading(student.force)) is not None and teacher.taken_up == ()


def test_bad_skills_and_thresholds_are_refused(workbench: dict[str, Action]) -> None:
    with pytest.raises(SocialError, match="'rest_blue' has only goal keyframes"):
        InstructorPolicy(0.5, [workbench["rest_blue"]])
    with pytest.raises(SocialError, match="'bare' has no keyframes"):
        InstructorPolicy(0.5, [Action("bare")])
    with pytest.raises(SocialError, match="repeated: pick_red"):
        InstructorPolicy(0.5, [workbench["pick_red"], workbench["pick_red"]])
    for trigger in (0.0, 1.5, float("nan"), "high"):
        with pytest.raises(SocialError, match=r"trigger must be a number in \(0, 1\]"):
            InstructorPolicy(trigger, [workbench["pick_red"]])  # type: ignore[arg-type]
    teacher = InstructorPolicy(0.5, [workbench["pick_red"]])
    with pytest.raises(SocialError, match=r"force_reading must be a number in \[0, 1\]"):
        teacher.next_target(float("nan"))
    with pytest.raises(SocialError, match="repetitions count from 1"):
        teacher.cycle(0)
    assert teacher.next_target(0.0) is not None  # a refused reading changed nothing
    assert InstructorPolicy(0.5, []).done


def test_reading_is_the_largest_force_at_the_skill_including_its_goal(workbench: dict[str, Action]) -> None:
    push = workbench["push_blue"]
    teacher = InstructorPolicy(0.5, [push])
    at_goal = SocialForce(min_radius=0.05)
    at_goal.update(0.0, push.keyframes[-1].point)
    assert teacher.reading(at_goal) == pytest.approx(1.0)
