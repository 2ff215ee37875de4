"""Household maps: the text format, its errors (with line and column), the shipped maps, the dynamics."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import MapFileError
from supportive.worlds.household import (
    DAMAGE,
    Collision,
    EpsilonGreedyNovice,
    HouseholdWorld,
    MapDistances,
    Terrain,
    load_map,
    map_names,
    parse_map,
    read_map,
)

TINY = """\
; a comment
#######
#B..C.#
#R...S#
#######
"""


def test_parse_tiny_map() -> None:
    grid = parse_map(TINY, "tiny")
    assert (grid.rows, grid.cols) == (4, 7)
    assert grid.bins == ((1, 1),)
    assert grid.stairs == ((2, 5),)
    assert grid.tables == ((1, 4),) and grid.candles == frozenset({(1, 4)})
    assert grid.caregiver_start == (2, 1)
    assert (
        grid.at((0, 0)) is Terrain.WALL
        and grid.at((-1, 3)) is Terrain.WALL
        and grid.at((1, 2)) is Terrain.FLOOR
    )
    assert len(grid.play_area) == 6  # (1, 5) is walled in by the candle table and the stairs
    assert parse_map(grid.render(), "tiny") == grid


@pytest.mark.parametrize(
    ("text", "where", "words"),
    [
        ("####\n#BX#\n####\n", ":2:3:", "unknown map character 'X'"),
        ("; note\n####\n#B.#\n###\n", ":4:4:", "row is 3 cells wide"),
        ("####\n#..#\n####\n", "", "no toy bin"),
        ("#####\n#B#.#\n#####\n", ":2:2:", "toy bin cannot be reached"),
        ("######\n#B.#B#\n#..###\n######\n", ":2:5:", "toy bin cannot be reached"),
        ("#####\n#BR.#\n#.R.#\n#####\n", ":3:3:", "a second caregiver start"),
        ("; only a comment\n", "", "the map is empty"),
    ],
)
def test_map_errors_name_line_and_column(tmp_path: Path, text: str, where: str, words: str) -> None:
    path = tmp_path / "bad.map"
    path.write_text(text)
    with pytest.raises(MapFileError) as caught:
        read_map(path)
    message = str(caught.value)
    assert message.startswith(f"{path}{where}") and words in message


def test_missing_file_and_unknown_name(tmp_path: Path) -> None:
    with pytest.raises(MapFileError, match="no such file"):
        read_map(tmp_path / "none.map")
    with pytest.raises(MapFileError, match=r"^castle: no shipped map of this name"):
        load_map("castle")


@pytest.mark.parametrize("name", map_names())
def test_shipped_maps_are_usable(name: str) -> None:
    grid = load_map(name)
    distances = MapDistances(grid)
    assert grid.bins and grid.stairs and grid.candles
    for b in grid.bins:  # every bin is reachable from every play-area cell
        assert int(distances.to_bin[b].max()) < 10_000
    assert grid.caregiver_start in grid.play_area


def _hit(collision: Collision | None) -> Collision:
    assert collision is not None
    return collision


def test_novice_collisions_and_damage() -> None:
    grid = parse_map(TINY)
    world = HouseholdWorld.start(grid, novice=(2, 4), caregiver=(2, 1))
    assert world.move_novice("east") == world.collision_at((2, 5))
    assert _hit(world.collision_at((2, 5))).damage == DAMAGE["stairs"] == 5
    assert world.novice == (2, 4)  # a collision leaves the novice in place
    world.novice = (1, 3)
    assert _hit(world.move_novice("east")).kind == "candle"
    world.candles.clear()
    assert _hit(world.move_novice("east")).kind == "table"
    assert _hit(world.move_novice("north")).kind == "wall"
    world.novice = (1, 2)
    assert _hit(world.move_novice("west")).damage == 0  # the bin
    with pytest.raises(ValueError, match="unknown novice action"):
        world.move_novice("up")


def test_caregiver_actions_move_a_candle_and_block_stairs() -> None:
    grid = parse_map(TINY)
    world = HouseholdWorld.start(grid, novice=(2, 1), caregiver=(1, 3))
    assert world.act_caregiver("get") and world.carrying and not world.candles
    assert not world.act_caregiver("get")  # hands full
    assert world.act_caregiver("place") and world.candles == {(1, 4)} and not world.carrying
    for move in ("south", "east", "east"):
        assert world.act_caregiver(move)
    assert world.blocked_stairs() == (2, 5)
    world.novice = (2, 4)
    assert world.move_novice("east").kind == "caregiver"
    assert not world.act_caregiver("east")  # a wall
    with pytest.raises(ValueError, match="unknown caregiver action"):
        world.act_caregiver("fly")


@given(st.floats(0.0, 1.0), st.integers(0, 2**32 - 1))
def test_novice_moves_stay_in_the_play_area(epsilon: float, seed: int) -> None:
    grid = load_map("playroom")
    distances = MapDistances(grid)
    novice = EpsilonGreedyNovice(distances, epsilon, seed)
    world = HouseholdWorld.start(grid, novice.start_cell())
    for _ in range(50):
        world.move_novice(novice.act(world.novice))
        assert world.novice in distances.novice.index


def test_greedy_novice_walks_a_shortest_path_to_its_bin() -> None:
    grid = load_map("house")
    distances = MapDistances(grid)
    novice = EpsilonGreedyNovice(distances, 0.0, seed=4)
    cell = novice.start_cell()
    goal = novice.goal
    steps = int(distances.to_bin[goal][distances.novice.index[cell]])
    world = HouseholdWorld.start(grid, cell)
    for _ in range(steps):
        assert world.move_novice(novice.act(world.novice)) is None
    assert novice.arrived(world.novice) and novice.goal == goal
