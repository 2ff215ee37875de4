"""The circuit-building world of §3.2.9 as a tabletop world: a snap board that only the lead may build on,
pieces scattered on a shared table, and a goal the finished circuit must meet.

Pieces lie on the table as rectangles ``span · pitch + 2`` cm long and 3 cm wide, turned in quarter turns;
a piece's table rotation uses the board's convention (its first snap towards −x for rotation 0), so putting
it on the board needs no turn when the two rotations agree (a half turn is free for non-polar pieces).
The lead's operator installs a piece of a kind at a board pose; the support agent may pick pieces up and put
them down on the table or in its tray, and P forbids it ``on_board(*)``.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from supportive.envs.circuits.board import Board, BoardPose
from supportive.envs.circuits.goals import CircuitGoal
from supportive.envs.circuits.pieces import PIECE_TYPES, piece_type
from supportive.envs.tabletop.arms import ArmModel
from supportive.envs.tabletop.geometry import Point, Rect
from supportive.envs.tabletop.items import Item, ItemType, TablePose
from supportive.envs.tabletop.layout import TableLayout
from supportive.envs.tabletop.state import Status, TabletopState
from supportive.envs.tabletop.world import TabletopWorld
from supportive.errors import PlanningError

__all__ = ["BoardGeometry", "CircuitState", "CircuitWorld", "circuit_item_types"]

CircuitState = TabletopState[Board]
"""A state of the circuit world: the table, the board, the hands."""

_PIECE_WIDTH = 3.0
_PIECE_MARGIN = 2.0
_ARROWS = ("→", "↑", "←", "↓")
_MEMORY = 100_000  # boards remembered before the memory is cleared


@dataclass(frozen=True)
class BoardGeometry:
    """Where the snap board lies on the table.

    Attributes:
        columns: Grid columns (along the table's x).
        rows: Grid rows (along y, row 0 nearest the lead).
        pitch: Distance between neighbouring grid points, cm.
        origin: Table position of grid point (0, 0), cm.
    """

    columns: int = 6
    rows: int = 5
    pitch: float = 4.0
    origin: Point = (44.0, 8.0)

    def __post_init__(self) -> None:
        if self.columns < 2 or self.rows < 2 or self.pitch <= 0:
            raise PlanningError("a board needs at least 2 columns and 2 rows and a positive pitch")

    def point(self, col: float, row: float) -> Point:
        """The table position of a (possibly fractional) grid point."""
        return (self.origin[0] + col * self.pitch, self.origin[1] + row * self.pitch)

    @property
    def area(self) -> Rect:
        """The board on the table (its grid plus a margin of half a pitch)."""
        x0, y0 = self.point(-0.5, -0.5)
        x1, y1 = self.point(self.columns - 0.5, self.rows - 0.5)
        return Rect(x0, y0, x1, y1)


def circuit_item_types(pitch: float) -> dict[str, ItemType]:
    """Every catalogue piece as an object on the table, sized for a board of ``pitch``."""
    return {
        name: ItemType(name, kind.span * pitch + _PIECE_MARGIN, _PIECE_WIDTH, not kind.polar, kind.text)
        for name, kind in PIECE_TYPES.items()
    }


class CircuitWorld(TabletopWorld[Board, BoardPose]):
    """Circuit building at a shared table (§3.2.9.1).

    Args:
        board: Where the board lies.
        goal: What the circuit must do.
        layout: The table (its goal area must hold the board).
        pieces: Every piece: id, kind and where it lies on the table at the start.
        lead: The lead's arm.
        support: The support agent's arm.
        prohibited: P (default ``on_board(*)``).
    """

    goal_predicate = "on_board"

    def __init__(
        self,
        board: BoardGeometry,
        goal: CircuitGoal,
        layout: TableLayout,
        pieces: Sequence[tuple[str, str, TablePose]],
        lead: ArmModel,
        support: ArmModel,
        prohibited: Sequence[str] | None = None,
    ) -> None:
        if not layout.goal_area.encloses(board.area):
            raise PlanningError(
                f"the board {board.area} is not inside the table's goal area {layout.goal_area}"
            )
        self.board = board
        self.goal = goal
        self.pieces = tuple(pieces)
        items = [Item(piece_id, kind) for piece_id, kind, _ in pieces]
        for _, kind, _ in pieces:
            piece_type(kind)
        initial = TabletopState(
            tuple(pose for _, _, pose in pieces),
            tuple(Status.TABLE for _ in pieces),
            Board(board.columns, board.rows),
            (lead.home, support.home),
        )
        super().__init__(layout, circuit_item_types(board.pitch), items, initial, lead, support, prohibited)
        for index, (piece_id, _, pose) in enumerate(pieces):
            if not self.is_free(initial, index, pose):
                raise PlanningError(
                    f"piece {piece_id} at ({pose.x:g}, {pose.y:g}) overlaps the board or another piece, or is off the table"
                )
        self._reached: dict[Board, bool] = {}
        self._accepts: dict[tuple[Board, str, BoardPose], bool] = {}
        self._boards: dict[tuple[Board, int, BoardPose], Board] = {}

    def with_speeds(self, lead: float, support: float) -> CircuitWorld:
        """The same world with the lead and the support agent at these fractions of full speed."""
        return CircuitWorld(
            self.board,
            self.goal,
            self.layout,
            self.pieces,
            self.lead_arm.slowed(lead),
            self.support_arm.slowed(support),
            self.prohibited,
        )

    def target_point(self, target: BoardPose) -> Point:
        """The table position of the target's first snap: where the lead's hand puts a piece down (the
        piece's length is left out of the estimate)."""
        return self.board.point(target.col, target.row)

    def target_rotation(self, target: BoardPose) -> int:
        """The board rotation is the table rotation."""
        return target.rotation

    def can_receive(self, goal: Board, kind: str, target: BoardPose) -> bool:
        """Whether the board accepts a piece of ``kind`` at ``target`` now (remembered per board)."""
        key = (goal, kind, target)
        accepted = self._accepts.get(key)
        if accepted is None:
            accepted = self._accepts[key] = goal.can_place("\0candidate", kind, target) is None
        return accepted

    def receive(self, goal: Board, item: int, target: BoardPose) -> Board:
        """The board with the piece placed (remembered: estimating many plans in many hypothetical
        environments builds the same boards again and again, and the support agent never changes them)."""
        key = (goal, item, target)
        board = self._boards.get(key)
        if board is None:
            if len(self._boards) > _MEMORY:
                self._boards.clear()
                self._accepts.clear()
            piece = self.items[item]
            board = self._boards[key] = goal.place(piece.id, piece.kind, target)
        return board

    def can_release(self, goal: Board, item: int) -> bool:
        """Nothing rests on the piece."""
        return not goal.dependents(self.items[item].id)

    def release(self, goal: Board, item: int) -> Board:
        """The board without the piece."""
        return goal.remove(self.items[item].id)

    def installed(self, goal: Board) -> Mapping[BoardPose, str]:
        """Each placed piece's pose and kind."""
        return {placement.pose: placement.kind for placement in goal}

    def goal_reached(self, state: TabletopState[Board]) -> bool:
        """Whether the board meets the circuit goal (remembered per board)."""
        board = state.goal
        reached = self._reached.get(board)
        if reached is None:
            reached = self._reached[board] = self.goal.satisfied(board)
        return reached

    def describe_target(self, target: BoardPose) -> str:
        """``(col, row) → level 0``."""
        return f"({target.col}, {target.row}) {_ARROWS[target.rotation]} level {target.level}"

    def inventory(self, state: TabletopState[Board]) -> Counter[str]:
        """The pieces the lead can count on, by kind: on the table within its reach, or in the support
        agent's hand (it will put them down)."""
        return Counter(
            self.items[i].kind
            for i, status in enumerate(state.status)
            if status is Status.HELD_SUPPORT or (status is Status.TABLE and self.reachable(state, "lead", i))
        )
