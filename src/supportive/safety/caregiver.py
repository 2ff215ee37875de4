"""The caregiver robot (§3.5.5.3): it watches the novice and rearranges the house to keep it safe.

Each novice step the caregiver may take up to three actions (a 5.0 km/h adult beside a 1.6 km/h toddler).
It keeps P(safe | τ) of the novice's trajectory (:class:`~supportive.safety.safe_probability.SafetyEstimate`)
and the expected damage of every hazard (:class:`~supportive.safety.danger.DangerModel`), and weighs the two
interventions of the thesis against the time they take:

* **block a stairwell**: stand in it. Benefit: the stairwell's expected damage. Time: the walk there.
* **move a candle** from its table to an empty one. Benefit: the candle's expected damage there minus
  what it will be at the new table — (1 − P(safe)) · (4 − 1) · (P(reach) there − P(reach) at the new
  table), since the old table stays a (harmless-ish) empty table. Time: the walk to the candle, ``get``, the
  walk to the new table, ``place``.

The cost of an intervention is ``cost_per_step`` damage per novice step it takes (caregiver steps / 3), the
thesis's "cost to mitigate risk … proportional to the time required". The best positive net benefit wins;
the current intervention is kept unless another beats it by ``switch_margin`` (no dithering), and a candle
in hand is always put down first (on the empty table where it adds the least danger, counting the walk).

It never makes things worse: it does not step where it would cut the novice off from every toy bin.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

from supportive.errors import SafetyError
from supportive.safety.danger import HORIZON, DangerModel
from supportive.safety.priors import ActionPriors
from supportive.safety.safe_probability import SafetyEstimate
from supportive.seeding import Seed, rng_from
from supportive.worlds.household.distances import UNREACHABLE, MapDistances
from supportive.worlds.household.grid_map import MOVES, Cell, Terrain
from supportive.worlds.household.world import DAMAGE, HouseholdWorld

__all__ = ["MEMORY", "Caregiver", "Decision", "Intervention"]

MEMORY = 0.9
"""Default γ of the caregiver's P(safe | τ): roughly the last ten moves count (see docs/caregiver.md)."""

CANDLE_GAIN = DAMAGE["candle"] - DAMAGE["table"]
"""What moving a candle off a table changes there: a candle (4) becomes an empty table (1)."""


@dataclass(frozen=True)
class Intervention:
    """What the caregiver is doing: blocking a stairwell, or moving a candle from ``target`` to ``destination``.

    Attributes:
        kind: ``"block"``, ``"move-candle"`` or ``"stand-by"`` (nothing is worth doing: wait in the
            stairwell nearest the novice, out of its way).
        target: The stairwell cell, or the table the candle stands on.
        destination: The empty table the candle goes to (``move-candle`` only).
        benefit: Expected damage it removes.
        cost: The time it takes, as damage (``cost_per_step`` per novice step).
    """

    kind: str
    target: Cell
    destination: Cell | None
    benefit: float
    cost: float

    @property
    def net(self) -> float:
        """Benefit minus cost."""
        return self.benefit - self.cost

    def describe(self) -> str:
        """One line for a person."""
        if self.kind == "block":
            return f"block the stairwell at {self.target}"
        if self.kind == "stand-by":
            return f"stand by in the stairwell at {self.target}"
        return f"move the candle at {self.target} to the table at {self.destination}"


@dataclass(frozen=True)
class Decision:
    """One caregiver turn: the actions to take, why, and what it believed.

    Attributes:
        actions: Up to ``actions_per_step`` caregiver actions, in order.
        intervention: What they serve (None: nothing to do on a map without stairs; it waits).
        p_safe: P(safe | τ) when deciding.
        expected_damage: E(d_o | τ) of every hazard when deciding.
    """

    actions: tuple[str, ...]
    intervention: Intervention | None
    p_safe: float
    expected_damage: dict[Cell, float]


