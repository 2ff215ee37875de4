"""The household world as a Gymnasium environment for the novice (§3.5): learn to walk without getting hurt.

The agent is the novice; optionally the built-in caregiver robot
(:class:`~supportive.safety.caregiver.Caregiver`) is part of the dynamics. Each step:

1. the caregiver (when present) takes the up to three actions it decides on,
2. the novice makes its move (the action: an index into :data:`~supportive.worlds.household.grid_map.MOVES`,
   north, east, south, west),
3. the caregiver observes the move and updates P(safe | τ).

The observation is the grid of cell codes of :mod:`supportive.envs.household.encoding` (floor 0, wall 1,
stairwell 2, empty table 3, candle table 4, toy bin 5, novice 6, caregiver 7). The reward is minus the damage
of the move's collision (stairwell 5, candle 4, table 1, anything else 0). The episode terminates when the
damage reaches ``threshold`` and is truncated after ``max_steps`` moves.

Importing this module registers the environment as ``"supportive/Household-v0"``::

    env = gymnasium.make("supportive/Household-v0", grid="playroom", caregiver=True)
"""

from __future__ import annotations

from typing import Any, SupportsFloat

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
from supportive.errors import MissingExtraError
from supportive.safety.caregiver import Caregiver
from supportive.safety.episode import map_model
from supportive.worlds.household.grid_map import GridMap
from supportive.worlds.household.world import NOVICE_ACTIONS, HouseholdWorld

try:
    import gymnasium
    from gymnasium import spaces
except ImportError:  # pragma: no cover - the ``envs`` extra is missing
    raise MissingExtraError("the household Gymnasium environment", "gymnasium", "envs") from None

__all__ = ["ENV_ID", "NoviceEnv", "register_envs"]

ENV_ID = "supportive/Household-v0"
"""The Gymnasium id of :class:`NoviceEnv`."""


class NoviceEnv(EpisodeHost, gymnasium.Env[NDArray[np.int8], np.int64]):
    """The novice in the household, alone or with the built-in caregiver.

    Args:
        grid: The map, or a shipped map's name or a map file's path (see
            :func:`~supportive.worlds.household.grid_map.load_map`).
        caregiver: Whether the caregiver robot (with the map's action priors) acts in the house.
        max_steps: Novice steps before the episode is truncated.
        threshold: Total damage at which the episode terminates.
        render_mode: None, or ``"ansi"``: :meth:`render` returns the map with ``N`` (novice), ``R``
            (caregiver), ``C`` (candles) and a status line.

    ``reset(options=...)`` accepts ``{"novice": (row, col)}`` (a play-area cell) and, with a caregiver,
    ``{"caregiver": (row, col)}`` to fix the starts; otherwise the novice starts on a play-area cell drawn
    from :attr:`np_random` and the caregiver on the map's ``R`` cell. ``info`` holds ``step``, ``damage`` so
    far, the last ``collision`` kind (or None), ``cells_explored``, ``carrying``, the ``novice`` and
    ``caregiver`` cells, and with a caregiver ``p_safe`` (its P(safe | τ)) and ``caregiver_actions``.

    Raises:
        WorldError: for a ``render_mode`` other than None or ``"ansi"``, or limits below 1.
        MapFileError: for an unknown map name or a bad map file.

    >>> env = NoviceEnv("playroom", render_mode="ansi")
    >>> obs, info = env.reset(seed=0, options={"novice": (5, 1)})
    >>> obs.shape, info["damage"], info["cells_explored"]
    ((9, 12), 0, 1)
    >>> obs, reward, terminated, truncated, info = env.step(np.int64(3))  # west, into the wall
    >>> reward, info["collision"], terminated, truncated
    (0.0, 'wall', False, False)
    """

    metadata: dict[str, Any] = {"render_modes": ["ansi"], "render_fps": 4}  # noqa: RUF012 - Gymnasium's convention

    def __init__(
        self,
        grid: GridMap | str = "house",
        caregiver: bool = False,
        max_steps: int = 200,
        threshold: int = 15,
        render_mode: str | None = None,
    ) -> None:
        self._host(grid, max_steps, threshold, render_mode)
        self.observation_space = observation_space(self.grid)
        self.action_space = spaces.Discrete(len(NOVICE_ACTIONS))
        self.caregiver: Caregiver | None = None
        if caregiver:
            distances, priors = map_model(self.grid)
            self.caregiver = Caregiver(distances, priors)
        self._p_safe: float | None = None
        self._caregiver_actions: tuple[str, ...] = ()

    def _info(self) -> dict[str, Any]:
        info = self.episode.info()
        if self.caregiver is not None:
            info["p_safe"] = self._p_safe
            info["caregiver_actions"] = self._caregiver_actions
        return info

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[NDArray[np.int8], dict[str, Any]]:
        """Start an episode.

        Args:
            seed: Seeds :attr:`np_random`, from which the novice's start and the caregiver's generator come
                (the same seed gives the same episode for the same actions).
            options: ``"novice"`` and ``"caregiver"`` start cells (optional; other keys are ignored).

        Returns:
            The first observation and the info.

        Raises:
            WorldError: for a bad start cell in ``options``.
        """
        super().reset(seed=seed)
        novice = novice_cell(self.grid, options, self.np_random)
        carer_rng: np.random.Generator | None = None
        if self.caregiver is not None:  # drawn after the novice's start: the same start with or without it
            carer_rng = np.random.default_rng(int(self.np_random.integers(2**63)))
        carer = caregiver_cell(self.grid, options, novice, carer_rng)
        self._episode = EpisodeState(HouseholdWorld.start(self.grid, novice, carer), self.limits)
        self._caregiver_actions = ()
        if self.caregiver is not None:
            assert carer_rng is not None
            self.caregiver.reset()
            self.caregiver.rng = carer_rng
            self._p_safe = self.caregiver.safety.probability
        return self.episode.observation(), self._info()

    def step(
        self, action: int | np.integer[Any]
    ) -> tuple[NDArray[np.int8], SupportsFloat, bool, bool, dict[str, Any]]:
        """One novice step (preceded by the caregiver's turn when there is a caregiver).

        Args:
            action: The novice's move, an index into north, east, south, west.

        Returns:
            Observation, reward (minus the collision's damage), terminated (damage >= threshold), truncated
            (``max_steps`` reached), info.

        Raises:
            WorldError: for an action outside ``range(4)``.
            ResetNeededError: before the first :meth:`reset`.
        """
        move = action_name(action, NOVICE_ACTIONS, "novice")
        episode = self.episode
        world = episode.world
        if self.caregiver is not None:
            self._caregiver_actions = self.caregiver.decide(world).actions
            for caregiver_action in self._caregiver_actions:
                world.act_caregiver(caregiver_action)
        before = world.novice
        episode.move_novice(move)
        if self.caregiver is not None:
            self._p_safe = self.caregiver.observe(before, move)
        return episode.observation(), episode.reward, episode.terminated, episode.truncated, self._info()

    def render(self) -> str | None:
        """The ``ansi`` text of the current state (None, with a warning, when ``render_mode`` is None).

        Raises:
            ResetNeededError: before the first :meth:`reset`.
        """
        return self._ansi(self._p_safe)


def register_envs() -> None:
    """Register :class:`NoviceEnv` with Gymnasium as :data:`ENV_ID` (a no-op when it already is)."""
    if ENV_ID not in gymnasium.registry:
        gymnasium.register(id=ENV_ID, entry_point="supportive.envs.household.gym_env:NoviceEnv")


register_envs()
