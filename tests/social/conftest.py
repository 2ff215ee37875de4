"""Recorded hand paths on the workbench (metres, 30 Hz) and the construction task's subtasks."""

from __future__ import annotations

from collections.abc import Callable

import pytest

from supportive import examples
from supportive.social import Candidate, SocialForce
from supportive.tasks.spec import Action

HZ = 30.0
HUMAN_SIDE = (0.9, 0.02)  # a hand resting at the front edge of the table, where people stand


class Hand:
    """A tracked hand: it starts at rest at the front edge, moves in straight lines and holds still, one
    sample every 1/30 s into its own :class:`SocialForce`; its clock runs on from move to move."""

    def __init__(self, force: SocialForce) -> None:
        self.force = force
        self.t = 0.0
        self.at = HUMAN_SIDE
        force.update(self.t, self.at)

    def move(self, to: tuple[float, float], seconds: float = 0.6) -> Hand:
        """Move in a straight line to ``to`` in ``seconds``."""
        steps = round(seconds * HZ)
        (x0, y0), (x1, y1) = self.at, to
        for i in range(1, steps + 1):
            f = i / steps
            self.force.update(self.t + i / HZ, (x0 + (x1 - x0) * f, y0 + (y1 - y0) * f))
        self.t += steps / HZ
        self.at = to
        return self

    def hold(self, seconds: float) -> Hand:
        """Stay still for ``seconds``."""
        return self.move(self.at, seconds)


@pytest.fixture
def hand() -> Callable[[], Hand]:
    """Make a new tracked hand (min_radius 5 cm, the default 0.75 s window)."""
    return lambda: Hand(SocialForce(min_radius=0.05))


@pytest.fixture
def workbench() -> dict[str, Action]:
    """The actions of examples/workbench-blocks.yaml, by id."""
    return {a.id: a for a in examples.load("workbench-blocks").actions}


CandidateMaker = Callable[..., list[Candidate]]


@pytest.fixture
def candidates(workbench: dict[str, Action]) -> CandidateMaker:
    """``candidates("locate_blue", "pick_red", current="locate_blue", claimed=("pick_red",))``."""

    def make(*ids: str, current: str | None = None, claimed: tuple[str, ...] = ()) -> list[Candidate]:
        return [Candidate.from_action(workbench[i], current=i == current, claimed=i in claimed) for i in ids]

    return make
