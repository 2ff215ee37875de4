"""Markdown tables for experiment reports."""

from __future__ import annotations

from collections.abc import Sequence

__all__ = ["markdown_table"]


def markdown_table(header: Sequence[str], rows: Sequence[Sequence[str]], *, align: str = "") -> list[str]:
    """The lines of a markdown table; the first column left-aligned, the others right-aligned unless
    ``align`` gives one of ``l``/``r`` per column.

    >>> markdown_table(["model", "top-1"], [["bigram", "0.52"]])
    ['| model | top-1 |', '|---|---:|', '| bigram | 0.52 |']
    """
    align = align or "l" + "r" * (len(header) - 1)
    rule = "|" + "|".join("---:" if a == "r" else "---" for a in align) + "|"
    return ["| " + " | ".join(header) + " |", rule, *("| " + " | ".join(row) + " |" for row in rows)]
