"""What the household's Gymnasium and PettingZoo environments share: the grid-code observation, the text
rendering, the random starts and one episode's bookkeeping.

An observation is the map as an ``int8`` array of shape (rows, columns), one :class:`CellCode` per cell:

=====  ===============  =====
code   cell             text
=====  ===============  =====
0      open floor       ``.``
1      wall             ``#``
2      stairwell        ``S``
3      empty table      ``T``
4      candle table     ``C``
5      toy bin          ``B``
6      the novice       ``N``
7      the caregiver    ``R``
=====  ===============  =====

The agents are drawn over the terrain: the caregiver standing in a stairwell shows as ``7``, and a candle the
caregiver carries is not on the grid (the environments report it in ``info["carrying"]``).
"""

from __future__ import annotations

import enum
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache
from typing import Any

import numpy as np
from numpy.typing import NDArray

from supportive.errors import MissingExtraError, ResetNeededError, WorldError
from supportive.worlds.household.grid_map import Cell, GridMap, Terrain, load_map
from supportive.worlds.household.world import Collision, HouseholdWorld

try:
    import gymnasium
    from gymnasium import spaces
except ImportError:  # pragma: no cover - the ``envs`` extra is missing
    raise MissingExtraError("the household RL environments", "gymnasium", "envs") from None

__all__ = [
    "CODE_CHARS",
    "MAX_CODE",
    "CellCode",
    "EpisodeHost",
    "EpisodeLimits",
    "EpisodeState",
    "action_name",
    "caregiver_cell",
    "caregiver_start",
    "encode",
    "novice_cell",
    "novice_start",
    "observation_space",
    "render_codes",
    "resolve_grid",
    "terrain_codes",
]


class CellCode(enum.IntEnum):
    """The code of a cell in an observation (see the module docstring)."""

    FLOOR = 0
    WALL = 1
    STAIRS = 2
    TABLE = 3
    CANDLE = 4
    BIN = 5
    NOVICE = 6
    CAREGIVER = 7


MAX_CODE: int = max(CellCode)
"""The largest cell code (the observation space's upper bound)."""

CODE_CHARS: dict[CellCode, str] = {
    CellCode.FLOOR: ".",
    CellCode.WALL: "#",
    CellCode.STAIRS: "S",
    CellCode.TABLE: "T",
    CellCode.CANDLE: "C",
    CellCode.BIN: "B",
    CellCode.NOVICE: "N",
    CellCode.CAREGIVER: "R",
}
"""The character each code is drawn as in the ``ansi`` rendering."""

_TERRAIN_CODES = {
    Terrain.FLOOR: CellCode.FLOOR,
    Terrain.WALL: CellCode.WALL,
    Terrain.STAIRS: CellCode.STAIRS,
    Terrain.TABLE: CellCode.TABLE,
    Terrain.BIN: CellCode.BIN,
}
_CHAR_TABLE = np.array([CODE_CHARS[code] for code in CellCode])


def resolve_grid(grid: GridMap | str) -> GridMap:
    """``grid`` itself, or the map it names (a shipped map's name or a file path, via :func:`load_map`).

    Raises:
        MapFileError: for an unknown name or a bad file.
    """
    return load_map(grid) if isinstance(grid, str) else grid


@cache
def terrain_codes(grid: GridMap) -> NDArray[np.int8]:
    """The codes of the map's fixed terrain (tables without candles, no agents), read-only (cached per map).

    >>> from supportive.worlds.household.grid_map import parse_map
    >>> terrain_codes(parse_map("#####\\n#B.C#\\n#R.S#\\n#####\\n")).tolist()[1:3]
    [[1, 5, 0, 3, 1], [1, 0, 0, 2, 1]]
    """
    codes = np.array([[_TERRAIN_CODES[kind] for kind in row] for row in grid.terrain], dtype=np.int8)
    codes.setflags(write=False)
    return codes


def encode(world: HouseholdWorld) -> NDArray[np.int8]:
    """The observation of ``world``: a fresh (rows, columns) ``int8`` array of :class:`CellCode` s.

    >>> from supportive.worlds.household.grid_map import parse_map
    >>> world = HouseholdWorld.start(parse_map("#####\\n#B.C#\\n#R.S#\\n#####\\n"), (1, 2), (2, 3))
    >>> encode(world).tolist()[1:3]
    [[1, 5, 6, 4, 1], [1, 0, 0, 7, 1]]
    """
    codes = terrain_codes(world.grid).copy()
    for r, c in world.candles:
        codes[r, c] = CellCode.CANDLE
    if world.caregiver is not None:
        codes[world.caregiver] = CellCode.CAREGIVER
    codes[world.novice] = CellCode.NOVICE
    return codes


