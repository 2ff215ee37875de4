"""Planning circuits: which pieces go where on the board so that the goal holds (the lead's symbolic
planner, and the source of the known plan set Π_T).

A circuit here is one closed loop of pieces around a rectangle whose lower-left corner is the board's
``start`` point, walked counter-clockwise: along +col, then +row, −col and −row. Each piece lies along the
side it is on, its first snap where the previous piece ended; the pieces' levels alternate 0, 1, 0, …,
because two pieces meet only snap on snap (so a loop has an even number of pieces). Polar pieces lie with the
walk: a battery − before +, an LED anode before cathode, so that current flowing the way of the walk drives
them all forwards. The search proposes loops; the goal's circuit analysis decides (every loop returned meets
the goal on a real board).

The search is a depth-first search over the next piece. Its order is the planner's heuristic: by default the
catalogue's order (to enumerate Π_T); a greedy lead orders candidates by how near the board the nearest piece
of that kind lies and how far it must be turned (§3.2.9.2: "pieces most proximal to the board in their current
orientations, before branching out"). ``nodes`` counts the pieces it tried — its planning effort.

>>> from supportive.envs.circuits.goals import CircuitGoal
>>> search = LayoutSearch(4, 4, CircuitGoal(batteries_in_series=2, switch_controls=True))
>>> loop = next(search.loops({"battery": 2, "switch": 1, "led": 1}))
>>> [piece.kind for piece in loop.pieces], search.nodes
(['battery', 'battery', 'led', 'switch'], 4)
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from functools import cache

from supportive.envs.circuits.board import DIRECTIONS, Board, BoardPose, Placement, Point
from supportive.envs.circuits.goals import CircuitGoal
from supportive.envs.circuits.pieces import PIECE_TYPES, piece_type
from supportive.errors import CircuitError, PlanningError, SearchLimitError

__all__ = ["LayoutSearch", "Loop", "Segment", "required_pieces"]

Order = Callable[[str, BoardPose], float]
"""How a planner ranks placing a piece of a kind at a pose (lower first)."""


@dataclass(frozen=True)
class Segment:
    """One piece of a loop: its kind and where it lies."""

    kind: str
    pose: BoardPose


@dataclass(frozen=True)
class Loop:
    """A closed loop of pieces, in walking order."""

    pieces: tuple[Segment, ...]

    @property
    def build_order(self) -> tuple[Segment, ...]:
        """The order to put the pieces on the board: level 0 first (a piece rests on the ones below)."""
        return tuple(sorted(self.pieces, key=lambda s: s.pose.level))

    def board(self, columns: int, rows: int) -> Board:
        """The loop on an empty board, pieces named ``p0``, ``p1``, … in build order.

        Raises:
            CircuitError: when a piece breaks a placement rule.
        """
        placements = (Placement(f"p{index}", s.kind, s.pose) for index, s in enumerate(self.build_order))
        return Board(columns, rows, placements)


def required_pieces(goal: CircuitGoal) -> Counter[str]:
    """The pieces any circuit meeting ``goal`` contains: the light, the batteries, the switch."""
    need: Counter[str] = Counter({goal.light: 1})
    if goal.batteries_in_series:
        need["battery"] = goal.batteries_in_series
    if goal.switch_controls:
        need["switch"] = 1
    return need


@dataclass
class _Walk:
    """The search's position: where the walk is and what it has laid."""

    point: Point
    side: int
    length: int
    sides: list[int]
    pieces: list[Segment]
    used: Counter[str]
    visited: set[Point]
    reused: int = 0


@cache
def _pose(col: int, row: int, rotation: int, level: int) -> BoardPose:
    """The pose, made once: the search asks for the same few hundred poses again and again (a loop's
    pieces lie at levels 0 and 1, so a board has ``columns × rows × 8`` of them)."""
    return BoardPose(col, row, rotation, level)


