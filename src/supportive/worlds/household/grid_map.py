"""Household floor plans (§3.5.5.1): a grid of walls, floor, stairwells, tables, candles and toy bins.

Maps are plain text a person can draw, one character per cell::

    ; a comment line (only at the top, before the first row)
    ##########
    #B..#...S#
    #...C....#
    #R..T...B#
    ##########

======  =====================================================================
``#``   wall
``.``   open floor
``S``   stairwell (a fall: damage 5)
``T``   table (bumping it: damage 1)
``C``   table with a candle on it (a fire: damage 4)
``B``   toy bin (a goal of the novice; bumping it is harmless)
``R``   open floor where the caregiver robot starts (at most one)
======  =====================================================================

Every row has the same width; cells beyond the edge count as walls. The *play area* is the connected floor
region next to the most toy bins; the novice starts on it, and every toy bin must border it.
"""

from __future__ import annotations

import enum
from collections import deque
from collections.abc import Iterator
from dataclasses import dataclass
from functools import cached_property
from importlib import resources
from pathlib import Path

from supportive.errors import MapFileError
from supportive.io.limits import MAX_MAP_CELLS, MAX_MAP_SIDE
from supportive.io.safe_load import read_text

__all__ = [
    "MOVES",
    "Cell",
    "GridMap",
    "Terrain",
    "load_map",
    "map_names",
    "parse_map",
    "read_map",
]

Cell = tuple[int, int]
"""A cell as (row, column), 0-based from the top left."""

MOVES: dict[str, Cell] = {"north": (-1, 0), "east": (0, 1), "south": (1, 0), "west": (0, -1)}
"""The 4-connected moves and their (row, column) offsets, in the order every action space uses."""


class Terrain(enum.Enum):
    """What occupies a cell (candles are tracked separately: they move)."""

    FLOOR = "."
    WALL = "#"
    STAIRS = "S"
    TABLE = "T"
    BIN = "B"


_SYMBOLS = {
    ".": Terrain.FLOOR,
    "R": Terrain.FLOOR,
    "#": Terrain.WALL,
    "S": Terrain.STAIRS,
    "T": Terrain.TABLE,
    "C": Terrain.TABLE,
    "B": Terrain.BIN,
}
_COMMENT = ";"


@dataclass(frozen=True)
class GridMap:
    """A parsed floor plan. Build one with :func:`parse_map`, :func:`read_map` or :func:`load_map`.

    Attributes:
        name: The map's name (its file stem).
        terrain: Rows of :class:`Terrain`.
        candles: Tables holding a candle at the start.
        caregiver_start: The ``R`` cell, or None when the map has none.
    """

    name: str
    terrain: tuple[tuple[Terrain, ...], ...]
    candles: frozenset[Cell]
    caregiver_start: Cell | None = None

    @property
    def rows(self) -> int:
        """Number of rows."""
        return len(self.terrain)

    @property
    def cols(self) -> int:
        """Number of columns."""
        return len(self.terrain[0])

    def at(self, cell: Cell) -> Terrain:
        """The terrain of ``cell``; a wall outside the grid."""
        r, c = cell
        if 0 <= r < self.rows and 0 <= c < self.cols:
            return self.terrain[r][c]
        return Terrain.WALL

    def cells(self, terrain: Terrain) -> tuple[Cell, ...]:
        """Every cell of one terrain, row by row."""
        return tuple(
            (r, c) for r, row in enumerate(self.terrain) for c, kind in enumerate(row) if kind is terrain
        )

    @cached_property
    def bins(self) -> tuple[Cell, ...]:
        """The toy bins, row by row."""
        return self.cells(Terrain.BIN)

    @cached_property
    def tables(self) -> tuple[Cell, ...]:
        """The tables (with or without a candle), row by row."""
        return self.cells(Terrain.TABLE)

    @cached_property
    def stairs(self) -> tuple[Cell, ...]:
        """The stairwell cells, row by row."""
        return self.cells(Terrain.STAIRS)

    @cached_property
    def floor(self) -> tuple[Cell, ...]:
        """The open floor cells, row by row."""
        return self.cells(Terrain.FLOOR)

    @cached_property
    def play_area(self) -> tuple[Cell, ...]:
        """The connected floor region next to the most toy bins (ties: the largest, then the first)."""
        return _play_area(self)

    def neighbours(self, cell: Cell) -> Iterator[tuple[str, Cell]]:
        """The four moves from ``cell`` and the cells they lead to (which may be walls or outside the grid)."""
        r, c = cell
        for move, (dr, dc) in MOVES.items():
            yield move, (r + dr, c + dc)

    def render(self, candles: frozenset[Cell] | None = None) -> str:
        """The map as text in the file format (with ``candles`` instead of the starting ones when given)."""
        lit = self.candles if candles is None else candles
        lines = []
        for r, row in enumerate(self.terrain):
            chars = []
            for c, kind in enumerate(row):
                if (r, c) == self.caregiver_start:
                    chars.append("R")
                elif kind is Terrain.TABLE and (r, c) in lit:
                    chars.append("C")
                else:
                    chars.append(kind.value)
            lines.append("".join(chars))
        return "\n".join(lines) + "\n"


def _floor_region(grid: GridMap, start: Cell) -> set[Cell]:
    region = {start}
    queue = deque([start])
    while queue:
        cell = queue.popleft()
        for _, following in grid.neighbours(cell):
            if following not in region and grid.at(following) is Terrain.FLOOR:
                region.add(following)
                queue.append(following)
    return region