def observation_space(grid: GridMap) -> spaces.Box[np.int8]:
    """The space of :func:`encode`'s arrays on ``grid``: ``Box(0, MAX_CODE, (rows, cols), int8)``."""
    return spaces.Box(low=0, high=MAX_CODE, shape=(grid.rows, grid.cols), dtype=np.int8)


def render_codes(codes: NDArray[np.integer[Any]], status: str = "") -> str:
    """An observation as text: one line per map row (``N`` novice, ``R`` caregiver, ``C`` candle, the other
    characters as in map files), then ``status`` on its own line when given.

    >>> from supportive.worlds.household.grid_map import parse_map
    >>> world = HouseholdWorld.start(parse_map("#####\\n#B.C#\\n#R.S#\\n#####\\n"), (1, 2), (2, 3))
    >>> print(render_codes(encode(world), "step 0"), end="")
    #####
    #BNC#
    #..R#
    #####
    step 0
    """
    lines = ["".join(row) for row in _CHAR_TABLE[codes].tolist()]
    if status:
        lines.append(status)
    return "\n".join(lines) + "\n"


def novice_start(grid: GridMap, rng: np.random.Generator) -> Cell:
    """A play-area cell drawn uniformly from ``rng``."""
    cells = grid.play_area
    return cells[int(rng.integers(len(cells)))]


def caregiver_start(grid: GridMap, novice: Cell, rng: np.random.Generator) -> Cell:
    """The map's ``R`` cell, or (when there is none or the novice stands on it) a play-area cell other than
    the novice's drawn uniformly from ``rng``.

    Raises:
        WorldError: when the play area has no cell besides the novice's.
    """
    if grid.caregiver_start is not None and grid.caregiver_start != novice:
        return grid.caregiver_start
    cells = [cell for cell in grid.play_area if cell != novice]
    if not cells:
        raise WorldError(f"map {grid.name!r}: the play area has no room for the caregiver beside the novice")
    return cells[int(rng.integers(len(cells)))]


def _option_cell(options: Mapping[str, Any], key: str) -> Cell | None:
    value = options.get(key)
    if value is None:
        return None
    if not isinstance(value, Sequence) or len(value) != 2:
        raise WorldError(f"options[{key!r}] must be a (row, column) pair, got {value!r}")
    return int(value[0]), int(value[1])


def novice_cell(grid: GridMap, options: Mapping[str, Any] | None, rng: np.random.Generator) -> Cell:
    """The novice's start for a reset: ``options["novice"]`` (a (row, column) pair) when given, else a
    play-area cell drawn from ``rng`` (other option keys are ignored).

    Raises:
        WorldError: for an ``options["novice"]`` that is not a play-area cell.
    """
    novice = _option_cell(options or {}, "novice")
    if novice is None:
        return novice_start(grid, rng)
    if novice not in grid.play_area:
        raise WorldError(f"options['novice'] = {novice} is not on the play area")
    return novice


def caregiver_cell(
    grid: GridMap, options: Mapping[str, Any] | None, novice: Cell, rng: np.random.Generator | None
) -> Cell | None:
    """The caregiver's start for a reset: ``options["caregiver"]`` (a (row, column) pair) when given, else as
    :func:`caregiver_start` says; None when there is no caregiver (``rng`` None).

    Raises:
        WorldError: for an ``options["caregiver"]`` that is not open floor or a stairwell, or is the novice's
            cell, or that is given when there is no caregiver.
    """
    carer = _option_cell(options or {}, "caregiver")
    if rng is None:
        if carer is not None:
            raise WorldError("options['caregiver'] given, but this environment has no caregiver")
        return None
    if carer is None:
        return caregiver_start(grid, novice, rng)
    if grid.at(carer) not in (Terrain.FLOOR, Terrain.STAIRS) or carer == novice:
        raise WorldError(f"options['caregiver'] = {carer} is not free floor or a stairwell")
    return carer


def action_name(action: Any, names: Sequence[str], who: str) -> str:
    """The name of an action given as an index (an ``int`` or a numpy integer) into ``names``.

    Raises:
        WorldError: for something that is not an integer in ``range(len(names))``.

    >>> action_name(np.int64(2), ("north", "east", "south", "west"), "novice")
    'south'
    """
    try:
        index = int(action)
    except (TypeError, ValueError):
        raise WorldError(f"{who} action must be an integer index, got {action!r}") from None
    if index != action or not 0 <= index < len(names):
        raise WorldError(f"{who} action must be an integer in [0, {len(names)}), got {action!r}")
    return names[index]