class LayoutSearch:
    """Depth-first search for loops that meet a circuit goal on a board.

    Args:
        columns: Board columns.
        rows: Board rows.
        goal: What the circuit must do.
        start: The loop's lower-left corner.
        max_pieces: The most pieces a loop may have (even).
        node_limit: Give up after trying this many pieces in one call of :meth:`loops` (raising
            :class:`~supportive.errors.SearchLimitError`).

    Attributes:
        nodes: Pieces tried by the last call of :meth:`loops` (so far, while it is being iterated).
    """

    def __init__(
        self,
        columns: int,
        rows: int,
        goal: CircuitGoal,
        *,
        start: Point = (0, 0),
        max_pieces: int = 8,
        node_limit: int = 200_000,
    ) -> None:
        if max_pieces < 4:
            raise PlanningError(f"max_pieces must be at least 4, got {max_pieces}")
        if not (0 <= start[0] < columns and 0 <= start[1] < rows):
            raise PlanningError(f"start {start} is not on a {columns} × {rows} board")
        self.columns = columns
        self.rows = rows
        self.goal = goal
        self.start = start
        self.max_pieces = max_pieces - max_pieces % 2
        self.node_limit = node_limit
        self.need = required_pieces(goal)
        self.nodes = 0
        # Whether a loop meets the goal, by its kinds in walking order. A loop's pieces meet only end to end
        # (the walk never comes back to a point it covered but to close), snap on snap, each lying with the
        # walk (polar pieces forwards): one ring of them in that order, whatever the rectangle, so its circuit
        # and the goal's verdict depend on that sequence alone; the board is still built, for its rules.
        self._verdicts: dict[tuple[str, ...], bool] = {}

    def loops(
        self,
        inventory: Mapping[str, int],
        board: Board | None = None,
        order: Order | None = None,
    ) -> Iterator[Loop]:
        """Every loop meeting the goal that the pieces allow, in the search's order.

        Args:
            inventory: How many pieces of each kind are at hand (not counting those on ``board``).
            board: Pieces already placed; a loop must contain every one of them, as it lies.
            order: The planner's ranking of candidate placements (default: catalogue order, straight on
                before turning).

        Raises:
            CircuitError: for an unknown kind in the inventory.
        """
        for kind in inventory:
            piece_type(kind)
        self.nodes = 0
        pieces = () if board is None else tuple(board)
        placed = {(p.pose.level, point): p for p in pieces for point in p.footprint}
        fixed = {(p.kind, p.pose) for p in pieces}
        catalogue = {kind: float(index) for index, kind in enumerate(PIECE_TYPES)}

        def by_catalogue(kind: str, pose: BoardPose) -> float:
            return catalogue[kind]

        rank = order or by_catalogue
        kinds = sorted(set(inventory) | {kind for kind, _ in fixed})
        walk = _Walk(self.start, 0, 0, [], [], Counter(), {self.start})
        yield from self._extend(walk, dict(inventory), kinds, placed, fixed, rank)

    def _extend(
        self,
        walk: _Walk,
        inventory: dict[str, int],
        kinds: list[str],
        placed: Mapping[tuple[int, Point], object],
        fixed: set[tuple[str, BoardPose]],
        rank: Order,
    ) -> Iterator[Loop]:
        """The loops that go on from ``walk``; ``kinds``: every kind the search may lay, sorted."""
        count = len(walk.pieces)
        if count >= self.max_pieces:
            return
        used = walk.used
        missing = sum(max(0, n - used[kind]) for kind, n in self.need.items())
        if missing > self.max_pieces - count:
            return
        level = count % 2
        turns = (0, 1) if count and walk.length and walk.side < 3 else (0,)
        poses = [_pose(walk.point[0], walk.point[1], walk.side + turn, level) for turn in turns]
        candidates = sorted(
            (rank(kind, poses[turn]), turn, kind)
            for turn in turns
            for kind in kinds
            if inventory.get(kind, 0) > 0 or (kind, poses[turn]) in fixed
        )
        for _, turn, kind in candidates:
            side = walk.side + turn
            pose = poses[turn]
            is_fixed = bool(fixed) and (kind, pose) in fixed
            if inventory.get(kind, 0) <= 0 and not is_fixed:
                continue
            step = self._step(walk, turn, kind, pose, placed, is_fixed)
            if step is None:
                continue
            self.nodes += 1
            if self.nodes > self.node_limit:
                raise SearchLimitError(f"the circuit search tried {self.node_limit:,} pieces, its limit")
            end, length, closed, footprint = step
            if not is_fixed:
                inventory[kind] -= 1
            walk.pieces.append(Segment(kind, pose))
            used[kind] += 1
            new_points = [pt for pt in footprint[1:] if pt != self.start or not closed]
            walk.visited.update(new_points)
            saved = (walk.point, walk.side, walk.length, walk.sides, walk.reused)
            walk.point, walk.side, walk.length = end, side, length
            if turn:
                walk.sides = [*walk.sides, saved[2]]
            walk.reused += is_fixed
            if closed:
                loop = self._finish(walk, fixed)
                if loop is not None:
                    yield loop
            else:
                yield from self._extend(walk, inventory, kinds, placed, fixed, rank)
            walk.point, walk.side, walk.length, walk.sides, walk.reused = saved
            walk.visited.difference_update(new_points)
            used[kind] -= 1
            walk.pieces.pop()
            if not is_fixed:
                inventory[kind] += 1

    def _step(
        self,
        walk: _Walk,
        turn: int,
        kind: str,
        pose: BoardPose,
        placed: Mapping[tuple[int, Point], object],
        is_fixed: bool,
    ) -> tuple[Point, int, bool, tuple[Point, ...]] | None:
        """Where laying ``kind`` at ``pose`` ends the walk, the length of the side it is on, whether it closes
        the loop, and the points the piece covers; None when it cannot go there. (The side before the
        turn, ``walk.length``, is not yet in ``walk.sides``; the sides this compares with are.)"""
        span = PIECE_TYPES[kind].span
        side = pose.rotation
        length = span if turn else walk.length + span
        if side >= 2 and length > walk.sides[side - 2]:
            return None  # longer than the opposite side
        dc, dr = DIRECTIONS[side]
        end = (walk.point[0] + span * dc, walk.point[1] + span * dr)
        if not (0 <= end[0] < self.columns and 0 <= end[1] < self.rows):
            return None
        closed = side == 3 and length == walk.sides[1]
        if closed and (end != self.start or (len(walk.pieces) + 1) % 2):
            return None
        footprint = pose.footprint(kind)
        visited = walk.visited
        for point in footprint[1:]:
            if point in visited and not (closed and point == self.start and point == footprint[-1]):
                return None
        if placed and not is_fixed and any((pose.level, point) in placed for point in footprint):
            return None
        return end, length, closed, footprint

    def _finish(self, walk: _Walk, fixed: set[tuple[str, BoardPose]]) -> Loop | None:
        """The walk as a loop, if it holds every placed piece, has what the goal needs and meets it."""
        if walk.reused != len(fixed):
            return None
        if any(walk.used[kind] < n for kind, n in self.need.items()):
            return None
        loop = Loop(tuple(walk.pieces))
        try:
            board = loop.board(self.columns, self.rows)
        except CircuitError:
            return None
        kinds = tuple(segment.kind for segment in loop.pieces)
        meets = self._verdicts.get(kinds)
        if meets is None:
            meets = self._verdicts[kinds] = self.goal.satisfied(board)
        return loop if meets else None
