"""``supportive workbench-sim``: the whole loop — a board service, a simulated person, a robot in each role —
on one machine, and what the robot did in each."""

from __future__ import annotations

from collections.abc import Callable

import pytest

from supportive.cli.workbench_sim import Line, run_workbench

CliRunner = Callable[[list[str]], tuple[int, str, str]]


@pytest.fixture(scope="module")
def stories() -> dict[str, list[Line]]:
    return {role: run_workbench(role, seconds=40.0) for role in ("student", "peer", "instructor")}


def said(lines: list[Line], who: str, start: str) -> list[Line]:
    return [line for line in lines if line.who == who and line.text.startswith(start)]


def test_the_student_waits_for_each_gesture_and_does_what_is_pointed_at(
    stories: dict[str, list[Line]],
) -> None:
    lines = stories["student"]
    started = [line for line in said(lines, "robot", "student: starting")]
    assert [line.text.split("'")[1] for line in started] == [
        "locate the blue block",
        "push the blue block next to the green one",
        "return the left arm to rest",
        "pick up the red block",
        "place the red block on the joined bases",
        "return the right arm to rest",
    ]
    assert started[0].t >= 1.5  # nothing before the person points at the blue block (at 1.5-2.5 s)
    assert said(lines, "robot", "student: waiting for a cue")[0].t == 0.0
    assert len(said(lines, "robot", "completed")) == 6


def test_the_peer_keeps_out_of_the_way_and_yields_the_contested_subtask(
    stories: dict[str, list[Line]],
) -> None:
    lines = stories["peer"]
    first = said(lines, "robot", "peer: starting")[0]
    assert "'pick up the red block'" in first.text and first.t == 0.0  # away from the person's hand at the blue block
    switch = said(lines, "robot", "peer: switching")
    assert switch and "from 'pick up the red block'" in switch[0].text and "to 'locate the blue block'" in switch[0].text
    assert 0.6 <= switch[0].t < 1.2  # as soon as the person's hand heads for the red block
    assert said(lines, "alice", "claims 'pick up the red block'")[0].t > switch[0].t
    done = {line.text.split("'")[1] for line in said(lines, "robot", "completed")}
    assert "pick up the red block" not in done and {"locate the blue block", "push the blue block next to the green one", "place the red block on the joined bases"} <= done


def test_the_instructor_stages_the_skill_and_stops_when_the_student_starts(
    stories: dict[str, list[Line]],
) -> None:
    lines = stories["instructor"]
    stages = said(lines, "robot", "instructor: repetition")
    red = [line for line in stages if "red block" in line.text]
    assert [line.text.split(":")[1].strip() for line in red[:3]] == [
        "repetition 1",
        "repetition 2",
        "repetition 3",
    ]
    assert all("close the gripper" not in line.text for line in stages)  # the goal state is never shown
    begun = said(lines, "robot", "instructor: the student has begun")
    assert [line.text.split("'")[1] for line in begun] == ["pick up the red block", "locate the blue block"]
    assert 9.0 <= begun[0].t <= 11.0  # when the person's hand reaches the red block (10.5 s)
    assert not [line for line in stages if "red block" in line.text and line.t > begun[0].t]


def test_the_command_tells_the_story(cli: CliRunner) -> None:
    code, out, err = cli(["workbench-sim", "--role", "peer", "--seconds", "12"])
    assert code == 0, err
    assert "the robot as peer" in out and "switching from 'pick up the red block'" in out
    code, _, err = cli(["workbench-sim", "--role", "boss"])
    assert code == 2 and "unknown role 'boss'" in err


def test_robot_lines_name_subtasks_as_the_persons_do_and_the_run_is_summed_up(
    stories: dict[str, list[Line]],
) -> None:
    """Issue 26: robot lines showed ids ('pick_red') where person lines showed names; no summary at the end."""
    for role, lines in stories.items():
        assert not any(f"'{id_}'" in line.text for line in lines for id_ in ("pick_red", "locate_blue", "rest_red")), role
        last = lines[-1]
        assert last.who == "board" and last.text.startswith("after "), (role, last)
    student = stories["student"][-1].text
    assert "6 of 6 subtasks done (robot 6); the task is finished" in student
    peer = stories["peer"][-1].text
    assert "(alice 1, robot " in peer
