"""Predicate prototypes: the prohibited set P of the SB-TAMP problem (§3.2.5).

A prototype is a predicate name with arguments, where ``*`` (or a ``?variable``) matches any argument:
``inCircuit(*)`` matches ``inCircuit(battery-1)``; a bare name ``on_board`` matches the predicate with any
arguments. An operator whose effects add or delete a predicate matching a prototype of P is prohibited to
the support agent.

>>> prototype = Prototype.parse("holding(support, *)")
>>> prototype.matches(("holding", "support", "wire3-1")), prototype.matches(("holding", "lead", "wire3-1"))
(True, False)
>>> Prototype.parse("on_board").matches(("on_board", "led-1"))
True
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass

from supportive.errors import PlanningError
from supportive.planning.world import Effects, Predicate

__all__ = ["Prototype", "matching", "parse_prototypes"]

_PROTOTYPE = re.compile(r"^\s*([A-Za-z_][\w-]*)\s*(?:\(\s*(.*?)\s*\))?\s*$")


@dataclass(frozen=True)
class Prototype:
    """A partially specified predicate.

    Attributes:
        name: The predicate's name.
        args: Its arguments, None where any argument matches; None for a bare name (any arity).
    """

    name: str
    args: tuple[str | None, ...] | None = None

    @classmethod
    def parse(cls, text: str) -> Prototype:
        """Read ``name``, ``name()`` or ``name(a, *, ?x)``.

        Raises:
            PlanningError: for text that is not a prototype.
        """
        found = _PROTOTYPE.match(text)
        if found is None:
            raise PlanningError(
                f"prohibited predicate {text!r}: expected name(arg, *, ...), like on_board(*)"
            )
        name, inside = found.groups()
        if inside is None:
            return cls(name)
        parts = [part.strip() for part in inside.split(",")] if inside else []
        if any(not part for part in parts):
            raise PlanningError(f"prohibited predicate {text!r}: an argument is empty")
        return cls(name, tuple(None if part == "*" or part.startswith("?") else part for part in parts))

    def matches(self, predicate: Predicate) -> bool:
        """Whether a ground predicate is an instance of this prototype."""
        if not predicate or predicate[0] != self.name:
            return False
        if self.args is None:
            return True
        arguments = predicate[1:]
        return len(arguments) == len(self.args) and all(
            want is None or want == got for want, got in zip(self.args, arguments, strict=True)
        )

    def __str__(self) -> str:
        if self.args is None:
            return self.name
        return f"{self.name}({', '.join('*' if a is None else a for a in self.args)})"


def parse_prototypes(texts: Iterable[str]) -> tuple[Prototype, ...]:
    """Parse every prototype of P (see :meth:`Prototype.parse`)."""
    return tuple(Prototype.parse(text) for text in texts)


def matching(effects: Effects, prohibited: Iterable[Prototype]) -> list[tuple[Prototype, Predicate]]:
    """The (prototype, predicate) pairs where an effect matches a prohibited prototype; empty when allowed."""
    touched = sorted(effects.touched)
    return [(proto, pred) for proto in prohibited for pred in touched if proto.matches(pred)]
