"""The one table helper every experiment report uses: markdown tables, cells escaped.

>>> markdown_table(["model", "top-1"], [["bigram", "0.52"]])
['| model | top-1 |', '|---|---:|', '| bigram | 0.52 |']
>>> markdown_table(["k", "reading"], [["1", "P(safe | τ)"]], align="rl")[2]
'| 1 | P(safe \\\\| τ) |'
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from supportive.errors import ExperimentError

__all__ = ["escape_cell", "markdown_table"]


def escape_cell(text: str) -> str:
    """``text`` for a markdown table cell: a bare ``|`` escaped (``P(safe | τ)`` -> ``P(safe \\| τ)``)."""
    return re.sub(r"(?<!\\)\|", r"\\|", text)


def markdown_table(header: Sequence[str], rows: Sequence[Sequence[str]], *, align: str = "") -> list[str]:
    """The lines of a markdown table of ``header`` and ``rows`` (cells as text, escaped with
    :func:`escape_cell`); the first column left-aligned and the others right-aligned unless ``align`` gives one
    of ``l``/``r`` per column.
    """
    align = align or "l" + "r" * (len(header) - 1)
    if len(align) != len(header) or any(len(row) != len(header) for row in rows):
        raise ExperimentError(f"a table of {len(header)} columns needs that many alignments and cells in every row")
    rule = "|" + "|".join("---:" if a == "r" else "---" for a in align) + "|"
    return [_row(header), rule, *(_row(row) for row in rows)]


def _row(cells: Sequence[str]) -> str:
    return "| " + " | ".join(escape_cell(c) for c in cells) + " |"
