"""Figures for reports: matplotlib's Agg backend, imported only when a plot is drawn (the ``plot`` extra).

Figures are made with :class:`matplotlib.figure.Figure` on an Agg canvas, never through ``pyplot``, so
plotting changes no global backend state and works without a display.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from supportive.errors import ExperimentError, MissingExtraError
from supportive.render.layout import legends_outside

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["PNG_SIGNATURE", "new_figure", "save_png"]

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
"""The first eight bytes of every PNG file."""


def new_figure(width: float = 7.0, height: float = 4.5) -> Figure:
    """A blank figure on an Agg canvas (size in inches).

    Raises:
        MissingExtraError: when matplotlib is not installed (``pip install 'supportive[plot]'``).
    """
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError:
        raise MissingExtraError("plotting experiment results", "matplotlib", "plot") from None
    figure = Figure(figsize=(width, height), layout="constrained")
    FigureCanvasAgg(figure)
    return figure


def save_png(figure: Figure, path: Path, *, dpi: int = 120) -> Path:
    """Write ``figure`` to ``path`` as PNG, creating the directory; every legend outside its axes
    (:func:`~supportive.render.layout.legends_outside`).

    Raises:
        ExperimentError: when the file cannot be written.
    """
    legends_outside(figure)  # no legend over the data it names, room made for every label
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        figure.savefig(path, format="png", dpi=dpi)
    except OSError as exc:
        raise ExperimentError(f"{path}: cannot write: {exc.strerror or exc}") from None
    return path
