"""Where pieces sit on the snap board, and which placements the toy allows.

The board is a grid of points ``(col, row)`` with ``0 <= col < columns`` and ``0 <= row < rows``. A piece
lies along a row or a column at a *level* (0 on the board, 1 on top of level-0 pieces, …). Our rules:

(a) every point of the piece's footprint (first snap to last) is on the board;
(b) two pieces at the same level never share a point: pieces cannot connect side by side (§3.2.9);
(c) a piece at level ``h >= 1`` rests its first and last snaps on snaps of pieces at level ``h - 1``;
(d) at level ``h >= 1`` a point of the footprint that is not one of the piece's own snaps must not lie
    above a snap at level ``h - 1``: the stud would push into the piece's body;
(e) a piece id is on the board at most once.

Snaps at the same point on consecutive levels are connected; that is the only way pieces connect. A
:class:`Board` is immutable and always valid: :meth:`Board.place` refuses a bad placement and
:meth:`Board.remove` refuses to take away a piece another one rests on.

>>> board = Board(3, 3).place("b1", "battery", BoardPose(0, 0))
>>> board.can_place("w1", "wire3", BoardPose(1, 0, rotation=1))
"overlaps 'b1' at (1, 0) on level 0"
>>> board.snap_at((2, 0), 0)
('b1', 1)
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from functools import cached_property, lru_cache

from supportive.envs.circuits.pieces import PieceType, piece_type
from supportive.errors import CircuitError

__all__ = ["DIRECTIONS", "Board", "BoardPose", "Placement", "Point"]

Point = tuple[int, int]
"""A grid point as (col, row)."""

DIRECTIONS: tuple[Point, ...] = ((1, 0), (0, 1), (-1, 0), (0, -1))
"""The step along a piece's axis for rotations 0 (+col), 1 (+row), 2 (−col) and 3 (−row)."""


def _kind(kind: str | PieceType) -> PieceType:
    return kind if isinstance(kind, PieceType) else piece_type(kind)


@dataclass(frozen=True)
class BoardPose:
    """Where a piece lies: its first snap's point, the direction of its axis, and its height.

    Args:
        col: Column of the first snap.
        row: Row of the first snap.
        rotation: Quarter turns, 0 to 3 (see :data:`DIRECTIONS`).
        level: Height in the stack, 0 on the board.

    Raises:
        CircuitError: On a rotation outside 0–3 or a negative level.

    >>> BoardPose(2, 0, rotation=1).snap_points("battery")
    ((2, 0), (2, 2))
    """

    col: int
    row: int
    rotation: int = 0
    level: int = 0

    def __post_init__(self) -> None:
        if self.rotation not in (0, 1, 2, 3):
            raise CircuitError(f"rotation must be 0, 1, 2 or 3 quarter turns, got {self.rotation!r}")
        if not isinstance(self.level, int) or self.level < 0:
            raise CircuitError(f"level must be an integer 0 or more, got {self.level!r}")

    def point(self, offset: int) -> Point:
        """The grid point ``offset`` steps along the axis from the first snap."""
        dc, dr = DIRECTIONS[self.rotation]
        return (self.col + offset * dc, self.row + offset * dr)

    def snap_points(self, kind: str | PieceType) -> tuple[Point, ...]:
        """The points of a piece's snaps, in the order of its terminals."""
        return _points(self.col, self.row, self.rotation, _kind(kind).snaps)

    def footprint(self, kind: str | PieceType) -> tuple[Point, ...]:
        """Every point the piece covers, first snap to last."""
        return _points(self.col, self.row, self.rotation, _kind(kind).reach)


@lru_cache(maxsize=65536)
def _points(col: int, row: int, rotation: int, offsets: tuple[int, ...]) -> tuple[Point, ...]:
    """The points ``offsets`` steps along the axis of a piece whose first snap is at ``(col, row)``
    (remembered: planners ask for the same ones often; keyed by plain numbers, which hash fast)."""
    dc, dr = DIRECTIONS[rotation]
    return tuple((col + offset * dc, row + offset * dr) for offset in offsets)


