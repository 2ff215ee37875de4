"""Pieces, poses, placement rules and nets, by hand."""

from __future__ import annotations

import re

import pytest

from supportive.envs.circuits import PIECE_TYPES, Board, BoardPose, Placement, netlist, piece_type
from supportive.errors import CircuitError


def test_catalogue_has_the_agreed_pieces() -> None:
    assert set(PIECE_TYPES) == {
        "wire2",
        "wire3",
        "wire4",
        "wire5",
        "battery",
        "led",
        "switch",
        "resistor",
        "lamp",
    }
    for n in range(2, 6):
        wire = piece_type(f"wire{n}")
        assert (wire.element, wire.snaps, wire.terminals, wire.span) == (
            "wire",
            tuple(range(n)),
            ("w",) * n,
            n - 1,
        )
        assert wire.text == f"a {n}-snap wire"
    assert piece_type("battery").terminals == ("-", "+")
    assert piece_type("led").terminals == ("anode", "cathode")
    assert {name for name, kind in PIECE_TYPES.items() if kind.polar} == {"battery", "led"}
    assert all(PIECE_TYPES[name].snaps == (0, 2) for name in ("battery", "led", "switch", "resistor", "lamp"))


def test_unknown_kind_lists_the_known_ones() -> None:
    with pytest.raises(
        CircuitError, match=r"unknown piece kind 'capacitor'.*wire5, battery, led, switch, resistor, lamp"
    ):
        piece_type("capacitor")
    with pytest.raises(CircuitError, match="unknown piece kind"):
        Placement("c1", "capacitor", BoardPose(0, 0))


@pytest.mark.parametrize(
    ("rotation", "snaps", "footprint"),
    [
        (0, ((1, 1), (3, 1)), ((1, 1), (2, 1), (3, 1))),
        (1, ((1, 1), (1, 3)), ((1, 1), (1, 2), (1, 3))),
        (2, ((1, 1), (-1, 1)), ((1, 1), (0, 1), (-1, 1))),
        (3, ((1, 1), (1, -1)), ((1, 1), (1, 0), (1, -1))),
    ],
)
def test_pose_points_follow_the_rotation(
    rotation: int, snaps: tuple[tuple[int, int], ...], footprint: tuple[tuple[int, int], ...]
) -> None:
    pose = BoardPose(1, 1, rotation)
    assert pose.snap_points("battery") == snaps
    assert pose.footprint("battery") == footprint
    assert pose.snap_points("wire3") == footprint


@pytest.mark.parametrize(("rotation", "level"), [(4, 0), (-1, 0), (0, -1)])
def test_bad_pose_is_refused(rotation: int, level: int) -> None:
    with pytest.raises(CircuitError):
        BoardPose(0, 0, rotation, level)


@pytest.mark.parametrize(("columns", "rows"), [(0, 3), (3, 0), (-2, 2)])
def test_bad_board_size_is_refused(columns: int, rows: int) -> None:
    with pytest.raises(CircuitError, match="1 or more"):
        Board(columns, rows)


def _level1_battery_on_wires() -> Board:
    """Two level-0 wires at columns 0 and 2 carry a battery on level 1 across the gap at column 1."""
    board = (
        Board(4, 3).place("w1", "wire2", BoardPose(0, 0, rotation=1)).place("w2", "wire2", BoardPose(2, 0, 1))
    )
    return board.place("b1", "battery", BoardPose(0, 0, level=1))


@pytest.mark.parametrize(
    ("board", "piece", "kind", "pose", "reason"),
    [
        (Board(3, 3), "b1", "battery", BoardPose(1, 0), "off the board at (3, 0)"),
        (Board(3, 3), "b1", "battery", BoardPose(1, 0, rotation=2), "off the board at (-1, 0)"),
        (Board(3, 3), "b1", "battery", BoardPose(0, 1, rotation=3), "off the board at (0, -1)"),
        (
            Board(3, 3).place("b1", "battery", BoardPose(0, 0)),
            "w1",
            "wire3",
            BoardPose(1, 0, rotation=1),
            "overlaps 'b1' at (1, 0) on level 0",
        ),
        (
            Board(3, 3),
            "b1",
            "battery",
            BoardPose(0, 0, level=1),
            "unsupported: no snap on level 0 under its snap at (0, 0)",
        ),
        (
            Board(3, 3).place("w1", "wire2", BoardPose(0, 0, rotation=1)),
            "b1",
            "battery",
            BoardPose(0, 0, level=1),
            "unsupported: no snap on level 0 under its snap at (2, 0)",
        ),
        (
            Board(3, 3).place("w1", "wire3", BoardPose(0, 0)),
            "b1",
            "battery",
            BoardPose(0, 0, level=1),
            "blocked by the stud of 'w1' at (1, 0) on level 0",
        ),
        (
            _level1_battery_on_wires(),
            "w3",
            "wire2",
            BoardPose(1, 0, rotation=1),
            "its stud at (1, 0) would block 'b1' on level 1",
        ),
        (
            Board(3, 3).place("b1", "battery", BoardPose(0, 0)),
            "b1",
            "lamp",
            BoardPose(0, 2),
            "'b1' is already on the board",
        ),
    ],
    ids=[
        "off-right",
        "off-left",
        "off-top",
        "overlap",
        "unsupported",
        "half-supported",
        "stud",
        "stud-below",
        "duplicate",
    ],
)
def test_placement_rules(board: Board, piece: str, kind: str, pose: BoardPose, reason: str) -> None:
    assert board.can_place(piece, kind, pose) == reason
    with pytest.raises(CircuitError, match=f"cannot place '{piece}' .*: {re.escape(reason)}"):
        board.place(piece, kind, pose)
    with pytest.raises(CircuitError, match="cannot place"):
        Board(board.columns, board.rows, (*board.placements, Placement(piece, kind, pose)))


