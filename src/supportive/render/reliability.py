"""A reliability diagram of next-step predictors (``supportive evaluate --plot``): for each tenth of the top-1
probability, the share of top-1 predictions that were right against their mean probability; a calibrated
predictor lies on the diagonal."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

from supportive.errors import ExportError, MissingExtraError
from supportive.render.layout import legends_outside

__all__ = ["write_reliability"]


def write_reliability(tables: Mapping[str, Sequence[Mapping[str, float | int]]], path: str | Path, title: str) -> Path:
    """Draw the reliability tables of several predictors (by name; rows as
    :meth:`~supportive.evaluation.crossval.StepScores.reliability` gives them) in one PNG.

    Raises:
        MissingExtraError: when matplotlib (the ``plot`` extra) is not installed.
        ExportError: when the file cannot be written.
    """
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError:
        raise MissingExtraError("drawing a reliability diagram", "matplotlib", "plot") from None
    figure = Figure(figsize=(6.6, 5.0))  # the legend beside the square diagram
    FigureCanvasAgg(figure)
    axes = figure.add_subplot(1, 1, 1)
    axes.plot([0, 1], [0, 1], color="#999999", linestyle="--", linewidth=1, label="calibrated")
    for name, rows in tables.items():
        axes.plot(
            [float(r["confidence"]) for r in rows],
            [float(r["accuracy"]) for r in rows],
            marker="o",
            markersize=3,
            label=name,
        )
    axes.set_xlim(0, 1)
    axes.set_ylim(0, 1)
    axes.set_xlabel("top-1 probability (mean of its tenth)")
    axes.set_ylabel("top-1 right (share)")
    axes.set_title(title, fontsize=9)
    axes.legend(fontsize=7)
    legends_outside(figure)
    target = Path(path)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        figure.savefig(target, dpi=130)
    except OSError as exc:
        raise ExportError(f"{target}: cannot write: {exc.strerror or exc}") from None
    return target
