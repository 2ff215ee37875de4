"""Tables that fit the terminal without cutting a word or a number: numbers are never shortened ("0.9…"),
text wraps at words, and a table too wide for the terminal even then is printed as one record per row.

>>> from rich.console import Console
>>> console = Console(width=30, color_system=None)
>>> with console.capture() as seen:
...     console.print(fitted_table(console, "scores", ["recipe", "precision", "recall"],
...                                [["tomato soup", "0.923", "1.000"]], numeric={1, 2}))
>>> "0.923" in seen.get() and "1.000" in seen.get() and "…" not in seen.get()
True
"""

from __future__ import annotations

from collections.abc import Collection, Sequence

from rich import box
from rich.console import Console, Group, RenderableType
from rich.table import Table
from rich.text import Text

from supportive.render.terminal import plain

__all__ = ["fitted_table"]



def fitted_table(
    console: Console,
    title: str,
    headers: Sequence[str],
    rows: Sequence[Sequence[str]],
    *,
    numeric: Collection[int] = (),
) -> RenderableType:
    """A table of ``rows`` (cells as text) for ``console``'s width.

    Args:
        console: Where it will be printed (its width decides the layout).
        title: Above the table.
        headers: One per column.
        rows: The cells, row by row.
        numeric: The indexes of the columns that hold numbers (right-aligned).
    """
    table = Table(title=plain(title), box=box.SIMPLE_HEAD, pad_edge=False, collapse_padding=True, title_justify="left")
    for index, header in enumerate(headers):
        cells = [row[index] for row in rows]
        word = max((len(w) for w in header.split()), default=1)
        if index in numeric:
            width = max([word, *(len(cell) for cell in cells)])
            table.add_column(header, justify="right", min_width=width, overflow="fold")
        else:
            longest = max([word, *(len(w) for cell in cells for w in cell.split())])
            table.add_column(header, min_width=longest, overflow="fold")
    for row in rows:
        table.add_row(*(plain(cell) for cell in row))  # cells are text, never markup
    if _words_whole(console, table, rows):
        return table
    records: list[RenderableType] = [Text(title, style="bold")]
    for row in rows:
        pairs = ", ".join(f"{header} {cell}" for header, cell in zip(headers[1:], row[1:], strict=True))
        records.append(plain(f"{row[0]}: {pairs}"))
    return Group(*records)


def _words_whole(console: Console, table: Table, rows: Sequence[Sequence[str]]) -> bool:
    """Whether the table, drawn at the console's width, shows every word of every cell whole, and each row's
    numbers on one line (rich shortens, breaks or drops what does not fit)."""
    drawn = Console(width=console.width, color_system=None, force_terminal=False)
    with drawn.capture() as capture:
        drawn.print(table)
    lines = [set(line.split()) for line in capture.get().splitlines()]
    seen = set().union(*lines) if lines else set()
    return all(word in seen for row in rows for cell in row for word in cell.split())