@dataclass(frozen=True)
class EpisodeLimits:
    """When an episode ends.

    Attributes:
        max_steps: Novice steps before the episode is truncated.
        threshold: Total damage at which it terminates (§3.5.7: 15, three stairwell falls).

    Raises:
        WorldError: when either is below 1.
    """

    max_steps: int = 200
    threshold: int = 15

    def __post_init__(self) -> None:
        if self.max_steps < 1 or self.threshold < 1:
            raise WorldError(
                f"max_steps and threshold must be >= 1, got {self.max_steps} and {self.threshold}"
            )


@dataclass
class EpisodeState:
    """One episode in an environment: the world and the running totals.

    Attributes:
        world: The household's state.
        limits: When the episode ends.
        steps: Novice steps taken.
        damage: Total damage so far.
        collision: What the last novice move bumped into (None: nothing, or no move yet).
        visited: Cells the novice has stood on (its start included).
    """

    world: HouseholdWorld
    limits: EpisodeLimits
    steps: int = 0
    damage: int = 0
    collision: Collision | None = None
    visited: set[Cell] = field(default_factory=set)

    def __post_init__(self) -> None:
        self.visited.add(self.world.novice)

    def move_novice(self, move: str) -> Collision | None:
        """Apply the novice's move and count it; return its collision (None when it walked)."""
        collision = self.world.move_novice(move)
        self.steps += 1
        self.collision = collision
        if collision is not None:
            self.damage += collision.damage
        self.visited.add(self.world.novice)
        return collision

    @property
    def reward(self) -> float:
        """Minus the last move's damage (0.0 without a collision)."""
        return float(-self.collision.damage) if self.collision is not None else 0.0

    @property
    def terminated(self) -> bool:
        """Whether the damage has reached the threshold."""
        return self.damage >= self.limits.threshold

    @property
    def truncated(self) -> bool:
        """Whether the episode has run ``max_steps`` novice steps."""
        return self.steps >= self.limits.max_steps

    def observation(self) -> NDArray[np.int8]:
        """The grid codes now (a fresh array)."""
        return encode(self.world)

    def info(self) -> dict[str, Any]:
        """``step``, ``damage`` so far, the last ``collision`` kind (or None), ``cells_explored``, whether the
        caregiver is ``carrying`` a candle, and the agents' cells."""
        return {
            "step": self.steps,
            "damage": self.damage,
            "collision": None if self.collision is None else self.collision.kind,
            "cells_explored": len(self.visited),
            "carrying": self.world.carrying,
            "novice": self.world.novice,
            "caregiver": self.world.caregiver,
        }

    def status(self, p_safe: float | None = None) -> str:
        """One status line: step, damage, the last bump, P(safe | τ) when known, a candle in hand."""
        parts = [
            f"step {self.steps}/{self.limits.max_steps}",
            f"damage {self.damage}/{self.limits.threshold}",
        ]
        if self.collision is not None:
            parts.append(
                f"bumped into {self.collision.kind} at {self.collision.cell} (+{self.collision.damage})"
            )
        if p_safe is not None:
            parts.append(f"P(safe) {p_safe:.2f}")
        if self.world.carrying:
            parts.append("caregiver carries a candle")
        return " | ".join(parts)

    def render(self, p_safe: float | None = None) -> str:
        """The ``ansi`` rendering: the map with the agents and candles, then :meth:`status`."""
        return render_codes(self.observation(), self.status(p_safe))


class EpisodeHost:
    """What both household environments share: the map, the episode's limits, the render mode and the running
    episode (the Gymnasium and the PettingZoo class each add their API)."""

    metadata: dict[str, Any]
    _episode: EpisodeState | None

    def _host(self, grid: GridMap | str, max_steps: int, threshold: int, render_mode: str | None) -> None:
        """Check and keep the settings every household environment takes; no episode yet.

        Raises:
            WorldError: for a ``render_mode`` other than None or ``"ansi"``, or limits below 1.
            MapFileError: for an unknown map name or a bad map file.
        """
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise WorldError(f"render_mode must be None or 'ansi', got {render_mode!r}")
        self.grid = resolve_grid(grid)
        self.limits = EpisodeLimits(max_steps, threshold)
        self.render_mode = render_mode
        self._episode = None

    @property
    def episode(self) -> EpisodeState:
        """The current episode's state.

        Raises:
            ResetNeededError: before the first :meth:`reset`.
        """
        if self._episode is None:
            raise ResetNeededError("call reset() before step() or render()")
        return self._episode

    def _ansi(self, p_safe: float | None = None) -> str | None:
        """The ``ansi`` text of the current state (None, with a warning, when ``render_mode`` is None).

        Raises:
            ResetNeededError: before the first :meth:`reset`.
        """
        if self.render_mode is None:
            gymnasium.logger.warn("render() called without a render_mode; create the env with render_mode='ansi'")
            return None
        return self.episode.render(p_safe)
