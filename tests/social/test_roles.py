"""Role policies on recorded hand paths over the construction task (§3.4.5): student, peer; tie-breaking."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from supportive.errors import SocialError
from supportive.social import Candidate, ForceField, PeerPolicy, RoleAction, SocialForce, StudentPolicy
from supportive.tasks.spec import Action, Keyframe

Hands = Callable[[], Any]
Make = Callable[..., list[Candidate]]

BLUE, RED, NEXT_TO_GREEN = (0.55, 0.30), (1.35, 0.30), (0.84, 0.33)  # the blocks; where blue goes
FIRST = ("locate_blue", "pick_red")  # what the task tree offers at the start: each branch's first action


# ----------------------------------------------------------------------------------------- student
def test_student_waits_without_a_gesture(hand: Hands, candidates: Make) -> None:
    student = StudentPolicy(min_force=0.2, seed=0)
    assert student.decide(candidates(*FIRST), SocialForce()).action is RoleAction.WAIT  # no one tracked
    resting = hand().hold(1.0)  # the instructor's hand rests at the front edge
    decision = student.decide(candidates(*FIRST), resting.force)
    assert decision.action is RoleAction.WAIT and decision.subtask is None
    assert decision.readings == (("locate_blue", 0.0), ("pick_red", 0.0))
    assert "below 0.20" in decision.reason


def test_student_follows_a_gesture_towards_the_blue_block(hand: Hands, candidates: Make) -> None:
    instructor = hand().hold(0.3).move(BLUE).hold(0.3)  # reaches for the blue block and points at it
    decision = StudentPolicy(min_force=0.2, seed=0).decide(candidates(*FIRST), instructor.force)
    assert decision.action is RoleAction.START and decision.subtask == "locate_blue"
    assert decision.reading("locate_blue") >= 0.2 and decision.reading("pick_red") == 0.0
    assert "locate_blue" in decision.reason


def test_student_follows_a_gesture_towards_the_red_block(hand: Hands, candidates: Make) -> None:
    instructor = hand().move(RED).hold(0.2)
    decision = StudentPolicy(min_force=0.2, seed=0).decide(candidates(*FIRST), instructor.force)
    assert (decision.action, decision.subtask) == (RoleAction.START, "pick_red")


def test_student_takes_the_thesis_sequence_from_gestures(hand: Hands, candidates: Make) -> None:
    """Blue block → locate; next to the green block → push; red block → pick up (§3.4.5.1)."""
    student = StudentPolicy(min_force=0.2, seed=0)
    instructor = hand().move(BLUE).hold(0.3)
    assert student.decide(candidates(*FIRST), instructor.force).subtask == "locate_blue"
    instructor.move(NEXT_TO_GREEN).hold(0.3)  # then where the blue block should go
    after_locate = candidates("push_blue", "pick_red")
    decision = student.decide(after_locate, instructor.force)
    assert (decision.action, decision.subtask) == (RoleAction.START, "push_blue")
    assert decision.reading("pick_red") == 0.0
    instructor.move(RED).hold(0.3)
    assert student.decide(candidates("rest_blue", "pick_red"), instructor.force).subtask == "pick_red"


def test_student_finishes_what_it_started_and_idles_when_nothing_is_free(hand: Hands, candidates: Make) -> None:
    student = StudentPolicy(min_force=0.2, seed=0)
    instructor = hand().move(RED).hold(0.3)  # gesturing at the red block while the robot locates the blue one
    busy = student.decide(candidates(*FIRST, current="locate_blue"), instructor.force)
    assert (busy.action, busy.subtask) == (RoleAction.CONTINUE, "locate_blue")
    taken = student.decide(candidates(*FIRST, claimed=FIRST), instructor.force)
    assert (taken.action, taken.subtask) == (RoleAction.IDLE, None)


def test_student_ignores_cues_at_claimed_subtasks(hand: Hands, candidates: Make) -> None:
    instructor = hand().move(RED).hold(0.3)
    decision = StudentPolicy(min_force=0.2, seed=0).decide(candidates(*FIRST, claimed=("pick_red",)), instructor.force)
    assert decision.action is RoleAction.WAIT  # the only cue is at a subtask someone else owns


# ----------------------------------------------------------------------------------------- peer
def test_peer_starts_with_the_least_conflicting_subtask(hand: Hands, candidates: Make) -> None:
    person = hand().move(RED)  # the person reaches for the red block
    decision = PeerPolicy(switch_margin=0.2, halt_below=-0.5, seed=0).decide(candidates(*FIRST), person.force)
    assert (decision.action, decision.subtask) == (RoleAction.START, "locate_blue")


def test_peer_yields_its_subtask_when_a_hand_moves_into_it(hand: Hands, candidates: Make) -> None:
    peer = PeerPolicy(switch_margin=0.2, halt_below=-0.5, seed=0)
    person = hand().hold(0.5)
    mine = candidates(*FIRST, current="locate_blue")
    assert peer.decide(mine, person.force).action is RoleAction.CONTINUE  # nobody near: carry on
    person.move(BLUE).hold(0.3)  # the human's hand moves into the region of the robot's current subtask
    decision = peer.decide(mine, person.force)
    assert (decision.action, decision.subtask) == (RoleAction.SWITCH, "pick_red")
    assert decision.reading("locate_blue") > 0.2 + decision.reading("pick_red")
    assert "switching from 'locate_blue'" in decision.reason


def test_peer_yields_before_the_hand_arrives(hand: Hands, candidates: Make) -> None:
    """The ellipse leads the hand: a reach still 13 cm short of the blue block already reads there."""
    start = (0.9, 0.02)
    on_the_way = (start[0] + 0.7 * (BLUE[0] - start[0]), start[1] + 0.7 * (BLUE[1] - start[1]))
    person = hand().move(on_the_way, seconds=0.42)
    assert math.dist(on_the_way, BLUE) > 0.13
    decision = PeerPolicy(0.2, -0.5, seed=0).decide(candidates(*FIRST, current="locate_blue"), person.force)
    assert (decision.action, decision.subtask) == (RoleAction.SWITCH, "pick_red")
    assert decision.reading("locate_blue") > 0.8


def test_peer_keeps_its_subtask_under_a_small_intrusion(hand: Hands, candidates: Make) -> None:
    person = hand().move((0.6, 0.1), seconds=0.4).hold(0.5)  # a hand near the blue block's front, not at it
    mine = candidates(*FIRST, current="locate_blue")
    low = PeerPolicy(switch_margin=0.0, halt_below=-0.5).decide(mine, person.force)
    assert low.action is RoleAction.CONTINUE and low.reading("locate_blue") == 0.0
    person.move((0.53, 0.33), seconds=0.3).hold(0.2)
    reading = PeerPolicy(0.0, -0.5).decide(mine, person.force).reading("locate_blue")
    assert 0 < reading < 1
    margin_above = PeerPolicy(switch_margin=min(1.0, reading + 0.01), halt_below=-0.5)
    assert margin_above.decide(mine, person.force).action is RoleAction.CONTINUE
    margin_below = PeerPolicy(switch_margin=max(0.0, reading - 0.01), halt_below=-0.5)
    assert margin_below.decide(mine, person.force).action is RoleAction.SWITCH


def test_peer_halts_when_everything_conflicts_and_resumes_later(hand: Hands, candidates: Make) -> None:
    peer = PeerPolicy(switch_margin=0.2, halt_below=-0.5, seed=0)
    person = hand().hold(0.3)
    mine = candidates(*FIRST, current="locate_blue", claimed=("pick_red",))  # the person owns the red branch
    assert peer.decide(mine, person.force).action is RoleAction.CONTINUE
    person.move(BLUE).hold(0.5)  # … but reaches into the robot's workspace
    halted = peer.decide(mine, person.force)
    assert (halted.action, halted.subtask) == (RoleAction.HALT, "locate_blue")
    assert halted.reading("locate_blue") > 0.5
    person.move(RED, seconds=0.5).hold(0.5)  # back to the red block
    resumed = peer.decide(mine, person.force)
    assert (resumed.action, resumed.subtask) == (RoleAction.CONTINUE, "locate_blue")
    assert resumed.reading("locate_blue") < 0.5


def test_peer_idles_when_everything_is_claimed(candidates: Make) -> None:
    decision = PeerPolicy(0.2, -0.5).decide(candidates(*FIRST, claimed=FIRST), SocialForce())
    assert decision.action is RoleAction.IDLE


def test_peer_reads_the_other_agents_in_a_field(hand: Hands, candidates: Make) -> None:
    people = ForceField(min_radius=0.05)
    alice, bob = hand(), hand()
    alice.move(BLUE).hold(0.3)
    bob.move(RED).hold(0.3)
    for who, h in (("alice", alice), ("bob", bob)):
        for t, point in zip(h.force.times, h.force.samples, strict=True):
            people.update(who, float(t), point)
    decision = PeerPolicy(0.2, -0.5, seed=0).decide(candidates(*FIRST, current="locate_blue"), people)
    assert decision.action is RoleAction.CONTINUE  # both branches are contested: no better one to switch to
    assert decision.reading("locate_blue") > 0.2 and decision.reading("pick_red") > 0.2


# ----------------------------------------------------------------------------------------- ties and seeds
def _tied() -> list[Candidate]:
    return [Candidate(f"s{i}", ((0.2 * i, 0.5),)) for i in range(5)]


class Uniform:
    """The same force everywhere: every subtask reads alike."""

    def __init__(self, value: float) -> None:
        self.value = value

    def field(self, points: Any) -> np.ndarray:
        return np.full(len(points), self.value)


@pytest.mark.parametrize(
    ("make", "force"),
    [
        (lambda seed: StudentPolicy(0.1, seed), Uniform(0.5)),
        (lambda seed: PeerPolicy(0.2, -0.5, seed), Uniform(0.5)),
        (lambda seed: PeerPolicy(0.2, -0.5, seed), SocialForce()),  # no social force measured at all
    ],
)
def test_ties_are_broken_at_random_and_the_seed_decides(make: Callable[[int], Any], force: Any) -> None:
    def run(seed: int) -> list[str | None]:
        policy = make(seed)
        return [policy.decide(_tied(), force).subtask for _ in range(40)]

    first = run(7)
    assert first == run(7)  # same seed, same choices
    assert len(set(first)) > 1  # ties really are broken at random …
    assert set(first) <= {c.id for c in _tied()}
    assert first != run(8)  # … and another seed gives another sequence
    decision = make(7).decide(_tied(), force)
    assert decision.action is RoleAction.START
    assert "chosen at random among the tied s0, s1, s2, s3, s4" in decision.reason


def test_waiting_draws_nothing_from_the_generator() -> None:
    fresh, waited = StudentPolicy(0.1, seed=7), StudentPolicy(0.1, seed=7)
    for _ in range(5):
        assert waited.decide(_tied(), Uniform(0.05)).action is RoleAction.WAIT  # tied, but all too weak
    assert [waited.decide(_tied(), Uniform(0.5)).subtask for _ in range(10)] == [
        fresh.decide(_tied(), Uniform(0.5)).subtask for _ in range(10)
    ]


def test_a_clear_winner_is_not_random() -> None:
    force = SocialForce(min_radius=0.1)
    force.update(0.0, (0.4, 0.5))
    choices = {StudentPolicy(0.1, seed).decide(_tied(), force).subtask for seed in range(20)}
    assert choices == {"s2"}


# ----------------------------------------------------------------------------------------- bad input
def test_candidates_and_parameters_are_checked(workbench: dict[str, Action]) -> None:
    with pytest.raises(SocialError, match="cannot be claimed by another agent and be the robot's own"):
        Candidate("a", claimed=True, current=True)
    with pytest.raises(SocialError, match="keyframe 2 of 'a' must be finite"):
        Candidate("a", ((0.0, 0.0), (float("nan"), 0.0)))
    with pytest.raises(SocialError, match="unique, repeated: a"):
        StudentPolicy(0.2).decide([Candidate("a"), Candidate("a")], SocialForce())
    with pytest.raises(SocialError, match="only one candidate can be current"):
        PeerPolicy(0.2, -0.5).decide([Candidate("a", current=True), Candidate("b", current=True)], SocialForce())
    with pytest.raises(SocialError, match=r"min_force must be a number in \(0, 1\]"):
        StudentPolicy(0.0)
    with pytest.raises(SocialError, match=r"switch_margin must be a number in \[0, 1\]"):
        PeerPolicy(-0.1, -0.5)
    with pytest.raises(SocialError, match=r"halt_below must be a number in \[-1, 0\]"):
        PeerPolicy(0.2, 0.5)
    with pytest.raises(SocialError, match="was not a candidate"):
        StudentPolicy(0.2).decide([Candidate("a")], SocialForce()).reading("b")
    assert Candidate.from_action(Action("x", keyframes=(Keyframe(1, 2, goal=True),))).keyframes == ((1.0, 2.0),)
    assert Candidate.from_action(workbench["rest_red"], claimed=True).claimed


def test_a_subtask_without_keyframes_reads_nothing(hand: Hands) -> None:
    person = hand().hold(0.5)
    decision = PeerPolicy(0.2, -0.5).decide([Candidate("unknown_place")], person.force)
    assert decision.readings == (("unknown_place", 0.0),) and decision.action is RoleAction.START
