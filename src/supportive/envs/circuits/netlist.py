"""The electrical connectivity of a board: which snaps form one conductor (a *net*), and what lies between nets.

Two rules join snaps into nets (union-find): all snaps of one wire are one conductor, and snaps at the same
point on consecutive levels touch. Every other piece is an :class:`Element` between the nets of its two
terminals, in the order of its terminals: ``(-, +)`` for a battery, ``(anode, cathode)`` for an LED.

Nets are numbered deterministically: in the order of their smallest snap, snaps ordered by
``(col, row, level)``. Elements are ordered by piece id. Neither depends on the order pieces were placed.

>>> from supportive.envs.circuits.board import Board, BoardPose
>>> board = Board(3, 1).place("b1", "battery", BoardPose(0, 0)).place("w1", "wire3", BoardPose(0, 0, level=1))
>>> circuit = netlist(board)
>>> circuit.net_count, circuit.elements[0].nets
(1, (0, 0))
"""

from __future__ import annotations

from dataclasses import dataclass

from supportive.envs.circuits.board import Board, Point
from supportive.envs.circuits.pieces import ElementKind, PieceType
from supportive.errors import CircuitError

__all__ = ["Element", "Netlist", "Terminal", "netlist"]


@dataclass(frozen=True, order=True)
class Terminal:
    """One snap of one piece.

    Args:
        point: Where the snap is.
        level: Its height.
        piece: The piece's id.
        index: Which of the piece's snaps it is.
        name: The terminal's name (``"+"``, ``"anode"``, ``"w"``, …).
    """

    point: Point
    level: int
    piece: str
    index: int
    name: str


@dataclass(frozen=True)
class Element:
    """A non-wire piece between two nets.

    Args:
        piece: The piece's id.
        piece_type: Its kind.
        nets: The nets of its first and second terminal: ``(-, +)`` for a battery, ``(anode, cathode)`` for
            an LED.
    """

    piece: str
    piece_type: PieceType
    nets: tuple[int, int]

    @property
    def element(self) -> ElementKind:
        """What it is electrically."""
        return self.piece_type.element


@dataclass(frozen=True)
class Netlist:
    """Nets and the elements between them.

    Args:
        nets: Each net's snaps, sorted.
        elements: The non-wire pieces, by piece id.
    """

    nets: tuple[tuple[Terminal, ...], ...]
    elements: tuple[Element, ...]

    @property
    def net_count(self) -> int:
        """How many nets there are."""
        return len(self.nets)

    def element(self, piece: str) -> Element:
        """The element of ``piece``.

        Raises:
            CircuitError: When ``piece`` is not a non-wire piece of this netlist.
        """
        for element in self.elements:
            if element.piece == piece:
                return element
        raise CircuitError(f"piece {piece!r} is not an element (a non-wire piece) of this circuit")

    def net(self, piece: str, terminal: str) -> int:
        """The net of ``piece``'s terminal called ``terminal``.

        Raises:
            CircuitError: When the piece has no such terminal.
        """
        for index, snaps in enumerate(self.nets):
            for snap in snaps:
                if snap.piece == piece and snap.name == terminal:
                    return index
        raise CircuitError(f"there is no terminal {terminal!r} of piece {piece!r} on the board")


def netlist(board: Board) -> Netlist:
    """The nets of ``board`` and the elements between them."""
    parent: dict[tuple[int, Point], tuple[int, Point]] = {}

    def find(site: tuple[int, Point]) -> tuple[int, Point]:
        root = site
        while parent[root] != root:
            root = parent[root]
        while parent[site] != root:
            parent[site], site = root, parent[site]
        return root

    def union(a: tuple[int, Point], b: tuple[int, Point]) -> None:
        ra, rb = find(a), find(b)
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)

    terminals: list[Terminal] = []
    for placement in board:
        ptype = placement.piece_type
        level = placement.level
        for index, point in enumerate(placement.snap_points):
            parent[(level, point)] = (level, point)
            terminals.append(Terminal(point, level, placement.piece, index, ptype.terminals[index]))
    for placement in board:
        level = placement.level
        points = placement.snap_points
        if placement.piece_type.element == "wire":
            for point in points[1:]:
                union((level, points[0]), (level, point))
        for point in points:
            if (level + 1, point) in parent:
                union((level, point), (level + 1, point))
    groups: dict[tuple[int, Point], list[Terminal]] = {}
    for terminal in sorted(terminals, key=lambda t: (t.point, t.level, t.piece, t.index)):
        groups.setdefault(find((terminal.level, terminal.point)), []).append(terminal)
    nets = tuple(tuple(group) for group in groups.values())
    net_of = {(t.piece, t.index): number for number, net in enumerate(nets) for t in net}
    elements = tuple(
        Element(p.piece, p.piece_type, (net_of[(p.piece, 0)], net_of[(p.piece, 1)]))
        for p in sorted(board, key=lambda p: p.piece)
        if p.piece_type.element != "wire"
    )
    return Netlist(nets, elements)
