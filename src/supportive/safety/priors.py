"""Action priors from expert trajectories (§3.5.2, Rosman & Ramamoorthy's action priors).

For every state (a cell) the prior counts, over a set of optimal policies Π (one per task: reaching one toy
bin), how many take action ``a`` there with probability above δ, plus a Dirichlet hyperprior α⁰:

    α_s(a) = |{π ∈ Π : π(s, a) > δ}| + α⁰_s(a),        θ_s ~ Dir(α_s).

Each policy π is estimated from expert trajectories — shortest collision-free paths from varied starts to
its bin, ties among shortest moves broken at random — as the share of the expert's visits to ``s`` that took
``a``. θ_s is the Dirichlet's mean α_s / Σα_s by default (a seeded draw on request, as the thesis's "draw
from a Dirichlet distribution"). A cell no expert visited gets the hyperprior alone: uniform.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from supportive.errors import SafetyError
from supportive.seeding import Seed, rng_from
from supportive.worlds.household.distances import MapDistances
from supportive.worlds.household.grid_map import MOVES, Cell

__all__ = ["ActionPriors", "expert_trajectory"]

_MOVE_INDEX = {move: k for k, move in enumerate(MOVES)}


def expert_trajectory(
    distances: MapDistances, start: Cell, goal: Cell, rng: np.random.Generator
) -> list[tuple[Cell, str]]:
    """A shortest collision-free path from ``start`` to beside the toy bin ``goal``, as (cell, move) pairs.

    Among several shortest moves one is drawn from ``rng``. Empty when ``start`` is already beside the bin.
    """
    steps = distances.to_bin[goal]
    index = distances.novice.index
    path: list[tuple[Cell, str]] = []
    cell = start
    while steps[index[cell]] > 0:
        here = steps[index[cell]]
        options = []
        for move, (dr, dc) in MOVES.items():
            following = (cell[0] + dr, cell[1] + dc)
            j = index.get(following)
            if j is not None and steps[j] == here - 1:
                options.append((move, following))
        move, following = options[int(rng.integers(len(options)))]
        path.append((cell, move))
        cell = following
    return path


@dataclass(frozen=True)
class ActionPriors:
    """θ_s(a) for every play-area cell and move.

    Attributes:
        cells: The play-area cells, in :class:`~supportive.worlds.household.distances.CellGraph` order.
        counts: α_s(a) without the hyperprior, shape (cells, 4), moves in ``MOVES`` order.
        theta: θ_s(a), shape (cells, 4); each row sums to 1.
        hyperprior: α⁰ (the same for every state and action).
    """

    cells: tuple[Cell, ...]
    counts: np.ndarray
    theta: np.ndarray
    hyperprior: float

    @classmethod
    def from_experts(
        cls,
        distances: MapDistances,
        *,
        starts: int | None = None,
        delta: float = 0.0,
        hyperprior: float = 0.5,
        sample: bool = False,
        seed: Seed = None,
    ) -> ActionPriors:
        """Learn the priors from expert trajectories to every toy bin.

        Args:
            distances: The map's distances.
            starts: Expert trajectories per bin, from starts drawn uniformly over the play area; None starts
                one from every play-area cell.
            delta: A policy "takes" ``a`` in ``s`` when its share of the expert's moves there exceeds this.
            hyperprior: α⁰ > 0, added to every count.
            sample: Draw θ_s from Dir(α_s) instead of taking its mean.
            seed: Seed or generator (start cells, ties between shortest moves, Dirichlet draws).

        Raises:
            SafetyError: for ``hyperprior`` <= 0, ``delta`` outside [0, 1) or ``starts`` < 1.

        >>> from supportive.worlds.household.grid_map import parse_map
        >>> priors = ActionPriors.from_experts(MapDistances(parse_map("#####\\n#B..#\\n#####\\n")), hyperprior=1.0)
        >>> priors.probability((1, 3), "west"), priors.probability((1, 3), "east")
        (0.4, 0.2)
        """
        if hyperprior <= 0:
            raise SafetyError(f"hyperprior must be > 0, got {hyperprior}")
        if not 0.0 <= delta < 1.0:
            raise SafetyError(f"delta must be in [0, 1), got {delta}")
        if starts is not None and starts < 1:
            raise SafetyError(f"starts must be >= 1 or None, got {starts}")
        rng = rng_from(seed)
        graph = distances.novice
        n = len(graph.cells)
        counts = np.zeros((n, len(MOVES)), dtype=np.int64)
        for goal in distances.grid.bins:
            visits = np.zeros((n, len(MOVES)), dtype=np.int64)
            origins = (
                graph.cells
                if starts is None
                else [graph.cells[int(i)] for i in rng.integers(n, size=starts)]
            )
            for start in origins:
                for cell, move in expert_trajectory(distances, start, goal, rng):
                    visits[graph.index[cell], _MOVE_INDEX[move]] += 1
            totals = visits.sum(axis=1, keepdims=True)
            share = np.divide(visits, totals, out=np.zeros(visits.shape), where=totals > 0)
            counts += share > delta
        alpha = counts + hyperprior
        if sample:
            theta = np.vstack([rng.dirichlet(row) for row in alpha])
        else:
            theta = alpha / alpha.sum(axis=1, keepdims=True)
        return cls(graph.cells, counts, theta, hyperprior)

    @cached_property
    def _rows(self) -> dict[Cell, int]:
        return {cell: i for i, cell in enumerate(self.cells)}

    def probability(self, cell: Cell, move: str) -> float:
        """θ_cell(move); 0.25 (uniform) for a cell outside the play area.

        Raises:
            SafetyError: for an unknown move.
        """
        if move not in MOVES:
            raise SafetyError(f"unknown move {move!r} (expected one of {', '.join(MOVES)})")
        row = self._rows.get(cell)
        if row is None:
            return 1.0 / len(MOVES)
        return float(self.theta[row, _MOVE_INDEX[move]])
