"""Circuit semantics on hand-built boards, with the expected currents worked out by hand.

Constants used in the comments: a cell is 1.5 V behind 0.2 Ω, a closed switch 0.01 Ω, the LED 1.8 V plus
100 Ω, a lamp 20 Ω.
"""

from __future__ import annotations

import pytest

from supportive.envs.circuits import (
    Board,
    BoardPose,
    CircuitGoal,
    Element,
    Netlist,
    Terminal,
    analyze,
    analyze_netlist,
    netlist,
    piece_type,
    series_count,
    supply_batteries,
)
from supportive.errors import CircuitError

Spec = tuple[str, str, int, int, int, int]  # piece id, kind, col, row, rotation, level


def build(columns: int, rows: int, specs: list[Spec]) -> Board:
    board = Board(columns, rows)
    for piece, kind, col, row, rotation, level in specs:
        board = board.place(piece, kind, BoardPose(col, row, rotation, level))
    return board


# The minimal square loop, 3 x 3. b1 (level 0) runs along +col from (0, 0): '-' at (0, 0), '+' at (2, 0).
# b2 (level 1, rotation 1) from (2, 0): '-' at (2, 0) rests on b1's '+', '+' at (2, 2) rests on s1's 'a'.
# s1 (level 0, rotation 2) from (2, 2): 'a' at (2, 2), 'b' at (0, 2). d1 (level 1, rotation 3) from (0, 2):
# anode at (0, 2) on s1's 'b', cathode at (0, 0) on b1's '-'. Going round: (0, 0) -> b1 -> +1.5 V at (2, 0)
# -> b2 -> +3.0 V at (2, 2) -> s1 -> anode at (0, 2), cathode back at (0, 0): the LED is forward biased by
# 3 V > 1.8 V, and the one loop current is (3 - 1.8) / (100 + 0.2 + 0.2 + 0.01) = 1.2 / 100.41 = 11.95 mA.
SQUARE: list[Spec] = [
    ("b1", "battery", 0, 0, 0, 0),
    ("s1", "switch", 2, 2, 2, 0),
    ("b2", "battery", 2, 0, 1, 1),
    ("d1", "led", 0, 2, 3, 1),
]
LOOP_CURRENT = 1.2 / 100.41


def square(**replace: Spec) -> Board:
    """The square loop with some pieces swapped for others (keyed by the id they replace)."""
    return build(3, 3, [replace.get(spec[0], spec) for spec in SQUARE])


TWO_CELLS = CircuitGoal(batteries_in_series=2, switch_controls=True)


def test_square_loop_lights_the_led_and_meets_the_goal() -> None:
    board = square()
    state = analyze(board)
    assert state.lit == {"d1"}
    assert not state.shorted
    for piece in ("b1", "b2", "s1", "d1"):
        assert state.currents[piece] == pytest.approx(LOOP_CURRENT, rel=1e-6)
    circuit = netlist(board)
    anode, cathode = circuit.element("d1").nets
    assert state.potentials[anode] - state.potentials[cathode] == pytest.approx(1.8 + 100 * LOOP_CURRENT)
    assert supply_batteries(circuit, state, "d1") == ("b1", "b2")
    report = TWO_CELLS.check(board)
    assert (report.satisfied, report.reasons, report.witness) == (True, (), "d1")
    assert TWO_CELLS.satisfied(board)


def test_square_loop_nets() -> None:
    circuit = netlist(square())
    assert circuit.net_count == 4
    members = {frozenset((t.piece, t.name) for t in net) for net in circuit.nets}
    assert members == {
        frozenset({("b1", "-"), ("d1", "cathode")}),
        frozenset({("b1", "+"), ("b2", "-")}),
        frozenset({("b2", "+"), ("s1", "a")}),
        frozenset({("s1", "b"), ("d1", "anode")}),
    }
    assert circuit.element("b2").nets == (circuit.net("b1", "+"), circuit.net("s1", "a"))


