"""What a finished circuit must do: goal predicates over a board, such as "an LED lights when the switch is
closed, powered by two batteries in series".

Our reading of the goal's parts (the thesis names the task, not its tests):

* *lights*: with every switch closed some LED (or lamp) of the goal's kind is lit;
* *batteries in series*: that light's current flows through at least ``n`` batteries carrying the same
  discharge current within 1 %. "Flows through" is traced along the currents
  (:func:`~supportive.envs.circuits.analysis.supply_batteries`), so a battery on a parallel branch does not
  count, and a light in parallel with another still counts the batteries they share;
* *switch controls*: the same light goes out when some single switch alone is opened;
* *no short*: no battery carries more than 1 A in any switch setting checked: every setting when the board has
  at most :data:`MAX_ENUMERATED_SWITCHES` switches, otherwise all closed and each one opened alone.

Each setting is analysed at most once per check, and only the settings a part of the goal needs. A check of
a ten-piece board with one switch takes about 0.15 ms (0.3 ms with three switches, eight settings).

>>> from supportive.envs.circuits.board import Board, BoardPose
>>> board = Board(3, 1).place("b1", "battery", BoardPose(0, 0)).place("w1", "wire3", BoardPose(0, 0, level=1))
>>> CircuitGoal(light="lamp").check(board).reasons
('no lamp lights with the switches closed', 'a battery is short-circuited')
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from itertools import combinations
from typing import Literal

from supportive.envs.circuits.analysis import CircuitState, analyze_netlist, supply_batteries
from supportive.envs.circuits.board import Board
from supportive.envs.circuits.netlist import Netlist, netlist
from supportive.errors import CircuitError

__all__ = ["MAX_ENUMERATED_SWITCHES", "SERIES_TOLERANCE", "CircuitGoal", "GoalReport", "series_count"]

MAX_ENUMERATED_SWITCHES = 3
"""Up to this many switches, the short-circuit test tries every combination of settings."""

SERIES_TOLERANCE = 0.01
"""Batteries count as in series when their discharge currents agree within this fraction."""

_NUMBERS = ("no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine")


@dataclass(frozen=True)
class GoalReport:
    """The outcome of checking a goal on a board.

    Args:
        satisfied: Whether the board meets the goal.
        reasons: What fails, in words; empty when satisfied.
        witness: The light that meets the goal (the first by id), or None when it is not met.
    """

    satisfied: bool
    reasons: tuple[str, ...]
    witness: str | None


@dataclass(frozen=True)
class CircuitGoal:
    """A circuit's required function.

    Args:
        light: The kind of element that must light: ``"led"`` or ``"lamp"``.
        batteries_in_series: How many batteries, at least, its current must flow through in series.
        switch_controls: Whether some switch alone must turn it off.
        no_short: Whether every switch setting checked must be free of short circuits.

    Raises:
        CircuitError: On an unknown light or a negative battery count.

    >>> CircuitGoal(batteries_in_series=2, switch_controls=True).text
    'An LED lights when the switches are closed and goes out when a switch is opened, powered by two batteries in series, with no battery short-circuited.'
    """

    light: Literal["led", "lamp"] = "led"
    batteries_in_series: int = 0
    switch_controls: bool = False
    no_short: bool = True

    def __post_init__(self) -> None:
        if self.light not in ("led", "lamp"):
            raise CircuitError(f"a goal's light must be 'led' or 'lamp', got {self.light!r}")
        count = self.batteries_in_series
        if isinstance(count, bool) or not isinstance(count, int) or count < 0:
            raise CircuitError(f"batteries_in_series must be an integer 0 or more, got {count!r}")

    @property
    def text(self) -> str:
        """The goal as a sentence."""
        words = ["An LED lights" if self.light == "led" else "A lamp lights"]
        if self.switch_controls:
            words.append(" when the switches are closed and goes out when a switch is opened")
        count = self.batteries_in_series
        if count:
            amount = _NUMBERS[count] if count < len(_NUMBERS) else str(count)
            words.append(
                ", powered by a battery" if count == 1 else f", powered by {amount} batteries in series"
            )
        if self.no_short:
            words.append(", with no battery short-circuited")
        return "".join(words) + "."

    def satisfied(self, board: Board) -> bool:
        """Whether ``board`` meets the goal."""
        return self.check(board).satisfied

    def check(self, board: Board) -> GoalReport:
        """Whether ``board`` meets the goal, and if not, why not."""
        circuit = netlist(board)
        settings = _Settings(circuit)
        closed = settings.state(frozenset())
        word = "LED" if self.light == "led" else "lamp"
        reasons: list[str] = []
        candidates = [e.piece for e in circuit.elements if e.element == self.light and e.piece in closed.lit]
        if not candidates:
            reasons.append(f"no {word} lights with the switches closed")
        needed = self.batteries_in_series
        if candidates and needed:
            counts = {piece: series_count(circuit, closed, piece) for piece in candidates}
            candidates = [piece for piece in candidates if counts[piece] >= needed]
            if not candidates:
                best = max(counts.values())
                reasons.append(
                    f"the {word}'s current flows through {best} {'battery' if best == 1 else 'batteries'}, "
                    f"not {needed} in series"
                )
        if candidates and self.switch_controls:
            candidates = self._controlled(settings, candidates)
            if not settings.switches:
                reasons.append(f"there is no switch to turn the {word} off")
            elif not candidates:
                reasons.append(f"opening no single switch turns the {word} off")
        if self.no_short:
            for opened in settings.for_shorts():
                if settings.state(opened).shorted:
                    reasons.append("a battery is short-circuited" + settings.describe(opened))
                    break
        satisfied = not reasons
        return GoalReport(satisfied, tuple(reasons), candidates[0] if satisfied else None)

    @staticmethod
    def _controlled(settings: _Settings, candidates: list[str]) -> list[str]:
        darkened: set[str] = set()
        for switch in settings.switches:
            darkened.update(
                piece for piece in candidates if piece not in settings.state(frozenset({switch})).lit
            )
            if len(darkened) == len(candidates):
                break
        return [piece for piece in candidates if piece in darkened]


def series_count(circuit: Netlist, state: CircuitState, piece: str) -> int:
    """How many batteries ``piece``'s current flows through in series: the most of its supply batteries
    (:func:`~supportive.envs.circuits.analysis.supply_batteries`) whose discharge currents agree within
    :data:`SERIES_TOLERANCE`.

    Raises:
        CircuitError: When ``piece`` is not an element of the circuit.
    """
    currents = sorted(state.currents[b] for b in supply_batteries(circuit, state, piece))
    best = 0
    low = 0
    for high, current in enumerate(currents):
        while current > currents[low] * (1 + SERIES_TOLERANCE):
            low += 1
        best = max(best, high - low + 1)
    return best


class _Settings:
    """The states of one circuit under switch settings, each analysed once, keyed by the switches opened."""

    def __init__(self, circuit: Netlist) -> None:
        self.circuit = circuit
        self.switches = tuple(e.piece for e in circuit.elements if e.element == "switch")
        self._states: dict[frozenset[str], CircuitState] = {}

    def state(self, opened: frozenset[str]) -> CircuitState:
        if opened not in self._states:
            self._states[opened] = analyze_netlist(self.circuit, {piece: False for piece in opened})
        return self._states[opened]

    def for_shorts(self) -> Iterator[frozenset[str]]:
        """All closed, each opened alone, then (for few switches) every other combination."""
        largest = len(self.switches) if len(self.switches) <= MAX_ENUMERATED_SWITCHES else 1
        for size in range(largest + 1):
            for opened in combinations(self.switches, size):
                yield frozenset(opened)

    def describe(self, opened: frozenset[str]) -> str:
        if not self.switches:
            return ""
        if not opened:
            return " with the switches closed"
        names = sorted(opened)
        listed = ", ".join(repr(name) for name in names[:-1])
        listed = f"{listed} and {names[-1]!r}" if listed else repr(names[-1])
        return f" with switch{'es' if len(names) > 1 else ''} {listed} open"
