"""The household world as a PettingZoo parallel environment: the novice and the caregiver both learn (§3.5).

Each step both agents act at once. The caregiver's action is three indices into
:data:`~supportive.worlds.household.world.CAREGIVER_ACTIONS` (north, east, south, west, wait, get, place: it
moves three times as fast as the novice, §3.5.5.3), applied in order; then the novice's move (an index into
north, east, south, west). Both see the grid of cell codes of :mod:`supportive.envs.household.encoding`, and
both are rewarded minus the damage of the novice's collision (the game is cooperative). The episode
terminates for both when the damage reaches ``threshold`` and is truncated after ``max_steps`` steps; the
``agents`` list is then empty.

>>> env = parallel_env(grid="playroom")
>>> observations, infos = env.reset(seed=0, options={"novice": (1, 2)})
>>> actions = {"novice": 3, "caregiver": [1, 1, 4]}  # novice west (to the stairwell); caregiver east, east, wait
>>> observations, rewards, terminations, truncations, infos = env.step(actions)
>>> rewards, infos["caregiver"]["caregiver"], infos["caregiver"]["applied"]
({'novice': -5.0, 'caregiver': -5.0}, (6, 3), (True, True, False))
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from supportive.envs.household.encoding import (
    EpisodeHost,
    EpisodeState,
    action_name,
    caregiver_cell,
    novice_cell,
    observation_space,
)
from supportive.errors import MissingExtraError, ResetNeededError, WorldError
from supportive.worlds.household.grid_map import GridMap
from supportive.worlds.household.world import CAREGIVER_ACTIONS, NOVICE_ACTIONS, HouseholdWorld

try:
    from gymnasium import spaces
    from gymnasium.utils import seeding
    from pettingzoo import ParallelEnv
except ImportError:  # pragma: no cover - the ``envs`` extra is missing
    raise MissingExtraError("the household PettingZoo environment", "pettingzoo", "envs") from None

__all__ = ["AGENTS", "CAREGIVER_TURN", "HouseholdParallelEnv", "parallel_env"]

AGENTS: tuple[str, str] = ("novice", "caregiver")
"""The agents, in the order of ``possible_agents``."""

CAREGIVER_TURN = 3
"""Caregiver actions per novice step (§3.5.5.3)."""

_Observation = NDArray[np.int8]
_Action = Any


class HouseholdParallelEnv(EpisodeHost, ParallelEnv):  # type: ignore[misc]
    """The novice and the caregiver acting together in the household.

    Args:
        grid: The map, or a shipped map's name or a map file's path.
        max_steps: Steps before the episode is truncated.
        threshold: Total damage at which the episode terminates.
        render_mode: None, or ``"ansi"``: :meth:`render` returns the map with ``N`` (novice), ``R``
            (caregiver), ``C`` (candles) and a status line.

    ``reset(options=...)`` accepts ``{"novice": (row, col)}`` (a play-area cell) and ``{"caregiver": (row,
    col)}`` (free floor or a stairwell) to fix the starts; otherwise the novice starts on a play-area cell
    drawn from the seeded generator and the caregiver on the map's ``R`` cell (or a drawn one). Every info
    holds ``step``, ``damage`` so far, the last ``collision`` kind (or None), ``cells_explored``,
    ``carrying`` and both agents' cells; the caregiver's also ``applied``: which of its three actions
    changed anything (a blocked move, ``wait``, or ``get`` with no candle beside it do not).

    Raises:
        WorldError: for a ``render_mode`` other than None or ``"ansi"``, or limits below 1.
        MapFileError: for an unknown map name or a bad map file.
    """

    metadata: dict[str, Any] = {  # noqa: RUF012 - PettingZoo's convention
        "name": "household_v0",
        "render_modes": ["ansi"],
        "render_fps": 4,
        "is_parallelizable": True,
    }

    def __init__(
        self,
        grid: GridMap | str = "house",
        max_steps: int = 200,
        threshold: int = 15,
        render_mode: str | None = None,
    ) -> None:
        self._host(grid, max_steps, threshold, render_mode)
        self.possible_agents: list[str] = list(AGENTS)
        self.agents: list[str] = []
        self.observation_spaces: dict[str, spaces.Space[Any]] = {
            agent: observation_space(self.grid) for agent in AGENTS
        }
        self.action_spaces: dict[str, spaces.Space[Any]] = {
            "novice": spaces.Discrete(len(NOVICE_ACTIONS)),
            "caregiver": spaces.MultiDiscrete([len(CAREGIVER_ACTIONS)] * CAREGIVER_TURN),
        }
        self.np_random, self.np_random_seed = seeding.np_random()
        self._applied: tuple[bool, ...] = ()

    def observation_space(self, agent: str) -> spaces.Space[Any]:
        """The grid-code ``Box`` (the same object on every call)."""
        return self.observation_spaces[agent]

    def action_space(self, agent: str) -> spaces.Space[Any]:
        """``Discrete(4)`` for the novice, ``MultiDiscrete([7, 7, 7])`` for the caregiver (the same object on
        every call)."""
        return self.action_spaces[agent]

    def _infos(self) -> dict[str, dict[str, Any]]:
        common = self.episode.info()
        return {"novice": dict(common), "caregiver": {**common, "applied": self._applied}}

    def _observations(self) -> dict[str, _Observation]:
        return {agent: self.episode.observation() for agent in AGENTS}

    def reset(
        self, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, _Observation], dict[str, dict[str, Any]]]:
        """Start an episode with both agents.

        Args:
            seed: Reseeds the environment's generator (the starts); None continues with it.
            options: ``"novice"`` and ``"caregiver"`` start cells (optional; other keys are ignored).

        Returns:
            Observations and infos, by agent.

        Raises:
            WorldError: for a bad start cell in ``options``.
        """
        if seed is not None:
            self.np_random, self.np_random_seed = seeding.np_random(seed)
        novice = novice_cell(self.grid, options, self.np_random)
        carer = caregiver_cell(self.grid, options, novice, self.np_random)
        self._episode = EpisodeState(HouseholdWorld.start(self.grid, novice, carer), self.limits)
        self._applied = ()
        self.agents = list(AGENTS)
        return self._observations(), self._infos()

    def step(
        self, actions: dict[str, _Action]
    ) -> tuple[
        dict[str, _Observation],
        dict[str, float],
        dict[str, bool],
        dict[str, bool],
        dict[str, dict[str, Any]],
    ]:
        """One step: the caregiver's three actions in order, then the novice's move.

        Args:
            actions: ``"novice"``: an index into north, east, south, west; ``"caregiver"``: three indices into
                :data:`~supportive.worlds.household.world.CAREGIVER_ACTIONS`.

        Returns:
            Observations, rewards (minus the collision's damage, for both), terminations (damage >=
            threshold), truncations (``max_steps`` reached) and infos, by agent.

        Raises:
            ResetNeededError: when no episode is running (before :meth:`reset` or after it ended).
            WorldError: for a missing or malformed action.
        """
        if not self.agents:
            raise ResetNeededError("no episode is running: call reset()")
        missing = [agent for agent in self.agents if agent not in actions]
        if missing:
            raise WorldError(f"no action for {', '.join(missing)}")
        move = action_name(actions["novice"], NOVICE_ACTIONS, "novice")
        turn = np.asarray(actions["caregiver"]).reshape(-1)
        if turn.shape != (CAREGIVER_TURN,):
            raise WorldError(
                f"the caregiver takes {CAREGIVER_TURN} actions per step, got {actions['caregiver']!r}"
            )
        names = [action_name(index, CAREGIVER_ACTIONS, "caregiver") for index in turn]
        episode = self.episode
        self._applied = tuple(episode.world.act_caregiver(name) for name in names)
        episode.move_novice(move)
        reward, terminated, truncated = episode.reward, episode.terminated, episode.truncated
        result = (
            self._observations(),
            dict.fromkeys(AGENTS, reward),
            dict.fromkeys(AGENTS, terminated),
            dict.fromkeys(AGENTS, truncated),
            self._infos(),
        )
        if terminated or truncated:
            self.agents = []
        return result

    def render(self) -> str | None:
        """The ``ansi`` text of the current state (None, with a warning, when ``render_mode`` is None).

        Raises:
            ResetNeededError: before the first :meth:`reset`.
        """
        return self._ansi()

    def close(self) -> None:
        """Nothing to release."""


def parallel_env(**kwargs: Any) -> HouseholdParallelEnv:
    """A :class:`HouseholdParallelEnv` (PettingZoo's factory convention); ``kwargs`` go to its constructor."""
    return HouseholdParallelEnv(**kwargs)
