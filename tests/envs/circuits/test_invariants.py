"""Invariants over random valid boards: Kirchhoff's current law, energy balance, consistent LED states,
determinism, and boards that stay valid."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.envs.circuits import (
    PIECE_TYPES,
    Board,
    BoardPose,
    CircuitGoal,
    CircuitState,
    Element,
    Netlist,
    Terminal,
    analyze,
    analyze_netlist,
    netlist,
    piece_type,
)
from supportive.envs.circuits.pieces import (
    BATTERY_EMF,
    BATTERY_RESISTANCE,
    GMIN,
    LAMP_LIT_CURRENT,
    LAMP_RESISTANCE,
    LED_FORWARD_VOLTAGE,
    LED_LIT_CURRENT,
    LED_RESISTANCE,
    RESISTOR_RESISTANCE,
    SHORT_CURRENT,
    SWITCH_RESISTANCE,
)

# Batteries, switches and LEDs twice, so random boards have enough of them to make loops.
KINDS = [*sorted(PIECE_TYPES), "battery", "switch", "led"]


@st.composite
def boards(draw: st.DrawFn) -> Board:
    """A random valid board: each step picks a kind and a level (up to one above the current top, so stacks
    are common), then one of the poses the board allows there, if any."""
    columns, rows = draw(st.integers(2, 5)), draw(st.integers(2, 4))
    board = Board(columns, rows)
    for step in range(draw(st.integers(0, 12))):
        piece, kind = f"p{step}", draw(st.sampled_from(KINDS))
        level = draw(st.integers(0, max((p.level for p in board), default=-1) + 1))
        poses = [
            pose
            for col in range(columns)
            for row in range(rows)
            for rotation in range(4)
            if board.can_place(piece, kind, pose := BoardPose(col, row, rotation, level)) is None
        ]
        if poses:
            board = board.place(piece, kind, draw(st.sampled_from(poses)))
    return board


@st.composite
def boards_and_settings(draw: st.DrawFn) -> tuple[Board, dict[str, bool]]:
    board = draw(boards())
    switches = sorted(p.piece for p in board if p.kind == "switch")
    return board, {piece: draw(st.booleans()) for piece in switches}


@st.composite
def circuits(draw: st.DrawFn) -> tuple[Netlist, dict[str, bool]]:
    """A circuit and switch settings: from a random board, or a random netlist with no geometry at all
    (denser, with many batteries and LEDs, to exercise the LED pivoting)."""
    if draw(st.booleans()):
        board, settings = draw(boards_and_settings())
        return netlist(board), settings
    count = draw(st.integers(1, 5))
    nets = tuple((Terminal((net, 0), 0, f"n{net}", 0, "w"),) for net in range(count))
    kinds = draw(
        st.lists(st.sampled_from(["battery"] * 3 + ["led"] * 3 + ["lamp", "resistor", "switch"]), max_size=12)
    )
    elements = tuple(
        Element(f"e{k}", piece_type(kind), (draw(st.integers(0, count - 1)), draw(st.integers(0, count - 1))))
        for k, kind in enumerate(kinds)
    )
    settings = {e.piece: draw(st.booleans()) for e in elements if e.element == "switch"}
    return Netlist(nets, elements), settings


def _resistance(kind: str) -> float:
    return {"resistor": RESISTOR_RESISTANCE, "lamp": LAMP_RESISTANCE, "switch": SWITCH_RESISTANCE}[kind]


def _kirchhoff_residuals(circuit: Netlist, state: CircuitState) -> list[float]:
    """Current into every net from the elements, less the leak to ground."""
    into = [0.0] * circuit.net_count
    for element in circuit.elements:
        first, second = element.nets
        into[first] -= state.currents[element.piece]
        into[second] += state.currents[element.piece]
    return [flow - GMIN * potential for flow, potential in zip(into, state.potentials, strict=True)]


@given(circuits())
def test_currents_obey_kirchhoff_and_balance_energy(case: tuple[Netlist, dict[str, bool]]) -> None:
    circuit, settings = case
    state = analyze_netlist(circuit, settings)
    assert max(map(abs, _kirchhoff_residuals(circuit, state)), default=0.0) < 1e-9
    supplied = 0.0
    spent = sum(GMIN * v * v for v in state.potentials)
    for element in circuit.elements:
        current = state.currents[element.piece]
        kind = element.element
        if kind == "battery":
            supplied += BATTERY_EMF * current
            spent += BATTERY_RESISTANCE * current * current
        elif kind == "led":
            spent += (LED_FORWARD_VOLTAGE + LED_RESISTANCE * current) * current
        else:
            spent += _resistance(kind) * current * current
    assert spent == pytest.approx(supplied, rel=1e-6, abs=1e-9)


@given(circuits())
def test_led_states_are_consistent_and_flags_follow_the_thresholds(
    case: tuple[Netlist, dict[str, bool]],
) -> None:
    circuit, settings = case
    state = analyze_netlist(circuit, settings)
    for element in circuit.elements:
        current = state.currents[element.piece]
        first, second = element.nets
        across = state.potentials[first] - state.potentials[second]
        kind = element.element
        if kind == "led":
            assert current >= -1e-12
            if current > 0:
                assert across == pytest.approx(LED_FORWARD_VOLTAGE + LED_RESISTANCE * current, abs=1e-9)
            else:
                assert across <= LED_FORWARD_VOLTAGE + 1e-9
            assert (element.piece in state.lit) == (current >= LED_LIT_CURRENT)
        elif kind == "lamp":
            assert (element.piece in state.lit) == (abs(current) >= LAMP_LIT_CURRENT)
        elif kind == "battery":
            assert (element.piece in state.shorted_batteries) == (abs(current) > SHORT_CURRENT)
        elif kind == "switch" and not settings.get(element.piece, True):
            assert current == 0.0
    assert state.lit <= {e.piece for e in circuit.elements if e.element in ("led", "lamp")}
    assert state.switches == {
        e.piece: settings.get(e.piece, True) for e in circuit.elements if e.element == "switch"
    }
    assert analyze_netlist(circuit, settings) == state


@given(boards_and_settings())
def test_analysis_is_deterministic_and_ignores_placement_order(case: tuple[Board, dict[str, bool]]) -> None:
    board, settings = case
    shuffled = Board(board.columns, board.rows, reversed(board.placements))
    assert netlist(shuffled) == netlist(board)
    assert analyze(shuffled, settings) == analyze(board, settings)
    goal = CircuitGoal(batteries_in_series=2, switch_controls=True)
    assert goal.check(shuffled) == goal.check(board)


@given(boards())
def test_boards_stay_valid_while_pieces_come_off(board: Board) -> None:
    assert Board(board.columns, board.rows, board.placements) == board
    while len(board):
        free = [p.piece for p in board if not board.dependents(p.piece)]
        assert free  # the topmost pieces can always be taken off
        board = board.remove(free[0])
        assert Board(board.columns, board.rows, board.placements) == board


@given(
    st.sampled_from(sorted(PIECE_TYPES)),
    st.integers(-3, 3),
    st.integers(-3, 3),
    st.integers(0, 3),
    st.integers(0, 2),
)
def test_a_piece_turned_round_from_its_last_snap_covers_the_same_points(
    kind: str, col: int, row: int, rotation: int, level: int
) -> None:
    pose = BoardPose(col, row, rotation, level)
    snaps = pose.snap_points(kind)
    footprint = pose.footprint(kind)
    assert len(footprint) == piece_type(kind).span + 1 and set(snaps) <= set(footprint)
    turned = BoardPose(*snaps[-1], (rotation + 2) % 4, level)
    assert turned.footprint(kind) == footprint[::-1]
    assert set(turned.snap_points(kind)) == set(snaps)
