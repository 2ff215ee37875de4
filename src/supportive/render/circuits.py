"""Drawing the circuit table with matplotlib: the board with its pieces, the pieces lying on the table, and
what a supportive action moves (before and after, side by side)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from supportive.envs.circuits.board import Board
from supportive.envs.circuits.pieces import piece_type
from supportive.envs.circuits.world import CircuitWorld
from supportive.envs.tabletop.items import TablePose
from supportive.envs.tabletop.state import Status, TabletopState
from supportive.envs.tabletop.world import Move
from supportive.errors import ExportError, MissingExtraError
from supportive.render.files import picture_file, picture_path
from supportive.render.layout import legends_outside, spread_labels

__all__ = ["ELEMENT_COLOURS", "draw_state", "write_before_after"]

ELEMENT_COLOURS = {
    "wire": "#7f7f7f",
    "battery": "#d62728",
    "led": "#2ca02c",
    "switch": "#1f77b4",
    "resistor": "#ff7f0e",
    "lamp": "#e6c700",
}
"""The colour of each element kind, on the table and on the board."""


def draw_state(
    axes: Any,
    world: CircuitWorld,
    state: TabletopState[Board],
    moved: Move | None = None,
    origin: TablePose | None = None,
) -> list[tuple[Any, tuple[float, float, float, float]]]:
    """Draw the table, the board and every piece into matplotlib ``axes``; the piece of ``moved`` is outlined
    in black, with an arrow from ``origin`` (where it lay) when given. Returns each piece's label with the
    piece's box, for :func:`~supportive.render.layout.spread_labels` once the figure is laid out."""
    from matplotlib.patches import FancyArrowPatch, Rectangle

    layout = world.layout
    for surface, colour in ((layout.table, "#f3ead8"), *(((layout.tray, "#e0e0e0"),) if layout.tray else ())):
        axes.add_patch(
            Rectangle((surface.x0, surface.y0), surface.width, surface.height, color=colour, zorder=0)
        )
    area = world.board.area
    axes.add_patch(Rectangle((area.x0, area.y0), area.width, area.height, color="#cfd8dc", zorder=1))
    geometry = world.board
    xs = [geometry.point(c, 0)[0] for c in range(geometry.columns)]
    ys = [geometry.point(0, r)[1] for r in range(geometry.rows)]
    axes.scatter([x for x in xs for _ in ys], [y for _ in xs for y in ys], s=4, color="#607d8b", zorder=2)
    for placement in state.goal:
        points = [geometry.point(*p) for p in placement.snap_points]
        colour = ELEMENT_COLOURS[placement.piece_type.element]
        width = 6 if placement.level == 0 else 3.5
        axes.plot(
            [p[0] for p in points],
            [p[1] for p in points],
            color=colour,
            linewidth=width,
            zorder=3 + placement.level,
            solid_capstyle="round",
        )
        axes.scatter([p[0] for p in points], [p[1] for p in points], s=12, color="black", zorder=5)
    labels: list[tuple[Any, tuple[float, float, float, float]]] = []
    for index, item in enumerate(world.items):
        pose = state.poses[index]
        if pose is None or state.status[index] is not Status.TABLE:
            continue
        rect = world.footprint_of(index, pose)
        highlight = moved is not None and moved.item == index
        axes.add_patch(
            Rectangle(
                (rect.x0, rect.y0),
                rect.width,
                rect.height,
                facecolor=ELEMENT_COLOURS[piece_type(item.kind).element],
                edgecolor="black" if highlight else "none",
                linewidth=1.5,
                zorder=4,
            )
        )
        label = axes.text(pose.x, pose.y, item.id, fontsize=5, ha="center", va="center", zorder=6)
        labels.append((label, (rect.x0, rect.y0, rect.x1, rect.y1)))
    if moved is not None:
        start = world.initial_state.poses[moved.item]
        if start is not None:
            axes.add_patch(
                FancyArrowPatch(
                    start.point, moved.pose.point, arrowstyle="->", mutation_scale=10, color="black", zorder=7
                )
            )
    bounds = layout.bounds.grown(4.0)
    axes.set_xlim(bounds.x0, bounds.x1)
    axes.set_ylim(min(bounds.y0, world.lead_arm.home[1]) - 2, max(bounds.y1, world.support_arm.home[1]) + 2)
    axes.set_aspect("equal")
    axes.plot(*world.lead_arm.home, marker="^", color="black")
    axes.plot(*world.support_arm.home, marker="v", color="black")
    axes.text(world.lead_arm.home[0] + 3, world.lead_arm.home[1], "lead", fontsize=6, va="center")
    axes.text(world.support_arm.home[0] + 3, world.support_arm.home[1], "support", fontsize=6, va="center")
    axes.set_xticks([])
    axes.set_yticks([])
    return labels


def write_before_after(
    world: CircuitWorld,
    before: TabletopState[Board],
    after: TabletopState[Board],
    path: str | Path,
    *,
    moved: Move | None = None,
    titles: tuple[str, str] = ("before", "after"),
) -> Path:
    """Draw two states side by side and save them as a PNG (``path`` ends in ``.png``), atomically.

    Raises:
        MissingExtraError: when matplotlib (the ``plot`` extra) is not installed.
        ExportError: for a path that is a folder or does not end in ``.png``, or that cannot be written.
    """
    picture_path(path, ".png", "the picture")
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError:
        raise MissingExtraError("drawing the circuit table", "matplotlib", "plot") from None
    figure = Figure(figsize=(10, 4.2))
    FigureCanvasAgg(figure)
    drawn = []
    for i, (state, title) in enumerate(zip((before, after), titles, strict=True)):
        axes = figure.add_subplot(1, 2, i + 1)
        if i == 1 and moved is not None:
            drawn.append((axes, draw_state(axes, world, state, moved, before.poses[moved.item])))
        else:
            drawn.append((axes, draw_state(axes, world, state)))
        axes.set_title(title, fontsize=9)
    legends_outside(figure)
    figure.draw_without_rendering()  # laid out: the labels' sizes on the page are known
    for axes, labels in drawn:
        spread_labels(axes, labels)
    target = Path(path)
    try:
        with picture_file(target, ".png", "the picture") as temporary:
            figure.savefig(temporary, dpi=130)
    except OSError as exc:
        raise ExportError(f"{target}: cannot write: {exc.strerror or exc}") from None
    return target
