"""The household as Gymnasium and PettingZoo environments: the libraries' API checkers, seeding, and the
dynamics seen through the environments (falls, termination, the caregiver's moves and candles)."""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from typing import Any

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env
from pettingzoo.test import parallel_api_test, parallel_seed_test

from supportive.envs.household.encoding import CODE_CHARS, MAX_CODE, CellCode, encode, render_codes
from supportive.envs.household.gym_env import ENV_ID, NoviceEnv, register_envs
from supportive.envs.household.parallel_env import HouseholdParallelEnv, parallel_env
from supportive.worlds.household import (
    CAREGIVER_ACTIONS,
    DAMAGE,
    NOVICE_ACTIONS,
    load_map,
    map_names,
    parse_map,
)

NORTH, EAST, SOUTH, WEST = range(4)
C = {name: CAREGIVER_ACTIONS.index(name) for name in CAREGIVER_ACTIONS}

CORRIDOR = """\
#######
#B...S#
#######
"""

WORKSHOP = """\
########
#B....T#
#R...C.#
#......#
########
"""

LANDING = """\
######
#B..S#
#R...#
######
"""


@pytest.fixture
def strict_warnings() -> Iterator[None]:
    """Any warning (the API checkers report problems as warnings) fails the test."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        yield


# -- the libraries' own checkers ---------------------------------------------------------------------------


@pytest.mark.usefixtures("strict_warnings")
@pytest.mark.parametrize("caregiver", [False, True], ids=["alone", "caregiver"])
@pytest.mark.parametrize("name", map_names())
def test_gymnasium_check_env(name: str, caregiver: bool) -> None:
    # Made through the registry so the checker also has a spec: it then re-makes the env for every render
    # mode and checks close() too.
    env = gymnasium.make(ENV_ID, grid=name, caregiver=caregiver, render_mode="ansi")
    assert isinstance(env.unwrapped, NoviceEnv)
    check_env(env.unwrapped)
    env.close()


@pytest.mark.usefixtures("strict_warnings")
@pytest.mark.parametrize("name", map_names())
def test_gymnasium_check_env_direct(name: str) -> None:
    check_env(NoviceEnv(name, caregiver=True).unwrapped, skip_render_check=True)


@pytest.mark.usefixtures("strict_warnings")
@pytest.mark.parametrize("name", map_names())
def test_pettingzoo_parallel_api(name: str) -> None:
    env = HouseholdParallelEnv(name)
    parallel_api_test(env, num_cycles=300)
    parallel_seed_test(lambda: HouseholdParallelEnv(name), num_cycles=300)


@pytest.mark.parametrize("name", map_names())
def test_parallel_episode_ends_and_empties_agents(name: str) -> None:
    env = parallel_env(grid=name, max_steps=50)
    env.reset(seed=1)
    assert env.agents == ["novice", "caregiver"]
    steps, done = 0, False
    while env.agents:
        actions = {agent: env.action_space(agent).sample() for agent in env.agents}
        _, rewards, terminations, truncations, infos = env.step(actions)
        steps += 1
        assert (
            rewards["novice"] == rewards["caregiver"] == -float(DAMAGE.get(infos["novice"]["collision"], 0))
        )
        done = terminations["novice"] or truncations["novice"]
        assert terminations["novice"] == terminations["caregiver"] == (infos["novice"]["damage"] >= 15)
    assert done and steps <= 50
    assert (steps == 50) or infos["novice"]["damage"] >= 15
    with pytest.raises(RuntimeError, match="reset"):
        env.step({"novice": 0, "caregiver": [4, 4, 4]})


# -- Gymnasium: registration, seeding, dynamics ------------------------------------------------------------


def test_make_by_id_and_register_twice() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        register_envs()  # already registered at import: a no-op, not an "overriding" warning
    env = gymnasium.make(ENV_ID)
    assert isinstance(env.unwrapped, NoviceEnv) and env.unwrapped.grid.name == "house"
    obs, info = env.reset(seed=3)
    assert env.observation_space.contains(obs)
    assert env.action_space == gymnasium.spaces.Discrete(4)
    assert {k: info[k] for k in ("step", "damage", "collision", "cells_explored")} == {
        "step": 0,
        "damage": 0,
        "collision": None,
        "cells_explored": 1,
    }
    obs, reward, *_, info = env.step(env.action_space.sample())
    assert env.observation_space.contains(obs) and float(reward) <= 0 and info["step"] == 1
    made = gymnasium.make(ENV_ID, grid="playroom", caregiver=True, max_steps=7)
    assert isinstance(made.unwrapped, NoviceEnv) and made.unwrapped.caregiver is not None
    assert made.unwrapped.observation_space.shape == (load_map("playroom").rows, load_map("playroom").cols)


def _play(env: NoviceEnv, seed: int, actions: list[int]) -> list[tuple[Any, ...]]:
    obs, info = env.reset(seed=seed)
    trace: list[tuple[Any, ...]] = [(obs.tolist(), info)]
    for action in actions:
        obs, reward, terminated, truncated, info = env.step(action)
        trace.append((obs.tolist(), reward, terminated, truncated, info))
        if terminated or truncated:
            break
    return trace


@pytest.mark.parametrize("caregiver", [False, True], ids=["alone", "caregiver"])
def test_same_seed_same_episode(caregiver: bool) -> None:
    actions = [int(a) for a in np.random.default_rng(5).integers(4, size=120)]
    first = _play(NoviceEnv("house", caregiver=caregiver), 11, actions)
    again = _play(NoviceEnv("house", caregiver=caregiver), 11, actions)
    assert first == again
    assert len(first) > 20
    assert any(step[1] < 0 for step in first[1:])  # some collisions happened: not a trivially empty trace
    starts = {NoviceEnv("house", caregiver=caregiver).reset(seed=s)[1]["novice"] for s in range(10)}
    assert len(starts) > 1  # the seed does choose the start


def test_caregiver_does_not_change_the_novice_start() -> None:
    for seed in range(5):
        alone = NoviceEnv("house").reset(seed=seed)[1]["novice"]
        helped = NoviceEnv("house", caregiver=True).reset(seed=seed)[1]["novice"]
        assert alone == helped


def test_reset_without_seed_continues_the_generator() -> None:
    env = NoviceEnv("house")
    env.reset(seed=0)
    starts = [env.reset()[1]["novice"] for _ in range(8)]
    other = NoviceEnv("house")
    other.reset(seed=0)
    assert starts == [other.reset()[1]["novice"] for _ in range(8)]
    assert len(set(starts)) > 1


def test_fall_down_the_stairs_costs_five_and_three_falls_terminate() -> None:
    env = NoviceEnv(parse_map(CORRIDOR, "corridor"), render_mode="ansi")
    obs, info = env.reset(seed=0, options={"novice": (1, 2)})
    assert obs[1, 2] == CellCode.NOVICE and obs[1, 5] == CellCode.STAIRS
    rewards = []
    for action in (EAST, EAST, EAST):
        obs, reward, terminated, truncated, info = env.step(action)
        rewards.append(reward)
    assert rewards == [0.0, 0.0, -5.0]
    assert info["collision"] == "stairs" and info["damage"] == 5 and not terminated
    assert obs[1, 4] == CellCode.NOVICE  # a collision leaves the novice where it was
    assert info["cells_explored"] == 3
    text = env.render()
    assert text is not None
    assert text.splitlines()[:3] == ["#######", "#B..NS#", "#######"]
    assert "damage 5/15" in text.splitlines()[3] and "stairs" in text.splitlines()[3]
    obs, reward, terminated, truncated, info = env.step(NORTH)
    assert (reward, info["collision"], info["damage"]) == (0.0, "wall", 5)
    env.step(EAST)
    obs, reward, terminated, truncated, info = env.step(EAST)
    assert reward == -5.0 and info["damage"] == 15 and terminated and not truncated


def test_truncated_at_max_steps() -> None:
    env = NoviceEnv(parse_map(CORRIDOR), max_steps=3)
    env.reset(seed=0, options={"novice": (1, 2)})
    flags = [env.step(WEST)[2:4] for _ in range(3)]  # bumping the bin: harmless
    assert flags == [(False, False), (False, False), (False, True)]


def test_built_in_caregiver_acts_and_reports_p_safe() -> None:
    env = NoviceEnv("playroom", caregiver=True)
    obs, info = env.reset(seed=2)
    assert 0.0 <= info["p_safe"] <= 1.0 and info["caregiver_actions"] == ()
    cells = {info["caregiver"]}
    for _ in range(40):
        obs, *_, info = env.step(env.action_space.sample())
        assert len(info["caregiver_actions"]) == 3
        assert set(info["caregiver_actions"]) <= set(CAREGIVER_ACTIONS)
        assert obs[info["caregiver"]] == CellCode.CAREGIVER
        cells.add(info["caregiver"])
    assert len(cells) > 1  # the robot really moved around the house
    # a novice hurling itself at walls is not safe
    env.reset(seed=2, options={"novice": (2, 1)})
    p_safe = [env.step(WEST)[4]["p_safe"] for _ in range(10)]
    assert p_safe[-1] < p_safe[0]


def test_novice_env_rejects_bad_input() -> None:
    with pytest.raises(ValueError, match="render_mode"):
        NoviceEnv("playroom", render_mode="human")
    with pytest.raises(ValueError, match="max_steps"):
        NoviceEnv("playroom", max_steps=0)
    env = NoviceEnv("playroom")
    with pytest.raises(RuntimeError, match="reset"):
        env.step(0)
    env.reset(seed=0)
    with pytest.raises(ValueError, match="novice action"):
        env.step(4)
    with pytest.raises(ValueError, match="no caregiver"):
        env.reset(options={"caregiver": (6, 1)})
    with pytest.raises(ValueError, match="play area"):
        env.reset(options={"novice": (0, 0)})


# -- PettingZoo: the caregiver's actions -------------------------------------------------------------------


def test_parallel_caregiver_moves_and_carries_a_candle() -> None:
    env = HouseholdParallelEnv(parse_map(WORKSHOP, "workshop"), render_mode="ansi")
    observations, infos = env.reset(seed=0, options={"novice": (3, 1)})
    start = observations["caregiver"]
    assert (
        start[2, 1] == CellCode.CAREGIVER and start[2, 5] == CellCode.CANDLE and start[1, 6] == CellCode.TABLE
    )
    assert env.observation_space("novice").contains(start)

    def turn(*names: str, novice: int = SOUTH) -> tuple[Any, ...]:
        return env.step({"novice": novice, "caregiver": np.array([C[n] for n in names])})

    # nothing to get or place, a wall to the west, the novice to the south: nothing happens
    obs, rewards, _, _, infos = turn("get", "place", "west", novice=SOUTH)
    obs, rewards, _, _, infos = turn("south", "wait", "wait", novice=NORTH)  # the novice bumps the robot
    assert infos["caregiver"]["applied"] == (False, False, False)
    assert infos["novice"]["collision"] == "caregiver" and rewards == {"novice": 0.0, "caregiver": 0.0}
    assert obs["novice"][2, 1] == CellCode.CAREGIVER

    obs, *_, infos = turn("east", "east", "east")
    assert infos["caregiver"]["applied"] == (True, True, True)
    assert obs["caregiver"][2, 4] == CellCode.CAREGIVER and obs["caregiver"][2, 1] == CellCode.FLOOR

    obs, *_, infos = turn("get", "north", "east")
    assert infos["caregiver"]["applied"] == (True, True, True) and infos["caregiver"]["carrying"]
    assert obs["novice"][2, 5] == CellCode.TABLE and obs["novice"][1, 5] == CellCode.CAREGIVER
    assert not (obs["novice"] == CellCode.CANDLE).any()  # the candle is in the robot's hands
    assert "carries a candle" in (env.render() or "")

    obs, *_, infos = turn("place", "get", "wait")
    assert infos["caregiver"]["applied"] == (True, True, False)  # it placed the candle, then lifted it again
    obs, *_, infos = turn("place", "wait", "wait")
    assert infos["caregiver"]["applied"] == (True, False, False) and not infos["caregiver"]["carrying"]
    assert obs["caregiver"][1, 6] == CellCode.CANDLE and obs["caregiver"][2, 5] == CellCode.TABLE
    assert (obs["novice"] == obs["caregiver"]).all() and obs["novice"] is not obs["caregiver"]


def test_parallel_caregiver_blocks_the_stairs() -> None:
    env = HouseholdParallelEnv(parse_map(LANDING, "landing"))
    env.reset(seed=0, options={"novice": (1, 2)})
    _, _, *_, infos = env.step({"novice": WEST, "caregiver": [C["east"], C["east"], C["east"]]})
    assert infos["novice"]["collision"] == "bin" and infos["caregiver"]["caregiver"] == (2, 4)
    obs, rewards, *_, infos = env.step({"novice": EAST, "caregiver": [C["north"], C["wait"], C["wait"]]})
    assert obs["novice"][1, 4] == CellCode.CAREGIVER and infos["caregiver"]["caregiver"] == (1, 4)
    assert infos["novice"]["collision"] is None and infos["novice"]["novice"] == (1, 3)
    obs, rewards, *_, infos = env.step({"novice": EAST, "caregiver": [C["wait"]] * 3})
    assert infos["novice"]["collision"] == "caregiver" and rewards["novice"] == 0.0  # no fall: it is blocked
    # the same move with the robot out of the stairwell is a fall
    env.reset(seed=0, options={"novice": (1, 3)})
    _, rewards, *_ = env.step({"novice": EAST, "caregiver": [C["wait"]] * 3})
    assert rewards == {"novice": -5.0, "caregiver": -5.0}


def test_parallel_spaces_and_bad_actions() -> None:
    env = parallel_env(grid="playroom")
    assert env.action_space("novice") == gymnasium.spaces.Discrete(len(NOVICE_ACTIONS))
    assert env.action_space("caregiver") == gymnasium.spaces.MultiDiscrete([7, 7, 7])
    assert env.metadata["name"] == "household_v0" and env.metadata["render_modes"] == ["ansi"]
    env.reset(seed=0)
    with pytest.raises(ValueError, match="takes 3 actions"):
        env.step({"novice": 0, "caregiver": [0, 0]})
    with pytest.raises(ValueError, match="caregiver action"):
        env.step({"novice": 0, "caregiver": [0, 0, 7]})
    with pytest.raises(ValueError, match="no action for caregiver"):
        env.step({"novice": 0})
    assert env.episode.steps == 0  # a rejected step changes nothing


# -- the shared encoding -----------------------------------------------------------------------------------


@pytest.mark.parametrize("name", map_names())
def test_encoding_round_trips_to_the_map_text(name: str) -> None:
    grid = load_map(name)
    env = HouseholdParallelEnv(grid)
    observations, infos = env.reset(seed=4)
    codes = observations["novice"]
    assert codes.dtype == np.int8 and codes.min() >= 0 and codes.max() <= MAX_CODE
    assert (codes == CellCode.NOVICE).sum() == 1 and (codes == CellCode.CAREGIVER).sum() == 1
    lines = render_codes(codes).splitlines()
    expected = grid.render().replace("R", ".").splitlines()
    for (r, c), char in ((infos["novice"]["novice"], "N"), (infos["novice"]["caregiver"], "R")):
        expected[r] = expected[r][:c] + char + expected[r][c + 1 :]
    assert lines == expected
    assert set(CODE_CHARS) == set(CellCode)
    assert encode(env.episode.world).tolist() == codes.tolist()