@pytest.mark.parametrize(
    "replace",
    [
        # b2 turned round, from (2, 2) towards -row: its '+' meets b1's '+', 1.5 V - 1.5 V = 0 V.
        {"b2": ("b2", "battery", 2, 2, 3, 1)},
        # d1 turned round: anode at (0, 0), cathode at (0, 2), reverse biased by 3 V.
        {"d1": ("d1", "led", 0, 0, 1, 1)},
        # b2 swapped for a wire: one cell, 1.5 V < 1.8 V.
        {"b2": ("w1", "wire3", 2, 0, 1, 1)},
    ],
    ids=["batteries-opposing", "led-reversed", "one-battery"],
)
def test_square_loop_variants_stay_dark(replace: dict[str, Spec]) -> None:
    board = square(**replace)
    state = analyze(board)
    assert state.lit == frozenset()
    assert all(current == pytest.approx(0, abs=1e-7) for current in state.currents.values())
    assert TWO_CELLS.check(board).reasons == ("no LED lights with the switches closed",)


def test_reversed_led_blocks_the_full_voltage() -> None:
    board = square(d1=("d1", "led", 0, 0, 1, 1))
    circuit = netlist(board)
    anode, cathode = circuit.element("d1").nets
    potentials = analyze(board).potentials
    assert potentials[anode] - potentials[cathode] == pytest.approx(-3.0)


def test_open_switch_darkens_the_led() -> None:
    board = square()
    state = analyze(board, {"s1": False})
    assert state.lit == frozenset()
    assert state.switches == {"s1": False}
    assert state.currents["d1"] == 0.0
    assert abs(state.currents["b1"]) < 1e-8  # only the nano-siemens leaks


@pytest.mark.parametrize(("settings", "problem"), [({"d1": False}, "not a switch"), ({"s1": 1}, "True")])
def test_bad_switch_settings_are_refused(settings: dict[str, bool], problem: str) -> None:
    with pytest.raises(CircuitError, match=problem):
        analyze(square(), settings)


def test_one_battery_lights_a_lamp_but_not_two_in_series() -> None:
    # Lamp loop: 1.5 V / (20 + 0.2 + 0.01) = 74.2 mA >= 50 mA.
    board = square(b2=("w1", "wire3", 2, 0, 1, 1), d1=("l1", "lamp", 0, 2, 3, 1))
    state = analyze(board)
    assert state.lit == {"l1"}
    assert state.currents["l1"] == pytest.approx(1.5 / 20.21, rel=1e-6)
    assert CircuitGoal(light="lamp", batteries_in_series=1, switch_controls=True).satisfied(board)
    assert CircuitGoal(light="lamp", batteries_in_series=2).check(board).reasons == (
        "the lamp's current flows through 1 battery, not 2 in series",
    )
    assert CircuitGoal(light="led").check(board).reasons == ("no LED lights with the switches closed",)


@pytest.mark.parametrize(
    ("top", "battery2", "each"),
    [
        # Two LEDs stacked in parallel on two cells: 100 I = 3 - 1.8 - 0.41 * 2 I, so I = 1.2 / 100.82 each.
        ("led", ("b2", "battery", 2, 0, 1, 1), 1.2 / 100.82),
        # Two lamps in parallel on one cell: 20 I = 1.5 - 0.21 * 2 I, so I = 1.5 / 20.42 each.
        ("lamp", ("w1", "wire3", 2, 0, 1, 1), 1.5 / 20.42),
    ],
)
def test_two_lights_in_parallel_share_the_batteries(top: str, battery2: Spec, each: float) -> None:
    specs = [*SQUARE[:2], battery2, ("x1", top, 0, 2, 3, 1), ("x2", top, 0, 2, 3, 2)]
    board = build(3, 3, specs)
    state = analyze(board)
    assert state.lit == {"x1", "x2"}
    assert state.currents["x1"] == pytest.approx(each, rel=1e-6)
    assert state.currents["x2"] == pytest.approx(each, rel=1e-6)
    assert state.currents["b1"] == pytest.approx(2 * each, rel=1e-6)
    cells = 2 if top == "led" else 1
    circuit = netlist(board)
    assert series_count(circuit, state, "x1") == series_count(circuit, state, "x2") == cells
    assert CircuitGoal(light=top, batteries_in_series=cells, switch_controls=True).satisfied(board)  # type: ignore[arg-type]


