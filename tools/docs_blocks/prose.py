"""Numbers in words, as the docs' sentences quote them: signs, per cents, ranges, counts and lists."""

from __future__ import annotations

from collections.abc import Sequence


def minus(text: str) -> str:
    """A true minus sign for a negative number in prose (``−0.1``)."""
    return text.replace("-", "−")


def pct(value: float, digits: int = 1) -> str:
    """``21.1 %``, ``−0.1 %`` (never ``−0.0``)."""
    return minus(f"{round(value, digits) + 0.0:.{digits}f} %")


def span(values: Sequence[float], digits: int = 1, unit: str = "") -> str:
    """``a–b`` (``a to b`` when ``a`` is negative; ``a`` when they round alike) of the smallest and largest value."""
    low, high = (minus(f"{round(v, digits) + 0.0:.{digits}f}") for v in (min(values), max(values)))
    return (low if low == high else f"{low}{' to ' if low.startswith('−') else '–'}{high}") + unit


_NUMBERS = (
    "no",
    "one",
    "two",
    "three",
    "four",
    "five",
    "six",
    "seven",
    "eight",
    "nine",
    "ten",
    "eleven",
    "twelve",
)


def number(n: int) -> str:
    """``four`` (up to twelve), else ``13``."""
    return _NUMBERS[n] if 0 <= n < len(_NUMBERS) else str(n)


def of(k: int, n: int) -> str:
    """``all four`` or ``three of the four``."""
    return f"all {number(n)}" if k == n else f"{number(k)} of the {number(n)}"


def words(items: list[str]) -> str:
    """``a``, ``a and b``, ``a, b and c``."""
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]