def test_allowed_placements_connect_only_by_stacked_snaps() -> None:
    board = _level1_battery_on_wires()
    assert board.can_place("w3", "wire2", BoardPose(1, 1, rotation=1)) is None  # under nothing of level 1
    assert board.piece_at((1, 0), 1) == "b1"
    assert board.snap_at((1, 0), 1) is None
    assert board.snap_at((2, 0), 1) == ("b1", 1)
    assert board.snap_at((2, 1), 0) == ("w2", 1)
    assert board.piece_at((3, 0), 0) is None
    circuit = netlist(board)
    assert circuit.net(piece="b1", terminal="-") == circuit.net("w1", "w")
    assert circuit.net("b1", "+") == circuit.net("w2", "w")
    assert circuit.net("w1", "w") != circuit.net("w2", "w")


def test_side_by_side_pieces_do_not_connect() -> None:
    board = Board(4, 1).place("w1", "wire2", BoardPose(0, 0)).place("w2", "wire2", BoardPose(2, 0))
    circuit = netlist(board)
    assert circuit.net_count == 2
    assert circuit.net("w1", "w") != circuit.net("w2", "w")


def test_remove_refuses_to_drop_a_support() -> None:
    board = _level1_battery_on_wires()
    assert board.dependents("w1") == ("b1",)
    with pytest.raises(CircuitError, match="cannot remove 'w1': 'b1' rests on it"):
        board.remove("w1")
    lighter = board.remove("b1").remove("w1")
    assert [p.piece for p in lighter] == ["w2"]
    assert "b1" in board and "b1" not in lighter
    with pytest.raises(CircuitError, match="not on the board"):
        lighter.remove("b1")


def test_a_middle_snap_resting_on_a_piece_does_not_make_it_a_support() -> None:
    board = Board(3, 2)
    for col in range(3):
        board = board.place(f"w{col}", "wire2", BoardPose(col, 0, rotation=1))
    board = board.place("top", "wire3", BoardPose(0, 0, level=1))
    assert board.dependents("w1") == ()
    assert board.dependents("w0") == board.dependents("w2") == ("top",)
    assert netlist(board).net_count == 1
    assert netlist(board.remove("w1")).net_count == 1


def test_board_equality_ignores_order_and_construction_validates() -> None:
    board = _level1_battery_on_wires()
    again = Board(4, 3, reversed(board.placements))
    assert again == board and hash(again) == hash(board)
    assert [p.level for p in again.placements] == [0, 0, 1]
    assert board != Board(5, 3, board.placements)
    assert board != board.remove("b1")
    with pytest.raises(CircuitError, match="unsupported"):
        Board(4, 3, [p for p in board.placements if p.piece != "w2"])


def test_netlist_joins_wires_and_stacks_in_a_deterministic_order() -> None:
    # A battery on the board, a lamp on it and a 3-snap wire on top: three levels joined at two points.
    board = (
        Board(3, 2)
        .place("b1", "battery", BoardPose(0, 0))
        .place("l1", "lamp", BoardPose(0, 0, level=1))
        .place("w1", "wire3", BoardPose(0, 0, level=2))
        .place("r1", "resistor", BoardPose(0, 1))
    )
    circuit = netlist(board)
    assert circuit.net_count == 3  # one conductor through the stack, and the resistor's two snaps alone
    assert [e.piece for e in circuit.elements] == ["b1", "l1", "r1"]
    assert circuit.element("b1").nets == (0, 0) and circuit.element("l1").nets == (0, 0)
    assert circuit.element("r1").nets == (1, 2)  # (0, 1) before (2, 1): nets follow their first snap
    assert [(t.piece, t.level) for t in circuit.nets[0] if t.point == (0, 0)] == [
        ("b1", 0),
        ("l1", 1),
        ("w1", 2),
    ]
    assert netlist(Board(3, 2, reversed(board.placements))) == circuit
    with pytest.raises(CircuitError, match="not an element"):
        circuit.element("w1")
    with pytest.raises(CircuitError, match="no terminal"):
        circuit.net("b1", "anode")