def test_a_battery_on_another_loop_does_not_count_even_with_the_same_current() -> None:
    # A figure of eight, 5 x 5: loop A (cell A, lamp l1) and loop B (cell B, lamp l2) share only the net of the
    # 5-snap wire along row 2. Each lamp carries 1.5 / 20.2 A, as does each cell, but l1's current never
    # passes through B.
    board = build(
        5,
        5,
        [
            ("A", "battery", 0, 0, 0, 0),
            ("n", "wire5", 0, 2, 0, 0),
            ("t", "wire2", 3, 4, 0, 0),
            ("up", "wire3", 2, 0, 1, 1),
            ("l1", "lamp", 0, 2, 3, 1),
            ("B", "battery", 4, 2, 1, 1),
            ("l2", "lamp", 3, 4, 3, 1),
        ],
    )
    state = analyze(board)
    circuit = netlist(board)
    assert state.lit == {"l1", "l2"}
    for piece in ("A", "B", "l1", "l2"):
        assert state.currents[piece] == pytest.approx(1.5 / 20.2, rel=1e-6)
    assert supply_batteries(circuit, state, "l1") == ("A",)
    assert supply_batteries(circuit, state, "l2") == ("B",)
    report = CircuitGoal(light="lamp", batteries_in_series=2, switch_controls=True).check(board)
    assert report.reasons == ("the lamp's current flows through 1 battery, not 2 in series",)
    assert CircuitGoal(light="lamp", switch_controls=True).check(board).reasons == (
        "there is no switch to turn the lamp off",
    )


def test_wires_on_level_one_bridge_level_zero_components() -> None:
    # Every component on the board (level 0), every connection a wire on level 1, 6 x 3:
    # b1 (0,0)-(2,0), wire (2,0)-(3,0), b2 (3,0)-(5,0), wire down column 5 to the anode at (5,2),
    # cathode at (3,2), wire to the switch at (2,2)-(0,2), wire up column 0 back to b1's '-'.
    specs: list[Spec] = [
        ("b1", "battery", 0, 0, 0, 0),
        ("b2", "battery", 3, 0, 0, 0),
        ("d1", "led", 5, 2, 2, 0),
        ("s1", "switch", 2, 2, 2, 0),
        ("w1", "wire2", 2, 0, 0, 1),
        ("w2", "wire3", 5, 0, 1, 1),
        ("w3", "wire2", 2, 2, 0, 1),
        ("w4", "wire3", 0, 0, 1, 1),
    ]
    board = build(6, 3, specs)
    state = analyze(board)
    assert state.lit == {"d1"}
    assert state.currents["d1"] == pytest.approx(LOOP_CURRENT, rel=1e-6)
    assert TWO_CELLS.satisfied(board)
    # Swap the switch for a wire and leave a switch lying on its own: nothing turns the LED off.
    specs[3] = ("w5", "wire3", 2, 2, 2, 0)
    loose = build(6, 3, [*specs, ("s9", "switch", 1, 1, 0, 0)])
    assert analyze(loose).lit == {"d1"}
    assert TWO_CELLS.check(loose).reasons == ("opening no single switch turns the LED off",)
    assert CircuitGoal(batteries_in_series=2).satisfied(loose)


def test_a_wire_bridging_a_battery_is_a_short() -> None:
    board = build(3, 1, [("b1", "battery", 0, 0, 0, 0), ("w1", "wire3", 0, 0, 0, 1)])
    state = analyze(board)
    assert state.currents["b1"] == pytest.approx(1.5 / 0.2)
    assert state.shorted and state.shorted_batteries == {"b1"}
    assert CircuitGoal(light="lamp").check(board).reasons == (
        "no lamp lights with the switches closed",
        "a battery is short-circuited",
    )


