"""The caregiver's choices in hand-built situations, its safety rule, and whole episodes."""

from __future__ import annotations

import pytest

from supportive.safety import ActionPriors, Caregiver, run_episode
from supportive.worlds.household import HouseholdWorld, MapDistances, load_map, map_names, parse_map


def _carer(text: str, **options: float) -> tuple[Caregiver, MapDistances]:
    distances = MapDistances(parse_map(text))
    return Caregiver(distances, ActionPriors.from_experts(distances, seed=0), seed=0, **options), distances  # type: ignore[arg-type]


def _wander(carer: Caregiver, moves: int = 30) -> None:
    """The novice has been bumping into the north wall (row 1 of every map here): not what an expert does."""
    for _ in range(moves):
        carer.observe((1, 3), "north")


def _turns(carer: Caregiver, world: HouseholdWorld, turns: int) -> None:
    for _ in range(turns):
        for action in carer.decide(world).actions:
            world.act_caregiver(action)


ROOM = """\
############
#B.........#
#..........#
#.C.......T#
#..........#
#R........B#
############
"""


def test_a_candle_near_a_wandering_novice_is_moved_away() -> None:
    carer, distances = _carer(ROOM)
    world = HouseholdWorld.start(distances.grid, novice=(2, 3), caregiver=(5, 1))
    _wander(carer)
    decision = carer.decide(world)
    assert decision.p_safe < 0.05
    assert decision.intervention is not None and decision.intervention.kind == "move-candle"
    assert (decision.intervention.target, decision.intervention.destination) == ((3, 2), (3, 10))
    assert decision.expected_damage[(3, 2)] > decision.expected_damage[(3, 10)]
    _turns(carer, world, 12)
    assert world.candles == {(3, 10)} and not world.carrying


def test_a_safe_novice_is_left_alone() -> None:
    carer, distances = _carer(ROOM)
    world = HouseholdWorld.start(distances.grid, novice=(2, 3), caregiver=(5, 1))
    for _ in range(30):  # walking the experts' way
        carer.observe((1, 3), "west")
    decision = carer.decide(world)
    assert decision.p_safe > 0.95 and decision.intervention is None and decision.actions == ("wait",) * 3


HALL = """\
###########
#B.......S#
#.........#
#R........#
###########
"""


def test_a_stairwell_in_the_novices_path_is_blocked() -> None:
    carer, distances = _carer(HALL)
    world = HouseholdWorld.start(distances.grid, novice=(1, 6), caregiver=(3, 1))
    _wander(carer)
    decision = carer.decide(world)
    assert decision.intervention is not None and decision.intervention.kind == "block"
    assert decision.intervention.target == (1, 9)
    assert len(decision.actions) == 3 and "wait" not in decision.actions
    _turns(carer, world, 4)
    assert world.blocked_stairs() == (1, 9)
    assert carer.decide(world).actions == ("wait", "wait", "wait")  # it stays there


CUT = """\
##########
#S...#..B#
#....R...#
#....#...#
##########
"""


def test_it_never_cuts_the_novice_off_from_every_bin() -> None:
    carer, distances = _carer(CUT)
    # the novice is in the west room; the only way to the bin is the doorway (2, 5), where the robot stands
    world = HouseholdWorld.start(distances.grid, novice=(2, 2), caregiver=(2, 6))
    _wander(carer)
    for _ in range(10):
        for action in carer.decide(world).actions:
            world.act_caregiver(action)
            assert world.caregiver != (2, 5)  # stepping into the doorway would cut the novice off
    assert world.caregiver in {(1, 6), (2, 6), (3, 6), (1, 7), (2, 7), (3, 7), (1, 8), (2, 8), (3, 8)}


def test_options_and_errors() -> None:
    carer, distances = _carer(ROOM)
    with pytest.raises(ValueError, match="no caregiver"):
        carer.decide(HouseholdWorld.start(distances.grid, novice=(2, 3)))
    with pytest.raises(ValueError):
        Caregiver(distances, ActionPriors.from_experts(distances), actions_per_step=0)


@pytest.mark.parametrize("name", map_names())
def test_episodes_are_deterministic_and_measured(name: str) -> None:
    grid = load_map(name)
    a = run_episode(grid, 0.5, seed=11, record=True, steps=60)
    b = run_episode(grid, 0.5, seed=11, record=True, steps=60)
    assert a == b and a.frames == b.frames and len(a.frames) == 60
    assert [f.decision.actions for f in a.frames] == [f.decision.actions for f in b.frames]  # type: ignore[union-attr]
    assert a.damage == a.frames[-1].damage == sum(
        f.collision.damage for f in a.frames if f.collision is not None
    )
    assert 1 <= a.cells_explored <= 61
    if not a.reached_threshold:
        assert a.steps == 60
    without = run_episode(grid, 0.5, caregiver=False, seed=11, steps=60, record=True)
    assert without.frames[0].novice == a.frames[0].novice or without.frames[0].move == a.frames[0].move


def test_the_caregiver_lowers_a_random_novices_damage() -> None:
    grid = load_map("house")
    without = sum(run_episode(grid, 1.0, caregiver=False, seed=s).damage for s in range(8))
    with_ = sum(run_episode(grid, 1.0, caregiver=True, seed=s).damage for s in range(8))
    assert with_ < 0.6 * without