class Caregiver:
    """The caregiver's policy.

    Args:
        distances: The map's distances.
        priors: Action priors learned from experts on the same map.
        actions_per_step: Caregiver actions per novice step (3 in the thesis).
        cost_per_step: Damage-equivalent cost of one novice step of intervention time.
        switch_margin: How much more net benefit another intervention needs to replace the current one.
        horizon: The danger model's reach horizon H, in novice steps (see :class:`DangerModel`).
        memory: γ of the P(safe | τ) estimate (see :class:`SafetyEstimate`; 1 is Eq. 3.2 over the whole
            trajectory).
        seed: Seed or generator for breaking ties between equally short moves.

    >>> from supportive.worlds.household import HouseholdWorld, MapDistances, parse_map
    >>> d = MapDistances(parse_map("#######\\n#B...S#\\n#R....#\\n#######\\n"))
    >>> carer = Caregiver(d, ActionPriors.from_experts(d, seed=0), seed=0)
    >>> world = HouseholdWorld.start(d.grid, novice=(1, 4), caregiver=(2, 1))
    >>> carer.decide(world).intervention.describe()
    'block the stairwell at (1, 5)'
    """

    def __init__(
        self,
        distances: MapDistances,
        priors: ActionPriors,
        *,
        actions_per_step: int = 3,
        cost_per_step: float = 0.1,
        switch_margin: float = 0.25,
        horizon: float = HORIZON,
        memory: float = MEMORY,
        seed: Seed = None,
    ) -> None:
        if actions_per_step < 1:
            raise SafetyError(f"actions_per_step must be >= 1, got {actions_per_step}")
        if cost_per_step < 0 or switch_margin < 0:
            raise SafetyError("cost_per_step and switch_margin must be >= 0")
        self.distances = distances
        self.grid = distances.grid
        self.actions_per_step = actions_per_step
        self.cost_per_step = cost_per_step
        self.switch_margin = switch_margin
        self.danger = DangerModel(distances, horizon)
        self.safety = SafetyEstimate(priors, memory=memory)
        self.rng = rng_from(seed)
        import networkx as nx  # here: networkx is a fifth of every command's start-up

        graph = distances.novice
        floor = nx.Graph()
        floor.add_nodes_from(graph.cells)
        floor.add_edges_from(
            (cell, n) for cell in graph.cells for _, n in self.grid.neighbours(cell) if n in graph.index
        )
        self._cut_cells = frozenset(nx.articulation_points(floor))
        self._bin_sides = frozenset(n for b in self.grid.bins for n in distances.approaches(b))
        self._table_sides = {
            t: tuple(n for _, n in self.grid.neighbours(t) if n in distances.caregiver.index)
            for t in self.grid.tables
        }
        self.intervention: Intervention | None = None

    def reset(self) -> None:
        """Forget the novice's trajectory and the current intervention (a new episode)."""
        self.safety.reset()
        self.intervention = None

    def observe(self, cell: Cell, move: str) -> float:
        """Watch the novice take ``move`` from ``cell``; return the new P(safe | τ)."""
        return self.safety.observe(cell, move)

    # -- choosing an intervention -------------------------------------------------------------------------

    def _walk(self, start: Cell, goal: Cell) -> int:
        return self.distances.caregiver.distance(start, goal)

    def _side(self, world: HouseholdWorld, table: Cell, action: str, start: Cell) -> tuple[Cell | None, int]:
        """The nearest cell beside ``table`` from which ``action`` (get/place) acts on it, and the walk."""
        best: tuple[Cell | None, int] = (None, int(UNREACHABLE))
        for side in self._table_sides[table]:
            if self._first_table(world, side, action) != table:
                continue
            steps = self._walk(start, side)
            if steps < best[1]:
                best = (side, steps)
        return best

    def _first_table(self, world: HouseholdWorld, side: Cell, action: str) -> Cell | None:
        for _, cell in self.grid.neighbours(side):
            if self.grid.at(cell) is not Terrain.TABLE:
                continue
            holds = cell in world.candles
            if (action == "get" and holds) or (action == "place" and not holds):
                return cell
        return None

    def _cost(self, caregiver_steps: int) -> float:
        return self.cost_per_step * caregiver_steps / self.actions_per_step

    def options(self, world: HouseholdWorld, p_safe: float) -> list[Intervention]:
        """Every intervention open now, with its benefit and cost (a candle in hand: only where to put it).

        Raises:
            SafetyError: when the world has no caregiver.
        """
        if world.caregiver is None:
            raise SafetyError("the world has no caregiver")
        here = world.caregiver
        reach = self.danger.reach_all(world.novice)
        unsafe = 1.0 - p_safe
        empty = [t for t in self.grid.tables if t not in world.candles]
        if world.carrying:
            assert self.intervention is not None and self.intervention.kind == "move-candle"
            source = self.intervention.target
            out = []
            for table in empty:
                side, steps = self._side(world, table, "place", here)
                if side is None or steps >= UNREACHABLE:
                    continue
                benefit = unsafe * CANDLE_GAIN * (reach.get(source, 0.0) - reach.get(table, 0.0))
                out.append(Intervention("move-candle", source, table, benefit, self._cost(steps + 1)))
            return out
        out = []
        for stairs in self.grid.stairs:
            steps = self._walk(here, stairs)
            if steps < UNREACHABLE:
                benefit = unsafe * reach.get(stairs, 0.0) * DAMAGE["stairs"]
                out.append(Intervention("block", stairs, None, benefit, self._cost(steps)))
        for candle in sorted(world.candles):
            side, to_candle = self._side(world, candle, "get", here)
            if side is None or to_candle >= UNREACHABLE:
                continue
            lifted = world.copy()
            lifted.candles.discard(candle)
            for table in empty:
                place_side, onward = self._side(lifted, table, "place", side)
                if place_side is None or onward >= UNREACHABLE:
                    continue
                benefit = unsafe * CANDLE_GAIN * (reach.get(candle, 0.0) - reach.get(table, 0.0))
                cost = self._cost(to_candle + 1 + onward + 1)
                out.append(Intervention("move-candle", candle, table, benefit, cost))
        return out

    def _stand_by(self, world: HouseholdWorld) -> Intervention | None:
        """With nothing worth doing: wait in the stairwell the novice could reach soonest (off every path the
        novice walks, and blocking the worst hazard there is); None on a map without stairs."""
        assert world.caregiver is not None
        here = world.caregiver
        reachable = [s for s in self.grid.stairs if self._walk(here, s) < UNREACHABLE]
        if not reachable:
            return None
        stairs = min(reachable, key=lambda s: (self.danger.steps(s, world.novice), self._walk(here, s), s))
        return Intervention("stand-by", stairs, None, 0.0, self._cost(self._walk(here, stairs)))

    def choose(self, world: HouseholdWorld, p_safe: float) -> Intervention | None:
        """The intervention to pursue now (with no positive net benefit anywhere, standing by)."""
        options = self.options(world, p_safe)
        if world.carrying:
            return max(options, key=lambda o: o.net, default=self.intervention)
        best = max(options, key=lambda o: o.net, default=None)
        if best is None or best.net <= 0:
            return self._stand_by(world)
        current = self.intervention
        if current is not None:
            same = [
                o for o in options
                if (o.kind, o.target, o.destination) == (current.kind, current.target, current.destination)
            ]
            if same and same[0].net > 0 and same[0].net + self.switch_margin >= best.net:
                return same[0]
        return best

    # -- acting -----------------------------------------------------------------------------------------

    def _keeps_novice_connected(self, world: HouseholdWorld, cell: Cell) -> bool:
        """True when the novice can still reach a toy bin with the caregiver standing on ``cell``."""
        if cell not in self._cut_cells:
            return True
        index = self.distances.novice.index
        seen = {world.novice}
        queue = deque([world.novice])
        while queue:
            current = queue.popleft()
            if current in self._bin_sides:
                return True
            for _, following in self.grid.neighbours(current):
                if following in index and following != cell and following not in seen:
                    seen.add(following)
                    queue.append(following)
        return False

    def _step_toward(self, world: HouseholdWorld, goal: Cell) -> str:
        assert world.caregiver is not None
        here = world.caregiver
        if abs(here[0] - world.novice[0]) + abs(here[1] - world.novice[1]) <= 2:
            return self._detour(world, goal)  # the novice may stand on the shortest way: walk around it
        remaining = self._walk(here, goal)
        moves = []
        for move, (dr, dc) in MOVES.items():
            following = (here[0] + dr, here[1] + dc)
            if (
                following in self.distances.caregiver.index
                and self._walk(following, goal) < remaining
                and world.caregiver_can_enter(following)
                and self._keeps_novice_connected(world, following)
            ):
                moves.append(move)
        if not moves:
            return "wait"
        clear = [m for m in moves if not self._beside_novice(world, m)]
        moves = clear or moves  # among equally short moves, keep out of the novice's way
        return moves[int(self.rng.integers(len(moves)))] if len(moves) > 1 else moves[0]

    def _detour(self, world: HouseholdWorld, goal: Cell) -> str:
        """A first step of a shortest way that avoids the novice's cell (breadth-first from the goal with that
        cell taken out); ``wait`` when there is no way round."""
        assert world.caregiver is not None
        walkable = self.distances.caregiver.index
        distance = {goal: 0}
        queue = deque([goal])
        while queue:
            cell = queue.popleft()
            for _, following in self.grid.neighbours(cell):
                if following in walkable and following != world.novice and following not in distance:
                    distance[following] = distance[cell] + 1
                    queue.append(following)
        here = distance.get(world.caregiver)
        for move, following in self.grid.neighbours(world.caregiver):
            if (
                here is not None
                and distance.get(following, here) < here
                and world.caregiver_can_enter(following)
                and self._keeps_novice_connected(world, following)
            ):
                return move
        return "wait"

    @staticmethod
    def _beside_novice(world: HouseholdWorld, move: str) -> bool:
        assert world.caregiver is not None
        dr, dc = MOVES[move]
        r, c = world.caregiver[0] + dr, world.caregiver[1] + dc
        return abs(r - world.novice[0]) + abs(c - world.novice[1]) <= 1

    def _next_action(self, world: HouseholdWorld, plan: Intervention | None) -> str:
        assert world.caregiver is not None
        if plan is None:
            return "wait"
        if plan.kind in ("block", "stand-by"):
            return "wait" if world.caregiver == plan.target else self._step_toward(world, plan.target)
        if not world.carrying:
            if world.table_for("get") == plan.target:
                return "get"
            side, _ = self._side(world, plan.target, "get", world.caregiver)
        else:
            assert plan.destination is not None
            if world.table_for("place") == plan.destination:
                return "place"
            side, _ = self._side(world, plan.destination, "place", world.caregiver)
        return "wait" if side is None else self._step_toward(world, side)

    def decide(self, world: HouseholdWorld) -> Decision:
        """Choose this turn's actions (the world is not changed; apply them with ``act_caregiver``).

        Raises:
            SafetyError: when the world has no caregiver.
        """
        if world.caregiver is None:
            raise SafetyError("the world has no caregiver")
        p_safe = self.safety.probability
        expected = self.danger.expected_damage(world, p_safe)
        self.intervention = self.choose(world, p_safe)
        scratch = world.copy()
        actions: list[str] = []
        for _ in range(self.actions_per_step):
            action = self._next_action(scratch, self.intervention)
            scratch.act_caregiver(action)
            actions.append(action)
            if action == "place":
                self.intervention = self.choose(scratch, p_safe)
        return Decision(tuple(actions), self.intervention, p_safe, expected)