@dataclass(frozen=True)
class Placement:
    """A piece on the board.

    Args:
        piece: The piece's instance id (``"b1"``).
        kind: Its catalogue name (``"battery"``).
        pose: Where it lies.

    Raises:
        CircuitError: On an empty id or an unknown kind.
    """

    piece: str
    kind: str
    pose: BoardPose

    def __post_init__(self) -> None:
        if not isinstance(self.piece, str) or not self.piece:
            raise CircuitError(f"a piece id must be a non-empty string, got {self.piece!r}")
        piece_type(self.kind)

    @cached_property
    def piece_type(self) -> PieceType:
        """The kind of piece."""
        return piece_type(self.kind)

    @property
    def level(self) -> int:
        """The piece's height in the stack."""
        return self.pose.level

    @cached_property
    def snap_points(self) -> tuple[Point, ...]:
        """The points of its snaps, in terminal order."""
        return self.pose.snap_points(self.piece_type)

    @cached_property
    def footprint(self) -> tuple[Point, ...]:
        """Every point it covers."""
        return self.pose.footprint(self.piece_type)


class Board:
    """An immutable, always valid snap board.

    Args:
        columns: Number of columns (1 or more).
        rows: Number of rows (1 or more).
        placements: Pieces already on it, in any order.

    Raises:
        CircuitError: On a non-positive size or placements that break a rule (the message says which).

    Two boards are equal when they have the same size and the same placements, whatever the order.
    """

    __slots__ = ("_by_id", "_cells", "_columns", "_hash", "_rows", "_snaps")

    def __init__(self, columns: int, rows: int, placements: Iterable[Placement] = ()) -> None:
        for name, value in (("columns", columns), ("rows", rows)):
            if not isinstance(value, int) or value < 1:
                raise CircuitError(f"a board needs {name} of 1 or more, got {value!r}")
        self._columns = columns
        self._rows = rows
        self._by_id: dict[str, Placement] = {}
        self._cells: dict[tuple[int, Point], str] = {}
        self._snaps: dict[tuple[int, Point], tuple[str, int]] = {}
        self._hash: int | None = None
        # Lower levels first, so every support is in place before what rests on it.
        for placement in sorted(placements, key=lambda p: p.level):
            reason = self.can_place(placement.piece, placement.kind, placement.pose)
            if reason is not None:
                raise CircuitError(_refusal(placement, reason))
            self._add(placement)

    @property
    def columns(self) -> int:
        """Number of columns."""
        return self._columns

    @property
    def rows(self) -> int:
        """Number of rows."""
        return self._rows

    @property
    def placements(self) -> tuple[Placement, ...]:
        """The pieces on the board, in the order they were added (lower levels first on construction)."""
        return tuple(self._by_id.values())

    def __len__(self) -> int:
        return len(self._by_id)

    def __iter__(self) -> Iterator[Placement]:
        return iter(self._by_id.values())

    def __contains__(self, piece: object) -> bool:
        return piece in self._by_id

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Board):
            return NotImplemented
        return (self._columns, self._rows, self._by_id) == (other._columns, other._rows, other._by_id)

    def __hash__(self) -> int:
        if self._hash is None:
            self._hash = hash((self._columns, self._rows, frozenset(self._by_id.values())))
        return self._hash

    def __repr__(self) -> str:
        return f"Board({self._columns}, {self._rows}, {self.placements!r})"

    def placement(self, piece: str) -> Placement:
        """The placement of ``piece``.

        Raises:
            CircuitError: When the piece is not on the board.
        """
        try:
            return self._by_id[piece]
        except KeyError:
            raise CircuitError(f"piece {piece!r} is not on the board") from None

    def on_board(self, point: Point) -> bool:
        """Whether ``point`` is a grid point of the board."""
        col, row = point
        return 0 <= col < self._columns and 0 <= row < self._rows

    def piece_at(self, point: Point, level: int) -> str | None:
        """The piece covering ``point`` at ``level``, if any."""
        return self._cells.get((level, point))

    def snap_at(self, point: Point, level: int) -> tuple[str, int] | None:
        """The piece with a snap at ``point`` on ``level`` and that snap's index, if any."""
        return self._snaps.get((level, point))

    def dependents(self, piece: str) -> tuple[str, ...]:
        """The pieces that rest an end snap on ``piece`` (they must go before it can), sorted.

        Raises:
            CircuitError: When the piece is not on the board.
        """
        placement = self.placement(piece)
        above = placement.level + 1
        found = set()
        for point in placement.snap_points:
            top = self._snaps.get((above, point))
            if top is not None and top[1] in (0, len(self._by_id[top[0]].piece_type.snaps) - 1):
                found.add(top[0])
        return tuple(sorted(found))

    def can_place(self, piece: str, kind: str, pose: BoardPose) -> str | None:
        """Why ``piece`` of ``kind`` cannot go at ``pose``, or None when it can.

        Raises:
            CircuitError: On an unknown kind.
        """
        if piece in self._by_id:
            return f"{piece!r} is already on the board"
        ptype = piece_type(kind)
        level = pose.level
        snaps = pose.snap_points(ptype)
        footprint = pose.footprint(ptype)
        for point in footprint:
            if not self.on_board(point):
                return f"off the board at {point}"
        for point in footprint:
            other = self._cells.get((level, point))
            if other is not None:
                return f"overlaps {other!r} at {point} on level {level}"
        snap_set = set(snaps)
        if level > 0:
            for point in (snaps[0], snaps[-1]):
                if (level - 1, point) not in self._snaps:
                    return f"unsupported: no snap on level {level - 1} under its snap at {point}"
            for point in footprint:
                if point not in snap_set and (level - 1, point) in self._snaps:
                    other = self._snaps[(level - 1, point)][0]
                    return f"blocked by the stud of {other!r} at {point} on level {level - 1}"
        for point in snaps:
            other = self._cells.get((level + 1, point))
            if other is not None and (level + 1, point) not in self._snaps:
                return f"its stud at {point} would block {other!r} on level {level + 1}"
        return None

    def place(self, piece: str, kind: str, pose: BoardPose) -> Board:
        """A board with ``piece`` of ``kind`` added at ``pose``.

        Raises:
            CircuitError: When the placement breaks a rule; the message gives the reason.
        """
        placement = Placement(piece, kind, pose)
        reason = self.can_place(piece, kind, pose)
        if reason is not None:
            raise CircuitError(_refusal(placement, reason))
        board = self._copy()
        board._add(placement)
        return board

    def remove(self, piece: str) -> Board:
        """A board without ``piece``.

        Raises:
            CircuitError: When the piece is not on the board, or other pieces rest on it.
        """
        resting = self.dependents(piece)
        if resting:
            names = ", ".join(repr(name) for name in resting)
            raise CircuitError(
                f"cannot remove {piece!r}: {names} rest{'s' if len(resting) == 1 else ''} on it"
            )
        board = Board(self._columns, self._rows)
        for placement in self._by_id.values():
            if placement.piece != piece:
                board._add(placement)
        return board

    def _copy(self) -> Board:
        board = Board(self._columns, self._rows)
        board._by_id = dict(self._by_id)
        board._cells = dict(self._cells)
        board._snaps = dict(self._snaps)
        return board

    def _add(self, placement: Placement) -> None:
        level = placement.level
        self._by_id[placement.piece] = placement
        for point in placement.footprint:
            self._cells[(level, point)] = placement.piece
        for index, point in enumerate(placement.snap_points):
            self._snaps[(level, point)] = (placement.piece, index)
        self._hash = None


def _refusal(placement: Placement, reason: str) -> str:
    pose = placement.pose
    where = f"({pose.col}, {pose.row}) rotation {pose.rotation} level {pose.level}"
    return f"cannot place {placement.piece!r} ({placement.kind}) at {where}: {reason}"