def test_a_wire_across_the_led_shorts_both_batteries_until_the_switch_opens() -> None:
    board = build(3, 3, [*SQUARE, ("w1", "wire3", 0, 2, 3, 2)])
    state = analyze(board)
    assert state.lit == frozenset()
    assert state.shorted_batteries == {"b1", "b2"}
    assert state.currents["b1"] == pytest.approx(3.0 / 0.41)
    assert not analyze(board, {"s1": False}).shorted
    assert TWO_CELLS.check(board).reasons == (
        "no LED lights with the switches closed",
        "a battery is short-circuited with the switches closed",
    )
    assert CircuitGoal(no_short=False).check(board).reasons == ("no LED lights with the switches closed",)


@pytest.mark.parametrize(
    ("reverse", "lit", "current"),
    [
        # Same way round: parallel cells, no current between them; the lamp takes 1.5 / (20 + 0.1) A.
        (False, {"l1"}, 1.5 / 20.1 / 2),
        # Opposing: b2's '+' on b1's '-' closes a loop of 3 V through 0.4 Ω, whatever the lamp does.
        (True, set(), 3.0 / 0.4),
    ],
    ids=["parallel", "opposing"],
)
def test_two_stacked_batteries(reverse: bool, lit: set[str], current: float) -> None:
    b2: Spec = ("b2", "battery", 2, 0, 2, 1) if reverse else ("b2", "battery", 0, 0, 0, 1)
    board = build(3, 1, [("b1", "battery", 0, 0, 0, 0), b2, ("l1", "lamp", 0, 0, 0, 2)])
    state = analyze(board)
    assert state.lit == lit
    assert state.currents["b1"] == pytest.approx(current, rel=1e-6)
    assert state.currents["b2"] == pytest.approx(current, rel=1e-6)
    assert state.shorted is reverse
    if not reverse:  # each cell carries half the lamp's current, so neither is in series with it
        assert series_count(netlist(board), state, "l1") == 0


def overload(switches: int) -> Board:
    """A cell b1 feeding 16 lamps in parallel (1.25 Ω), helped by a second cell b2 through parallel switches.

    5 x 3. Level 0: wire P along row 0 (0,0)-(2,0), wire Q along row 2 (0,2)-(3,2), b2 up column 4 ('-' at
    (4,2), '+' at (4,0)). Level 1: b1 up column 0 ('-' on Q, '+' on P), the first lamp down column 1, the switch
    s1 from P at (2,0) to b2's '+' at (4,0), a wire from Q at (3,2) to b2's '-'. Lamps 2-16 stack on lamp 1;
    s2 stacks on s1.

    With the switches closed the cells share the load: 1.5 V behind 0.2 Ω || 0.21 Ω drives 1.11 A, about 0.57 A
    each. With b2 cut off, b1 alone drives 1.5 / (0.2 + 1.25) = 1.03 A: more than 1 A, a short.
    """
    specs: list[Spec] = [
        ("P", "wire3", 0, 0, 0, 0),
        ("Q", "wire4", 0, 2, 0, 0),
        ("b2", "battery", 4, 2, 3, 0),
        ("b1", "battery", 0, 2, 3, 1),
        ("s1", "switch", 2, 0, 0, 1),
        ("q", "wire2", 3, 2, 0, 1),
    ]
    specs += [(f"l{k}", "lamp", 1, 0, 1, k) for k in range(1, 17)]
    specs += [(f"s{k}", "switch", 2, 0, 0, k) for k in range(2, switches + 1)]
    return build(5, 3, specs)


