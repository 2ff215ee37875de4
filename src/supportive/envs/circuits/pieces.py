"""The catalogue of circuit pieces (thesis §3.2.9: a SnapCircuits-like toy) and their electrical constants.

A piece is a straight block with snap buttons along its axis. Offsets count grid steps from the piece's first
snap, so a piece with snaps at offsets 0 and 2 covers three grid points and has a bare body at the middle one.

Our choices (the thesis gives none):

* wires ``wire2`` … ``wire5`` have 2 to 5 snaps on consecutive points, all one conductor (terminal ``w``);
* ``battery`` is a single 1.5 V cell with snaps 2 apart, terminals ``-`` then ``+``;
* ``led`` has a built-in series resistor (like SnapCircuits' D1), terminals ``anode`` then ``cathode``;
* ``switch``, ``resistor`` and ``lamp`` are non-polar two-snap parts 2 apart.

One cell (1.5 V) cannot light the LED (forward voltage 1.8 V); two cells in series can. That is deliberate:
it makes "powered by two batteries in series" a goal with teeth.

>>> piece_type("battery").terminals, piece_type("battery").span, piece_type("led").polar
(('-', '+'), 2, True)
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from types import MappingProxyType
from typing import Literal

from supportive.errors import CircuitError

__all__ = [
    "BATTERY_EMF",
    "BATTERY_RESISTANCE",
    "ELEMENTS",
    "GMIN",
    "LAMP_LIT_CURRENT",
    "LAMP_RESISTANCE",
    "LED_FORWARD_VOLTAGE",
    "LED_LIT_CURRENT",
    "LED_RESISTANCE",
    "PIECE_TYPES",
    "RESISTOR_RESISTANCE",
    "SHORT_CURRENT",
    "SWITCH_RESISTANCE",
    "ElementKind",
    "PieceType",
    "piece_type",
]

ElementKind = Literal["wire", "battery", "led", "switch", "resistor", "lamp"]
"""What a piece is electrically."""

ELEMENTS: tuple[ElementKind, ...] = ("wire", "battery", "led", "switch", "resistor", "lamp")
"""Every element kind, in catalogue order."""

# Electrical constants: volts, ohms, amperes, siemens.
BATTERY_EMF = 1.5
"""Open-circuit voltage of one cell (V)."""
BATTERY_RESISTANCE = 0.2
"""Internal resistance of one cell (Ω)."""
LED_FORWARD_VOLTAGE = 1.8
"""The LED conducts only above this voltage from anode to cathode (V)."""
LED_RESISTANCE = 100.0
"""The LED's built-in series resistor (Ω)."""
LAMP_RESISTANCE = 20.0
"""The bulb's resistance, taken as constant (Ω)."""
RESISTOR_RESISTANCE = 100.0
"""The resistor piece (Ω)."""
SWITCH_RESISTANCE = 0.01
"""A closed switch's contact resistance (Ω); an open switch conducts nothing."""
LED_LIT_CURRENT = 1e-3
"""An LED is lit at this forward current or more (A)."""
LAMP_LIT_CURRENT = 50e-3
"""A lamp is lit at this current or more, either way (A)."""
SHORT_CURRENT = 1.0
"""A battery carrying more than this, either way, is short-circuited (A)."""
GMIN = 1e-9
"""Leak conductance from every net to ground, so floating parts have defined potentials (S)."""


@dataclass(frozen=True)
class PieceType:
    """One kind of piece.

    Args:
        name: The catalogue name (``"wire3"``, ``"battery"``, …).
        element: What it is electrically.
        snaps: Snap offsets along the piece's axis, increasing, the first 0.
        terminals: One terminal name per snap (a wire's snaps are all ``"w"``, one conductor).
        text: The piece in words (``"a 3-snap wire"``).

    Raises:
        CircuitError: When snaps and terminals do not fit together.
    """

    name: str
    element: ElementKind
    snaps: tuple[int, ...]
    terminals: tuple[str, ...]
    text: str

    def __post_init__(self) -> None:
        if self.element not in ELEMENTS:
            raise CircuitError(
                f"piece {self.name!r}: unknown element {self.element!r}, expected one of {ELEMENTS}"
            )
        if len(self.snaps) < 2 or self.snaps[0] != 0:
            raise CircuitError(f"piece {self.name!r}: needs at least 2 snaps, the first at offset 0")
        if any(b <= a for a, b in zip(self.snaps, self.snaps[1:], strict=False)):
            raise CircuitError(f"piece {self.name!r}: snap offsets must increase, got {self.snaps}")
        if len(self.terminals) != len(self.snaps):
            raise CircuitError(
                f"piece {self.name!r}: {len(self.snaps)} snaps but {len(self.terminals)} terminals"
            )
        if self.element != "wire" and len(self.snaps) != 2:
            raise CircuitError(f"piece {self.name!r}: a {self.element} has exactly 2 snaps")

    @property
    def span(self) -> int:
        """Grid steps from the first snap to the last."""
        return self.snaps[-1]

    @cached_property
    def reach(self) -> tuple[int, ...]:
        """The offsets of every grid point the piece covers, first snap to last (``0 … span``)."""
        return tuple(range(self.span + 1))

    @property
    def polar(self) -> bool:
        """Whether turning the piece around changes the circuit (batteries and LEDs)."""
        return self.element in ("battery", "led")


def _two_snap(name: str, element: ElementKind, terminals: tuple[str, str], text: str) -> PieceType:
    return PieceType(name, element, (0, 2), terminals, text)


def _wire(snaps: int) -> PieceType:
    return PieceType(f"wire{snaps}", "wire", tuple(range(snaps)), ("w",) * snaps, f"a {snaps}-snap wire")


PIECE_TYPES: Mapping[str, PieceType] = MappingProxyType(
    {
        **{f"wire{n}": _wire(n) for n in range(2, 6)},
        "battery": _two_snap("battery", "battery", ("-", "+"), "a 1.5 V battery"),
        "led": _two_snap("led", "led", ("anode", "cathode"), "an LED"),
        "switch": _two_snap("switch", "switch", ("a", "b"), "a switch"),
        "resistor": _two_snap("resistor", "resistor", ("a", "b"), "a 100 Ω resistor"),
        "lamp": _two_snap("lamp", "lamp", ("a", "b"), "a lamp"),
    }
)
"""Every kind of piece by name."""


def piece_type(name: str) -> PieceType:
    """The kind of piece called ``name``.

    Raises:
        CircuitError: When there is no such kind; the message lists the known ones.

    >>> piece_type("wire3").snaps
    (0, 1, 2)
    """
    try:
        return PIECE_TYPES[name]
    except KeyError:
        raise CircuitError(
            f"unknown piece kind {name!r}, expected one of: {', '.join(PIECE_TYPES)}"
        ) from None
