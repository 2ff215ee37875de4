"""Shortest-path distances on a household map, computed once per map (the walls, stairs and tables never move).

The novice walks on the play area's open floor; the caregiver also on stairwell cells (it stands in one to
block it). Both are 4-connected. Distances come from ``scipy.sparse.csgraph.shortest_path`` (breadth-first
on the unweighted grid graph) and are looked up, not recomputed, during an episode; the agents themselves are
not obstacles in them.
"""

from __future__ import annotations

from collections.abc import Iterable
from functools import cached_property

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import shortest_path

from supportive.worlds.household.grid_map import Cell, GridMap

__all__ = ["UNREACHABLE", "CellGraph", "MapDistances"]

UNREACHABLE = np.iinfo(np.int32).max
"""Distance between cells with no path between them."""


class CellGraph:
    """All-pairs step counts over a set of walkable cells.

    Args:
        grid: The map.
        walkable: The cells an agent may stand on.

    >>> from supportive.worlds.household.grid_map import parse_map
    >>> grid = parse_map("#####\\n#B..#\\n#..S#\\n#####\\n")
    >>> graph = CellGraph(grid, grid.floor)
    >>> graph.distance((1, 2), (2, 1)), graph.distance((1, 2), (2, 3))
    (2, 2147483647)
    """

    def __init__(self, grid: GridMap, walkable: Iterable[Cell]) -> None:
        self.grid = grid
        self.cells: tuple[Cell, ...] = tuple(sorted(set(walkable)))
        self.index: dict[Cell, int] = {cell: i for i, cell in enumerate(self.cells)}
        rows, cols = [], []
        for i, cell in enumerate(self.cells):
            for _, following in grid.neighbours(cell):
                j = self.index.get(following)
                if j is not None:
                    rows.append(i)
                    cols.append(j)
        n = len(self.cells)
        adjacency = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n)).tocsr()
        raw = shortest_path(adjacency, method="D", unweighted=True, directed=False)
        self.matrix: np.ndarray = np.where(np.isinf(raw), UNREACHABLE, raw).astype(np.int32)

    def distance(self, a: Cell, b: Cell) -> int:
        """Steps from ``a`` to ``b`` (``UNREACHABLE`` when there is no path or either is not walkable)."""
        i, j = self.index.get(a), self.index.get(b)
        if i is None or j is None:
            return int(UNREACHABLE)
        return int(self.matrix[i, j])

    def to_any(self, targets: Iterable[Cell]) -> np.ndarray:
        """For every walkable cell (in :attr:`cells` order), the steps to the nearest of ``targets``."""
        columns = [self.index[t] for t in targets if t in self.index]
        if not columns:
            return np.full(len(self.cells), UNREACHABLE, dtype=np.int32)
        return np.asarray(self.matrix[:, columns].min(axis=1))


class MapDistances:
    """The distances the novice, the caregiver and the danger model need on one map.

    Attributes:
        novice: Distances over the play area (where the novice walks).
        caregiver: Distances over the play area plus the stairwell cells next to it.
    """

    def __init__(self, grid: GridMap) -> None:
        self.grid = grid
        area = set(grid.play_area)
        self.novice = CellGraph(grid, area)
        stairs = {s for s in grid.stairs if any(n in area for _, n in grid.neighbours(s))}
        self.caregiver = CellGraph(grid, area | stairs)

    def approaches(self, target: Cell) -> tuple[Cell, ...]:
        """The play-area cells next to ``target`` (where an agent stands to touch or bump into it)."""
        area = self.novice.index
        return tuple(n for _, n in self.grid.neighbours(target) if n in area)

    @cached_property
    def to_bin(self) -> dict[Cell, np.ndarray]:
        """For each toy bin, every play-area cell's steps to a cell beside it (0: already beside it)."""
        return {b: self.novice.to_any(self.approaches(b)) for b in self.grid.bins}

    @cached_property
    def to_collide(self) -> dict[Cell, np.ndarray]:
        """For each hazard cell (stairs, tables), every play-area cell's steps to bump into it (1: beside it)."""
        hazards = [c for c in (*self.grid.stairs, *self.grid.tables) if self.approaches(c)]
        out = {}
        for hazard in hazards:
            steps = self.novice.to_any(self.approaches(hazard))
            out[hazard] = np.where(steps == UNREACHABLE, UNREACHABLE, steps + 1).astype(np.int32)
        return out