@pytest.mark.parametrize(
    ("switches", "reason"),
    [
        (1, "a battery is short-circuited with switch 's1' open"),
        (2, "a battery is short-circuited with switches 's1' and 's2' open"),
    ],
)
def test_opening_a_switch_can_overload_the_other_battery(switches: int, reason: str) -> None:
    board = overload(switches)
    closed = analyze(board)
    assert not closed.shorted
    assert len(closed.lit) == 16
    assert closed.currents["b1"] == pytest.approx(0.57, abs=0.01)
    everything_open = analyze(board, {f"s{k}": False for k in range(1, switches + 1)})
    assert everything_open.shorted_batteries == {"b1"}
    assert everything_open.currents["b1"] == pytest.approx(1.5 / 1.45, rel=1e-6)
    assert CircuitGoal(light="lamp").check(board).reasons == (reason,)


def test_boards_without_loops() -> None:
    empty = analyze(Board(2, 2))
    assert (dict(empty.currents), empty.potentials, empty.lit, empty.shorted) == ({}, (), frozenset(), False)
    alone = build(
        4, 3, [("b1", "battery", 0, 0, 0, 0), ("d1", "led", 0, 2, 0, 0), ("w1", "wire3", 2, 0, 1, 1)]
    )
    state = analyze(alone)
    circuit = netlist(alone)
    assert state.currents["b1"] == pytest.approx(0, abs=1e-8)
    assert state.currents["d1"] == 0.0
    assert state.potentials[circuit.net("b1", "+")] - state.potentials[
        circuit.net("b1", "-")
    ] == pytest.approx(1.5)
    assert CircuitGoal().check(alone).reasons == ("no LED lights with the switches closed",)


def test_goal_text_and_validation() -> None:
    assert CircuitGoal().text == "An LED lights, with no battery short-circuited."
    assert (
        CircuitGoal(light="lamp", batteries_in_series=1, no_short=False).text
        == "A lamp lights, powered by a battery."
    )
    assert TWO_CELLS.text == (
        "An LED lights when the switches are closed and goes out when a switch is opened, "
        "powered by two batteries in series, with no battery short-circuited."
    )
    assert "powered by 12 batteries in series" in CircuitGoal(batteries_in_series=12).text
    with pytest.raises(CircuitError, match="'led' or 'lamp'"):
        CircuitGoal(light="buzzer")  # type: ignore[arg-type]
    for count in (-1, True, 1.5):
        with pytest.raises(CircuitError, match="batteries_in_series"):
            CircuitGoal(batteries_in_series=count)  # type: ignore[arg-type]


def test_an_led_switched_on_early_is_switched_back_off() -> None:
    # Straight from a netlist: 2 cells lift A to 3 V, 4 cells lift H to 6 V; d0 runs A -> X, d1 runs H -> X,
    # and X goes to ground G through 100 Ω. All off, X sits at 0 V and d0 (the first) looks forward biased.
    # With d0 on, d1 turns on too, and then X = (1.2 + 4.2) / 3 = 1.8 V leaves d0 reverse biased: it must go
    # off again. The consistent state: d0 off, d1 carrying 4.2 / (0.8 + 100 + 100) A.
    g, a, h, x = 0, 2, 6, 7  # nets 1 and 3-5 are the joints inside the battery stacks
    parts = [("a1", "battery", g, 1), ("a2", "battery", 1, a)]
    parts += [(f"h{k}", "battery", k + 2 if k else g, k + 3 if k < 3 else h) for k in range(4)]
    parts += [("d0", "led", a, x), ("d1", "led", h, x), ("r1", "resistor", x, g)]
    nets = tuple((Terminal((net, 0), 0, f"n{net}", 0, "w"),) for net in range(8))
    circuit = Netlist(nets, tuple(Element(p, piece_type(kind), (u, v)) for p, kind, u, v in parts))
    state = analyze_netlist(circuit)
    assert state.currents["d0"] == 0.0
    assert state.currents["d1"] == pytest.approx(4.2 / 200.8, rel=1e-6)
    assert state.lit == {"d1"}
    assert state.potentials[a] - state.potentials[x] == pytest.approx(3.0 - 100 * 4.2 / 200.8, rel=1e-6)
