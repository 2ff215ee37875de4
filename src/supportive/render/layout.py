"""Figures whose labels and legends do not overlap: each axes' legend moved outside it (to its right), the
figure laid out by matplotlib's constrained layout, which makes room for the legends, titles and labels; and
labels of items drawn close together (the pieces on a circuit table) moved apart.

Used on every saved figure (the experiments' reports, the reliability diagram, the circuit table), so a
legend never covers the lines or bars it names, whatever the data.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["legends_outside", "spread_labels"]

PAD = 2.0
"""Points between a label moved off its item and the item's edge."""


def legends_outside(figure: Figure) -> Figure:
    """Move every axes' legend outside its axes, to the right (its entries, title and font size kept), and
    lay the figure out with constrained layout. Returns the figure.

    >>> from matplotlib.figure import Figure
    >>> figure = Figure()
    >>> axes = figure.add_subplot()
    >>> _ = axes.plot([0, 1], [0, 1], label="line")
    >>> _ = axes.legend(loc="center")
    >>> legends_outside(figure).axes[0].get_legend().get_bbox_to_anchor() is not None
    True
    """
    for axes in figure.axes:
        legend = axes.get_legend()
        if legend is None:
            continue
        handles = [handle for handle in legend.legend_handles if handle is not None]
        labels = [text.get_text() for text in legend.get_texts()]
        title = legend.get_title().get_text() or None
        size = legend.get_texts()[0].get_fontsize() if labels else None
        axes.legend(
            handles,
            labels,
            title=title,
            fontsize=size,
            loc="upper left",
            bbox_to_anchor=(1.02, 1.0),
            borderaxespad=0.0,
            frameon=False,
        )
    figure.set_layout_engine("constrained")
    return figure


def spread_labels(axes: Any, labels: Sequence[tuple[Any, tuple[float, float, float, float]]]) -> int:
    """Move labels that would overlap one another: each (a matplotlib ``Text`` centred on its item, and the
    item's box ``(x0, y0, x1, y1)`` in data units) stays on its item when it overlaps no label placed before
    it, else goes just above, below, right or left of the item, the first of these that overlaps none (when
    none is free it stays). Call it once the figure is laid out (``figure.draw_without_rendering()``).
    Returns how many labels moved.
    """
    renderer = axes.figure.canvas.get_renderer()
    to_display = axes.transData.transform
    to_data = axes.transData.inverted().transform
    placed: list[Any] = []
    moved = 0
    for text, (x0, y0, x1, y1) in labels:
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        (left, bottom), (right, top) = to_display((x0, y0)), to_display((x1, y1))
        pad = PAD * axes.figure.dpi / 72
        spots = [
            ((left + right) / 2, (bottom + top) / 2, "center", "center"),
            ((left + right) / 2, top + pad, "center", "bottom"),
            ((left + right) / 2, bottom - pad, "center", "top"),
            (right + pad, (bottom + top) / 2, "left", "center"),
            (left - pad, (bottom + top) / 2, "right", "center"),
        ]
        for i, (x, y, ha, va) in enumerate(spots):
            text.set_position(tuple(to_data((x, y))) if i else (cx, cy))
            text.set_horizontalalignment(ha)
            text.set_verticalalignment(va)
            box = text.get_window_extent(renderer)
            if not any(box.overlaps(other) for other in placed):
                moved += i > 0
                break
        else:  # nowhere free: on its item
            text.set_position((cx, cy))
            text.set_horizontalalignment("center")
            text.set_verticalalignment("center")
            box = text.get_window_extent(renderer)
        placed.append(box)
    return moved
