"""The one escaping rule for text a user wrote that reaches a terminal through rich.

A user's text is shown as it is written, and only as text: rich markup in it (``[/]``, ``[bold]``) is not
interpreted, emoji codes (``:poop:``) are not replaced, and characters that would act on the terminal rather
than show — control characters (an ANSI escape ``ESC [ 2 J`` clears the screen), the bidirectional overrides
that make text read differently from what it is, and lone surrogates (undecodable bytes of a file name, which a
strict UTF-8 terminal cannot even encode) — are shown as visible escapes (``\\x1b``, ``\\u202e``, ``\\xff``).

* :func:`printable` applies the rule to a string;
* :func:`plain` makes a rich ``Text`` of it (no markup, no emoji), for tables, trees and labels;
* :func:`markup_safe` escapes it for a place inside a markup string;
* :func:`terminal_console` is the console every command prints through (emoji codes off, no highlighting).

>>> printable("red\\x1b[31m ok")
'red\\\\x1b[31m ok'
>>> markup_safe("a[/]b")
'a\\\\[/]b'
"""

from __future__ import annotations

import re

from rich.console import Console
from rich.markup import escape
from rich.text import Text

__all__ = ["markup_safe", "plain", "printable", "terminal_console"]

_UNSAFE = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069\ud800-\udfff]")


def _visible(match: re.Match[str]) -> str:
    code = ord(match.group())
    if 0xDC80 <= code <= 0xDCFF:  # a byte Python could not decode (surrogateescape): show the byte
        return f"\\x{code - 0xDC00:02x}"
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def printable(text: str, *, newlines: bool = True) -> str:
    """``text`` with every character that would act on a terminal shown as a visible escape (tabs and, when
    ``newlines``, line breaks kept)."""
    shown = _UNSAFE.sub(_visible, text)
    return shown if newlines else shown.replace("\n", "\\n").replace("\t", "\\t")


def plain(text: str, style: str = "") -> Text:
    """A rich ``Text`` of the user's ``text``: printed as written, never read as markup or emoji."""
    return Text(printable(text), style=style)


def markup_safe(text: str) -> str:
    """The user's ``text`` escaped for a place inside a rich markup string."""
    return escape(printable(text))


def terminal_console(*, stderr: bool = False, **options: object) -> Console:
    """A console for a command's output: emoji codes off always; highlighting off and long lines soft-wrapped
    unless ``options`` say otherwise. Without a ``width`` option its width is the terminal's (or ``COLUMNS``)
    when it prints, not when it was made (rich fixes it at creation when ``COLUMNS`` is set then: a console
    made at import would keep that width for good)."""
    settings: dict[str, object] = {"highlight": False, "soft_wrap": True, **options}
    console = Console(stderr=stderr, emoji=False, **settings)  # type: ignore[arg-type]
    if "width" not in options:
        console._width = None  # read again at every print (Console.size)
    return console
