"""DC analysis of a board: currents, which lights are lit, which batteries are short-circuited.

The electrical model (constants in :mod:`supportive.envs.circuits.pieces`):

* a battery is an EMF of 1.5 V behind an internal resistance of 0.2 Ω;
* a resistor (100 Ω) and a lamp (20 Ω) are plain resistances; a closed switch is 0.01 Ω, an open one is open;
* an LED is a piecewise-linear diode: *on*, a 1.8 V drop plus its built-in 100 Ω from anode to cathode;
  *off*, open. Wires are ideal: their snaps are one net.
* every net leaks to ground through a tiny conductance (1 nS), so floating parts have defined potentials and
  the nodal matrix is never singular.

Batteries and resistive parts become Norton equivalents in one symmetric nodal system solved with numpy. The
LEDs' on/off states are found by Murty's least-index principal pivoting: solve, flip the first LED whose
state contradicts the solution (on with reverse current, or off with more than 1.8 V across it), repeat.
Because every LED has a series resistance and every net a leak, the underlying linear complementarity
problem has a positive definite matrix, so there is exactly one consistent assignment and the pivoting
reaches it in a finite, deterministic number of steps.

Signs: an element's current is what flows through it from its first terminal to its second (see
:class:`~supportive.envs.circuits.netlist.Element`): for a battery positive means discharging (current
leaves its ``+`` into the circuit), for an LED positive means anode to cathode.

An LED is lit at 1 mA forward or more, a lamp at 50 mA either way; a battery carrying more than 1 A either
way is short-circuited.

>>> from supportive.envs.circuits.board import Board, BoardPose
>>> board = Board(3, 1).place("b1", "battery", BoardPose(0, 0)).place("w1", "wire3", BoardPose(0, 0, level=1))
>>> state = analyze(board)
>>> round(state.currents["b1"], 3), state.shorted
(7.5, True)
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np
import numpy.typing as npt

from supportive.envs.circuits.board import Board
from supportive.envs.circuits.netlist import Element, Netlist, netlist
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
from supportive.errors import CircuitError

__all__ = ["FLOW_CURRENT", "CircuitState", "analyze", "analyze_netlist", "supply_batteries"]

FLOW_CURRENT = 1e-6
"""Currents below this (A) count as no flow when tracing where a current goes (the leaks are ~1 nA)."""

_CURRENT_SLACK = 1e-12
_VOLTAGE_SLACK = 1e-9

_RESISTANCE = {"resistor": RESISTOR_RESISTANCE, "lamp": LAMP_RESISTANCE, "switch": SWITCH_RESISTANCE}

Matrix = npt.NDArray[np.float64]


@dataclass(frozen=True)
class CircuitState:
    """The steady state of a board under one setting of its switches.

    Args:
        currents: Current through every element (non-wire piece) by piece id, in amperes, signed as the
            module describes.
        potentials: Every net's potential (V), by net number. Only differences mean anything.
        lit: The LEDs and lamps that are lit.
        shorted_batteries: The batteries carrying more than 1 A.
        switches: Every switch's setting (True = closed).
    """

    currents: Mapping[str, float]
    potentials: tuple[float, ...]
    lit: frozenset[str]
    shorted_batteries: frozenset[str]
    switches: Mapping[str, bool]

    @property
    def shorted(self) -> bool:
        """Whether any battery is short-circuited."""
        return bool(self.shorted_batteries)


def analyze(board: Board, switches: Mapping[str, bool] | None = None) -> CircuitState:
    """The DC steady state of ``board``.

    Args:
        board: The board.
        switches: Switch id -> closed. Switches not named are closed.

    Raises:
        CircuitError: When ``switches`` names a piece that is not a switch on the board.
    """
    return analyze_netlist(netlist(board), switches)


def analyze_netlist(circuit: Netlist, switches: Mapping[str, bool] | None = None) -> CircuitState:
    """The DC steady state of a netlist (reuse one netlist for several switch settings).

    Args:
        circuit: The nets and elements.
        switches: Switch id -> closed. Switches not named are closed.

    Raises:
        CircuitError: When ``switches`` names a piece that is not a switch of the circuit.
    """
    closed = _switch_settings(circuit, switches)
    size = circuit.net_count
    base = GMIN * np.eye(size)
    injected = np.zeros(size)
    leds: list[Element] = []
    for element in circuit.elements:
        kind = element.element
        first, second = element.nets
        if kind == "battery":
            _stamp(base, first, second, 1.0 / BATTERY_RESISTANCE)
            injected[second] += BATTERY_EMF / BATTERY_RESISTANCE
            injected[first] -= BATTERY_EMF / BATTERY_RESISTANCE
        elif kind == "led":
            leds.append(element)
        elif kind != "switch" or closed[element.piece]:
            _stamp(base, first, second, 1.0 / _RESISTANCE[kind])
    on = [False] * len(leds)
    # Murty's pivoting visits no assignment twice, so 2**len(leds) solves always suffice.
    for _ in range(2 ** len(leds)):
        potentials = _solve(base, injected, leds, on)
        flip = _first_inconsistent(leds, on, potentials)
        if flip is None:
            break
        on[flip] = not on[flip]
    else:
        raise CircuitError("the LED states did not settle (numerical trouble in the circuit analysis)")
    led_on = {led.piece: state for led, state in zip(leds, on, strict=True)}
    currents = {element.piece: _current(element, potentials, closed, led_on) for element in circuit.elements}
    lit = frozenset(
        e.piece
        for e in circuit.elements
        if (e.element == "led" and led_on[e.piece] and currents[e.piece] >= LED_LIT_CURRENT)
        or (e.element == "lamp" and abs(currents[e.piece]) >= LAMP_LIT_CURRENT)
    )
    shorted = frozenset(
        e.piece for e in circuit.elements if e.element == "battery" and abs(currents[e.piece]) > SHORT_CURRENT
    )
    return CircuitState(
        MappingProxyType(currents),
        tuple(float(v) for v in potentials),
        lit,
        shorted,
        MappingProxyType(closed),
    )


def supply_batteries(circuit: Netlist, state: CircuitState, piece: str) -> tuple[str, ...]:
    """The discharging batteries that all of ``piece``'s current flows through, sorted.

    A battery counts when every path along the currents (elements carrying at least
    :data:`FLOW_CURRENT`, each in the direction of its current) that leads from where ``piece``'s current
    leaves it back to where it enters passes through that battery. So two batteries in series with an LED
    both count, also when a second LED is in parallel with the first; a battery on a parallel branch that
    only happens to carry the same current does not.

    Raises:
        CircuitError: When ``piece`` is not an element of the circuit.
    """
    target = circuit.element(piece)
    current = state.currents[piece]
    if abs(current) < FLOW_CURRENT:
        return ()
    entry, leave = target.nets if current > 0 else target.nets[::-1]
    arcs: list[tuple[int, int, str]] = []
    for element in circuit.elements:
        flow = state.currents[element.piece]
        if element.piece != piece and abs(flow) >= FLOW_CURRENT:
            first, second = element.nets
            arcs.append((first, second, element.piece) if flow > 0 else (second, first, element.piece))
    found = []
    for element in circuit.elements:
        if (
            element.element == "battery"
            and state.currents[element.piece] >= FLOW_CURRENT
            and not _reaches(leave, entry, [arc for arc in arcs if arc[2] != element.piece])
        ):
            found.append(element.piece)
    return tuple(sorted(found))


def _reaches(start: int, goal: int, arcs: list[tuple[int, int, str]]) -> bool:
    seen = {start}
    frontier = [start]
    while frontier:
        node = frontier.pop()
        if node == goal:
            return True
        for tail, head, _ in arcs:
            if tail == node and head not in seen:
                seen.add(head)
                frontier.append(head)
    return False


def _switch_settings(circuit: Netlist, switches: Mapping[str, bool] | None) -> dict[str, bool]:
    closed = {e.piece: True for e in circuit.elements if e.element == "switch"}
    for piece, setting in (switches or {}).items():
        if piece not in closed:
            known = ", ".join(repr(name) for name in closed) or "none"
            raise CircuitError(f"{piece!r} is not a switch on the board (switches: {known})")
        if not isinstance(setting, bool):
            raise CircuitError(
                f"switch {piece!r} must be set to True (closed) or False (open), got {setting!r}"
            )
        closed[piece] = setting
    return closed


def _stamp(matrix: Matrix, first: int, second: int, conductance: float) -> None:
    matrix[first, first] += conductance
    matrix[second, second] += conductance
    matrix[first, second] -= conductance
    matrix[second, first] -= conductance


def _solve(base: Matrix, injected: Matrix, leds: list[Element], on: list[bool]) -> Matrix:
    matrix = base.copy()
    rhs = injected.copy()
    for led, state in zip(leds, on, strict=True):
        if state:
            anode, cathode = led.nets
            _stamp(matrix, anode, cathode, 1.0 / LED_RESISTANCE)
            rhs[anode] += LED_FORWARD_VOLTAGE / LED_RESISTANCE
            rhs[cathode] -= LED_FORWARD_VOLTAGE / LED_RESISTANCE
    if matrix.size == 0:
        return rhs
    return np.asarray(np.linalg.solve(matrix, rhs), dtype=np.float64)


def _first_inconsistent(leds: list[Element], on: list[bool], potentials: Matrix) -> int | None:
    for index, (led, state) in enumerate(zip(leds, on, strict=True)):
        anode, cathode = led.nets
        across = float(potentials[anode] - potentials[cathode])
        if state and across - LED_FORWARD_VOLTAGE < -_CURRENT_SLACK * LED_RESISTANCE:
            return index
        if not state and across > LED_FORWARD_VOLTAGE + _VOLTAGE_SLACK:
            return index
    return None


def _current(
    element: Element, potentials: Matrix, closed: Mapping[str, bool], led_on: Mapping[str, bool]
) -> float:
    first, second = element.nets
    across = float(potentials[first] - potentials[second])
    kind = element.element
    if kind == "battery":
        return (BATTERY_EMF + across) / BATTERY_RESISTANCE
    if kind == "led":
        return (across - LED_FORWARD_VOLTAGE) / LED_RESISTANCE if led_on[element.piece] else 0.0
    if kind == "switch" and not closed[element.piece]:
        return 0.0
    return across / _RESISTANCE[kind]
