"""Novice agents (§3.5.5.2): ε-greedy walkers between toy bins.

A novice knows where every toy bin is, picks one at random as its goal, and at each step takes a shortest-path
move toward it with probability 1 − ε and a uniformly random move (which may bump into anything) with
probability ε. Beside its goal it has arrived and picks another bin. ε = 1 is "random motion", 0.75 "75 %
random", down to 0.05 "5 % random".

The thesis's sentence "it will take an optimal action ε% of the time and a random action (1 − ε)% of the
time" swaps the two; its own labels ("75% random") and the usual meaning of ε-greedy say ε is the random
share, which is what we implement.
"""

from __future__ import annotations

from supportive.errors import WorldError
from supportive.seeding import Seed, rng_from
from supportive.worlds.household.distances import MapDistances
from supportive.worlds.household.grid_map import MOVES, Cell

__all__ = ["NOVICE_TYPES", "EpsilonGreedyNovice"]

NOVICE_TYPES: dict[str, float] = {
    "random motion": 1.0,
    "75% random": 0.75,
    "50% random": 0.5,
    "25% random": 0.25,
    "5% random": 0.05,
}
"""The five novice types of Tables 3.1–3.3 and their ε."""


class EpsilonGreedyNovice:
    """An ε-greedy novice heading for toy bins.

    Args:
        distances: The map's distances (see :class:`MapDistances`).
        epsilon: Probability of a random move, in [0, 1].
        seed: Seed or generator for its start, goals and moves.

    Attributes:
        goal: The toy bin it is heading for.

    >>> from supportive.worlds.household.grid_map import parse_map
    >>> d = MapDistances(parse_map("#####\\n#B..#\\n#...#\\n#####\\n"))
    >>> novice = EpsilonGreedyNovice(d, epsilon=0.0, seed=1)
    >>> novice.optimal_moves((2, 3))
    ('north', 'west')
    """

    def __init__(self, distances: MapDistances, epsilon: float, seed: Seed = None) -> None:
        if not 0.0 <= epsilon <= 1.0:
            raise WorldError(f"epsilon must be in [0, 1], got {epsilon}")
        self.distances = distances
        self.epsilon = epsilon
        self.rng = rng_from(seed)
        self.goal: Cell = self._pick_goal(None)

    def start_cell(self) -> Cell:
        """A random cell of the play area (draws from the novice's generator)."""
        cells = self.distances.novice.cells
        return cells[int(self.rng.integers(len(cells)))]

    def _pick_goal(self, current: Cell | None) -> Cell:
        bins = [b for b in self.distances.grid.bins if b != current] or list(self.distances.grid.bins)
        return bins[int(self.rng.integers(len(bins)))]

    def optimal_moves(self, cell: Cell) -> tuple[str, ...]:
        """The moves from ``cell`` that shorten the way to the goal (none when it is already beside it)."""
        steps = self.distances.to_bin[self.goal]
        index = self.distances.novice.index
        here = steps[index[cell]]
        out = []
        for move, (dr, dc) in MOVES.items():
            j = index.get((cell[0] + dr, cell[1] + dc))
            if j is not None and steps[j] < here:
                out.append(move)
        return tuple(out)

    def arrived(self, cell: Cell) -> bool:
        """True when ``cell`` is beside the goal bin."""
        return bool(self.distances.to_bin[self.goal][self.distances.novice.index[cell]] == 0)

    def act(self, cell: Cell) -> str:
        """The novice's next move from ``cell`` (picking a new goal first if it has arrived)."""
        if self.arrived(cell):
            self.goal = self._pick_goal(self.goal)
        greedy = self.optimal_moves(cell)
        if not greedy or self.rng.random() < self.epsilon:
            moves = tuple(MOVES)
            return moves[int(self.rng.integers(len(moves)))]
        return greedy[int(self.rng.integers(len(greedy)))]