def _regions(grid: GridMap) -> list[set[Cell]]:
    seen: set[Cell] = set()
    out = []
    for cell in grid.floor:
        if cell not in seen:
            region = _floor_region(grid, cell)
            seen |= region
            out.append(region)
    return out


def _bins_next_to(grid: GridMap, region: set[Cell]) -> set[Cell]:
    return {b for b in grid.bins if any(n in region for _, n in grid.neighbours(b))}


def _play_area(grid: GridMap) -> tuple[Cell, ...]:
    regions = _regions(grid)
    if not regions:
        return ()
    best = max(regions, key=lambda region: (len(_bins_next_to(grid, region)), len(region)))
    return tuple(sorted(best))


def parse_map(text: str, name: str = "map", path: str | Path | None = None) -> GridMap:
    """Parse a map drawn one character per cell (see the module docstring).

    Args:
        text: The map's text.
        name: Its name.
        path: The file it came from (for error messages).

    Raises:
        MapFileError: for an unknown character, rows of different widths, an empty map, a map without a toy
            bin or floor, more than one ``R``, or a toy bin (or ``R``) the play area does not reach; the message
            gives the line and column. Also for a map over :data:`~supportive.io.limits.MAX_MAP_SIDE` cells a
            side, or a play area of one cell or over :data:`~supportive.io.limits.MAX_MAP_CELLS`.

    >>> grid = parse_map("#####\\n#B.C#\\n#R.S#\\n#####\\n", "tiny")
    >>> grid.bins, grid.stairs, sorted(grid.candles), grid.caregiver_start
    (((1, 1),), ((2, 3),), [(1, 3)], (2, 1))
    """
    terrain: list[tuple[Terrain, ...]] = []
    candles: set[Cell] = set()
    caregiver: Cell | None = None
    lines: list[int] = []
    width: int | None = None
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.rstrip()
        if not terrain and (not line or line.startswith(_COMMENT)):
            continue
        if not line:
            continue
        if len(line) > MAX_MAP_SIDE or len(terrain) >= MAX_MAP_SIDE:
            raise MapFileError(
                f"the map is larger than {MAX_MAP_SIDE} × {MAX_MAP_SIDE} cells, the limit", path=path, line=number
            )
        row: list[Terrain] = []
        for column, char in enumerate(line, start=1):
            kind = _SYMBOLS.get(char)
            if kind is None:
                raise MapFileError(
                    f"unknown map character {char!r} (expected one of # . S T C B R)",
                    path=path,
                    line=number,
                    column=column,
                )
            cell = (len(terrain), column - 1)
            if char == "C":
                candles.add(cell)
            if char == "R":
                if caregiver is not None:
                    raise MapFileError(
                        "a second caregiver start 'R' (at most one)", path=path, line=number, column=column
                    )
                caregiver = cell
            row.append(kind)
        if width is None:
            width = len(row)
        elif len(row) != width:
            raise MapFileError(
                f"row is {len(row)} cells wide, the first row is {width}",
                path=path,
                line=number,
                column=min(len(row), width) + 1,
            )
        terrain.append(tuple(row))
        lines.append(number)
    if not terrain:
        raise MapFileError("the map is empty (draw it one character per cell)", path=path)
    grid = GridMap(name, tuple(terrain), frozenset(candles), caregiver)
    if not grid.bins:
        raise MapFileError("the map has no toy bin ('B'): the novice needs a goal", path=path)
    area = set(grid.play_area)
    for cell in grid.bins:
        if not any(n in area for _, n in grid.neighbours(cell)):
            raise MapFileError(
                "toy bin cannot be reached: no open floor of the play area borders it",
                path=path,
                line=lines[cell[0]],
                column=cell[1] + 1,
            )
    if caregiver is not None and caregiver not in area:
        raise MapFileError(
            "the caregiver start 'R' is not on the play area",
            path=path,
            line=lines[caregiver[0]],
            column=caregiver[1] + 1,
        )
    if len(area) > MAX_MAP_CELLS:
        raise MapFileError(
            f"the play area has {len(area):,} floor cells, more than {MAX_MAP_CELLS:,}, the limit (the caregiver's "
            "model grows with the square of it)",
            path=path,
        )
    if len(area) < 2:
        raise MapFileError(
            f"the play area has {len(area)} floor cell: the novice and the caregiver need at least two", path=path
        )
    return grid


def read_map(path: str | Path) -> GridMap:
    """Read a map file (UTF-8 text, see the module docstring); its name is the file stem.

    Raises:
        MapFileError: when the file is missing, unreadable or malformed (naming file, line and column).
    """
    file = Path(path)
    return parse_map(read_text(file, MapFileError), file.stem, file)


def map_names() -> tuple[str, ...]:
    """The maps shipped with the package (``house`` is modelled on the thesis's Figure 3.13).

    >>> "house" in map_names()
    True
    """
    folder = resources.files("supportive.worlds.household") / "maps"
    return tuple(sorted(p.name.removesuffix(".map") for p in folder.iterdir() if p.name.endswith(".map")))


def load_map(name: str) -> GridMap:
    """A shipped map by name, or a map file by path.

    Raises:
        MapFileError: for an unknown name or a bad file.
    """
    if name in map_names():
        text = (resources.files("supportive.worlds.household") / "maps" / f"{name}.map").read_text("utf-8")
        return parse_map(text, name, f"maps/{name}.map")
    if Path(name).suffix or "/" in name:
        return read_map(name)
    raise MapFileError(
        f"no shipped map of this name (known: {', '.join(map_names())}; or give a file path)", path=name
    )
