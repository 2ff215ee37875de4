"""The one validation layer for numbers and ids that users give, in files, over the API or on the command line.

Numbers are finite and within a documented range (:mod:`supportive.io.limits`): a time of ``1e300`` or a hand
at ``1e308`` m is refused where it enters, so no computation downstream overflows. Ids are short, printable
text: no control character (an ANSI escape in an id cannot reach a terminal), no lone surrogate (every id can
be written back as UTF-8), and an action id holds no ``#`` (``a#2`` is how the second performance of ``a`` is
named).

The pydantic types (``Seconds``, ``Coordinate``, ``Ident``, ``ActionId``, ``Text``) are used by every
schema; :func:`check_number` and :func:`check_id` by the readers that are not pydantic models (CSV rows,
observation streams, command-line options).

>>> check_number(2.5, "start", low=-MAX_SECONDS, high=MAX_SECONDS)
2.5
>>> check_number(float("nan"), "start", low=0, high=1)
Traceback (most recent call last):
...
supportive.errors.InvalidValueError: start must be a finite number, got nan
>>> check_id("a#2", action=True)
Traceback (most recent call last):
...
supportive.errors.InvalidValueError: an action id may not contain '#' (a#2 names the second performance of a), got 'a#2'
"""

from __future__ import annotations

import math
import unicodedata
from typing import Annotated

from pydantic import AfterValidator, Field, StringConstraints

from supportive.errors import InvalidValueError
from supportive.io.limits import MAX_ID_LENGTH, MAX_SECONDS

__all__ = [
    "MAX_COORDINATE",
    "ActionId",
    "Coordinate",
    "Ident",
    "Seconds",
    "Text",
    "check_id",
    "check_number",
    "check_text",
    "is_digits",
]

MAX_COORDINATE = 1e6
"""The largest coordinate (keyframes, hand positions, table positions), in the task's units (metres or cm)."""


def is_digits(text: str) -> bool:
    """Whether ``text`` is one or more ASCII digits (``str.isdigit`` also says yes to ``²`` or ``٣``, which
    ``int`` refuses or reads as another number than a person typed).

    >>> is_digits("12"), is_digits("²"), is_digits("٣"), is_digits("")
    (True, False, False, False)
    """
    return text.isascii() and text.isdigit()


def check_number(value: float, what: str, *, low: float, high: float) -> float:
    """``value`` when it is a finite number in ``[low, high]``.

    Raises:
        InvalidValueError: naming ``what``, otherwise.
    """
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InvalidValueError(f"{what} must be a number, got {value!r}")
    if isinstance(value, int) and not -(10**30) < value < 10**30:
        raise InvalidValueError(f"{what} must be between {low:g} and {high:g}, got an integer of {len(str(abs(value)))} digits")
    if not math.isfinite(value):
        raise InvalidValueError(f"{what} must be a finite number, got {value}")
    if not low <= value <= high:
        raise InvalidValueError(f"{what} must be between {low:g} and {high:g}, got {value:g}")
    return value


def _unprintable(text: str, *, newlines: bool) -> str | None:
    """The first character of ``text`` that may not be in it, described; None when there is none."""
    for char in text:
        if newlines and char in "\n\t":
            continue
        category = unicodedata.category(char)
        if category == "Cs":
            return f"a lone surrogate (\\u{ord(char):04x})"
        if category == "Cc" or char in _BIDI:
            return f"a control character (U+{ord(char):04X})"
    return None


_BIDI = frozenset("\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")


def check_text(text: str, what: str = "text") -> str:
    """``text`` when it holds no control character (tabs and newlines aside) and no lone surrogate.

    Raises:
        InvalidValueError: naming the first character that may not be there.
    """
    bad = _unprintable(text, newlines=True)
    if bad is not None:
        raise InvalidValueError(f"{what} may not contain {bad}")
    return text


def check_id(text: str, *, action: bool = False, what: str = "an id") -> str:
    """``text`` when it is a valid id: at most :data:`MAX_ID_LENGTH` characters, printable, and for an action
    no ``#``.

    Raises:
        InvalidValueError: saying which rule it breaks.
    """
    if len(text) > MAX_ID_LENGTH:
        raise InvalidValueError(f"{what} is at most {MAX_ID_LENGTH} characters, got {len(text)}")
    bad = _unprintable(text, newlines=False)
    if bad is not None:
        raise InvalidValueError(f"{what} may not contain {bad}")
    if action and "#" in text:
        head = text.split("#")[0]
        raise InvalidValueError(f"an action id may not contain '#' ({head}#2 names the second performance of {head}), got {text!r}")
    return text


Seconds = Annotated[float, Field(allow_inf_nan=False, ge=-MAX_SECONDS, le=MAX_SECONDS)]
"""A time in seconds, finite, within ±:data:`MAX_SECONDS`."""

Coordinate = Annotated[float, Field(allow_inf_nan=False, ge=-MAX_COORDINATE, le=MAX_COORDINATE)]
"""A position along one axis, finite, within ±:data:`MAX_COORDINATE`."""

Ident = Annotated[
    str, StringConstraints(strip_whitespace=True, min_length=1), AfterValidator(lambda text: check_id(text))
]
"""An id or a name: non-empty, printable, at most :data:`MAX_ID_LENGTH` characters."""

ActionId = Annotated[
    str,
    StringConstraints(strip_whitespace=True, min_length=1),
    AfterValidator(lambda text: check_id(text, action=True, what="an action id")),
]
"""An action's id: an :data:`Ident` without ``#``."""

Text = Annotated[str, AfterValidator(check_text)]
"""Free text (an action's words, a behavior's): no control character but tab and newline, no lone
surrogate."""
