"""Watching a caregiver episode: recorded :class:`~supportive.safety.episode.Frame` s as text, as rich
renderables for the terminal, and as an animated GIF.

Every step is drawn as the map with the novice and the caregiver on it, beside a status panel: the step, the
damage so far, P(safe | τ), the novice's move and what it bumped into, the caregiver's actions and the
intervention they serve in words, and the hazards it expected the most damage from.

Map characters (the map-file format, plus the two agents):

======  =====================================================================
``N``   the novice
``R``   the caregiver robot (also when it stands in a stairwell, blocking it)
``C``   a table with a candle on it (candles move: the caregiver carries them)
``T``   a table without a candle
``S``   a stairwell
``B``   a toy bin
``#``   a wall
``.``   open floor
======  =====================================================================

The GIF needs matplotlib (the ``plot`` extra), imported only when one is drawn.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from rich.console import RenderableType
from rich.panel import Panel
from rich.table import Table
from rich.text import Text

from supportive.errors import ExportError, MissingExtraError
from supportive.render.files import picture_file, picture_path
from supportive.render.terminal import plain
from supportive.safety.episode import THRESHOLD, EpisodeResult, Frame
from supportive.worlds.household.grid_map import Cell, GridMap, Terrain

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "GIF_SIGNATURE",
    "LEGEND",
    "frame_text",
    "map_rows",
    "render_frame",
    "status_rows",
    "summary",
    "write_gif",
]

LEGEND = "N novice · R caregiver · C candle · T table · S stairwell · B toy bin · # wall"
"""What the map characters mean, in one line."""

GIF_SIGNATURE = b"GIF8"
"""The first four bytes of every GIF file."""

_STYLES = {
    "N": "bold magenta",
    "R": "bold cyan",
    "C": "bold yellow",
    "T": "yellow",
    "S": "bold red",
    "B": "bold blue",
    "#": "dim",
    ".": "dim",
}

_BUMPS = {
    "stairs": "fell down the stairwell at {cell}",
    "candle": "knocked over the candle at {cell}",
    "table": "bumped into the table at {cell}",
    "wall": "bumped into a wall",
    "bin": "reached the toy bin at {cell}",
    "caregiver": "bumped into the caregiver at {cell}",
}


def _terrain_char(grid: GridMap, cell: Cell, candles: frozenset[Cell]) -> str:
    kind = grid.at(cell)
    if kind is Terrain.TABLE and cell in candles:
        return "C"
    return kind.value


def map_rows(grid: GridMap, frame: Frame) -> list[str]:
    """The map after ``frame``'s step, one string per row, with the novice (``N``) and the caregiver (``R``).

    Args:
        grid: The episode's map.
        frame: One recorded step.

    >>> from supportive.worlds.household import parse_map
    >>> grid = parse_map("######\\n#B..C#\\n#R..S#\\n######\\n", "tiny")
    >>> frame = Frame(1, (1, 2), "east", None, (2, 4), None, frozenset(), False, 0, None)
    >>> print("\\n".join(map_rows(grid, frame)))
    ######
    #BN.T#
    #...R#
    ######
    """
    rows = []
    for r in range(grid.rows):
        chars = []
        for c in range(grid.cols):
            if (r, c) == frame.novice:
                chars.append("N")
            elif (r, c) == frame.caregiver:
                chars.append("R")
            else:
                chars.append(_terrain_char(grid, (r, c), frame.candles))
        rows.append("".join(chars))
    return rows


def _hazard_name(grid: GridMap, cell: Cell, candles: frozenset[Cell]) -> str:
    kind = grid.at(cell)
    if kind is Terrain.STAIRS:
        return "stairwell"
    if kind is Terrain.TABLE:
        return "candle" if cell in candles else "table"
    return kind.name.lower()


def status_rows(
    grid: GridMap, frame: Frame, *, steps: int | None = None, top: int = 3
) -> list[tuple[str, str]]:
    """The status of one step as (label, text) pairs.

    Args:
        grid: The episode's map.
        frame: One recorded step.
        steps: The episode's length, shown as "step 4 of 200" when given.
        top: How many hazards to list, most expected damage first.

    >>> from supportive.worlds.household import parse_map
    >>> grid = parse_map("######\\n#B..C#\\n#R..S#\\n######\\n", "tiny")
    >>> bump = Frame(2, (2, 3), "east", None, None, None, frozenset({(1, 4)}), False, 5, None)
    >>> for label, text in status_rows(grid, bump, steps=10):
    ...     print(f"{label}: {text}")
    step: 2 of 10
    damage: 5
    P(safe|τ): – (no caregiver to estimate it)
    novice: east
    caregiver: none
    """
    damage = str(frame.damage)
    move = frame.move
    if frame.collision is not None:
        words = _BUMPS.get(frame.collision.kind, "bumped into something at {cell}").format(
            cell=frame.collision.cell
        )
        move += f" → {words}"
        if frame.collision.damage:
            move += f" (+{frame.collision.damage})"
            damage += f" (+{frame.collision.damage} this step)"
    p_safe = "– (no caregiver to estimate it)" if frame.p_safe is None else f"{frame.p_safe:.2f}"
    rows = [
        ("step", f"{frame.step}" + (f" of {steps}" if steps is not None else "")),
        ("damage", damage),
        ("P(safe|τ)", p_safe),
        ("novice", move),
    ]
    decision = frame.decision
    if frame.caregiver is None or decision is None:
        rows.append(("caregiver", "none"))
        return rows
    doing = decision.intervention.describe() if decision.intervention is not None else "nothing to do: waits"
    rows.append(("caregiver", f"{', '.join(decision.actions)} → {doing}"))
    if frame.carrying:
        rows.append(("", "carrying a candle"))
    if decision.intervention is not None and decision.intervention.kind != "stand-by":
        rows.append(
            ("", f"benefit {decision.intervention.benefit:.2f}, cost {decision.intervention.cost:.2f}")
        )
    ranked = sorted(decision.expected_damage.items(), key=lambda item: (-item[1], item[0]))
    hazards = [
        f"{_hazard_name(grid, cell, frame.candles)} {cell} {value:.2f}"
        for cell, value in ranked[:top]
        if value > 0
    ]
    rows.append(("danger", " · ".join(hazards) if hazards else "no hazard it expects damage from"))
    return rows


def frame_text(grid: GridMap, frame: Frame, *, steps: int | None = None, top: int = 3) -> str:
    """One step as plain text: the map, then the status lines.

    Args:
        grid: The episode's map.
        frame: One recorded step.
        steps: The episode's length, when known.
        top: How many hazards to list.

    >>> from supportive.worlds.household import load_map
    >>> from supportive.safety.episode import run_episode
    >>> grid = load_map("playroom")
    >>> frame = run_episode(grid, 0.5, seed=1, steps=3, record=True).frames[-1]
    >>> text = frame_text(grid, frame, steps=3)
    >>> text.count("N"), "step       3 of 3" in text, "P(safe|τ)" in text
    (1, True, True)
    """
    rows = status_rows(grid, frame, steps=steps, top=top)
    width = max(len(label) for label, _ in rows)
    status = [f"{label:<{width}}  {text}" for label, text in rows]
    return "\n".join([*map_rows(grid, frame), *status]) + "\n"


def _map_text(grid: GridMap, frame: Frame) -> Text:
    text = Text(no_wrap=True)
    bumped = frame.collision.cell if frame.collision is not None and frame.collision.damage else None
    for r, row in enumerate(map_rows(grid, frame)):
        if r:
            text.append("\n")
        for c, char in enumerate(row):
            style = _STYLES.get(char, "")
            if (r, c) == bumped:
                style += " on red"
            text.append(char, style=style.strip())
    return text


def render_frame(grid: GridMap, frame: Frame, *, steps: int | None = None, top: int = 3) -> RenderableType:
    """One step for a rich console: the map (a cell the novice hurt itself on shown on red) beside a status
    panel.

    Args:
        grid: The episode's map.
        frame: One recorded step.
        steps: The episode's length, when known.
        top: How many hazards to list.
    """
    status = Table.grid(padding=(0, 1))
    status.add_column(style="bold", no_wrap=True)
    status.add_column()
    for label, text in status_rows(grid, frame, steps=steps, top=top):
        status.add_row(label, Text(text))
    layout = Table.grid(padding=(0, 2))
    layout.add_column(no_wrap=True)
    layout.add_column()
    layout.add_row(_map_text(grid, frame), status)
    return Panel(layout, title=plain(grid.name), title_align="left", expand=False)


def summary(result: EpisodeResult, *, threshold: int = THRESHOLD, steps: int | None = None) -> str:
    """The measures of an episode (§3.5.6) in one line: damage, the step the damage threshold was reached at
    (or that it was not), cells explored until then, toy bins reached, and the collisions by kind.

    Args:
        result: The episode.
        threshold: The critical damage the episode was run with.
        steps: The episode's length (default: the number of recorded frames, when there are any).

    >>> from supportive.worlds.household import load_map
    >>> from supportive.safety.episode import run_episode
    >>> print(summary(run_episode(load_map("playroom"), 0.0, caregiver=False, seed=0, steps=10), steps=10))
    damage 0 in 10 steps · damage 15 not reached in 10 steps · cells explored: 11 · toy bins reached: 0 · collisions: none
    """
    played = steps if steps is not None else (len(result.frames) or None)
    length = f" in {played} steps" if played is not None else ""
    if result.reached_threshold:
        until = f"damage {threshold} reached at step {result.steps}"
    else:
        until = f"damage {threshold} not reached" + (f" in {played} steps" if played is not None else "")
    bumps = ", ".join(f"{kind} {count}" for kind, count in result.collisions.items()) or "none"
    return (
        f"damage {result.damage}{length} · {until} · cells explored: {result.cells_explored} · "
        f"toy bins reached: {result.bins_reached} · collisions: {bumps}"
    )


# -- GIF ------------------------------------------------------------------------------------------------

_CODES = {Terrain.FLOOR: 0, Terrain.WALL: 1, Terrain.STAIRS: 2, Terrain.TABLE: 3, Terrain.BIN: 5}
_CANDLE = 4
_COLOURS = ("#f7f4ec", "#3b3b3b", "#d62728", "#a0785a", "#ff9f1c", "#1f77b4")
_NAMES = ("floor", "wall", "stairwell", "table", "candle", "toy bin")
_NOVICE, _CAREGIVER, _HURT = "#c51b8a", "#17becf", "#b00000"
_CELL, _BELOW, _ABOVE = 0.32, 0.75, 0.45
"""Inches: a grid cell, the key below the map, the title above it."""


def _codes(grid: GridMap, candles: frozenset[Cell]) -> list[list[int]]:
    return [
        [
            _CANDLE if (r, c) in candles and kind is Terrain.TABLE else _CODES[kind]
            for c, kind in enumerate(row)
        ]
        for r, row in enumerate(grid.terrain)
    ]


def _title(grid: GridMap, frame: Frame, steps: int) -> str:
    p_safe = "–" if frame.p_safe is None else f"{frame.p_safe:.2f}"
    return f"{grid.name}: step {frame.step} of {steps}   damage {frame.damage}   P(safe|τ) {p_safe}"


def _figure(grid: GridMap) -> Figure:
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError:
        raise MissingExtraError("drawing an episode as a GIF", "matplotlib", "plot") from None
    figure = Figure(figsize=(max(4.0, grid.cols * _CELL + 0.4), grid.rows * _CELL + _BELOW + _ABOVE))
    FigureCanvasAgg(figure)
    return figure


def write_gif(
    frames: Sequence[Frame], grid: GridMap, path: str | Path, *, fps: int = 4, dpi: int = 80
) -> Path:
    """Draw every frame with matplotlib (a colour-coded grid, the novice as a magenta disc, the caregiver as a
    cyan square, a red cross where the novice hurt itself) and save them as an animated GIF.

    Args:
        frames: The recorded steps, in order (``run_episode(..., record=True).frames``).
        grid: The episode's map.
        path: The GIF to write (its directory is created).
        fps: Frames per second.
        dpi: Resolution.

    Returns:
        The path written.

    Raises:
        MissingExtraError: when matplotlib (the ``plot`` extra) or pillow is not installed.
        ExportError: when there are no frames, ``fps`` is below 1, or the file cannot be written (a folder, a
            name not ending in ``.gif``: checked before any drawing; the file is written atomically).
    """
    if not frames:
        raise ExportError("no frames to draw: run the episode with record=True")
    if fps < 1:
        raise ExportError(f"fps must be >= 1, got {fps}")
    target = picture_path(path, ".gif", "a GIF")
    figure = _figure(grid)
    try:
        from matplotlib.animation import PillowWriter
        from matplotlib.colors import ListedColormap
    except ImportError:
        raise MissingExtraError("drawing an episode as a GIF", "matplotlib", "plot") from None
    width, height = figure.get_size_inches()
    axes = figure.add_axes((0.02, _BELOW / height, 0.96, grid.rows * _CELL / height))
    axes.set_axis_off()
    image = axes.imshow(
        _codes(grid, frames[0].candles),
        cmap=ListedColormap(list(_COLOURS)),
        vmin=0,
        vmax=len(_COLOURS) - 1,
        interpolation="nearest",
    )
    (novice,) = axes.plot([], [], "o", color=_NOVICE, markersize=13, markeredgecolor="black")
    (carer,) = axes.plot([], [], "s", color=_CAREGIVER, markersize=13, markeredgecolor="black")
    (bump,) = axes.plot([], [], "x", color=_HURT, markersize=16, markeredgewidth=3)
    title = axes.set_title("", fontsize=9)
    key = [(_COLOURS[i], "■", _NAMES[i]) for i in range(1, len(_NAMES))]
    key += [(_NOVICE, "●", "novice"), (_CAREGIVER, "■", "caregiver"), (_HURT, "✕", "hurt here")]
    for i, (colour, mark, label) in enumerate(key):  # a key of plain texts: a legend redraws slowly
        x, y = (0.2 + (i % 4) * 0.95) / width, (0.5 - (i // 4) * 0.25) / height
        figure.text(x, y, mark, color=colour, fontsize=9, va="center")
        figure.text(x + 0.15 / width, y, label, fontsize=7, va="center")
    writer = PillowWriter(fps=fps)
    steps = len(frames)
    try:
        with picture_file(target, ".gif", "a GIF") as temporary, writer.saving(figure, str(temporary), dpi):
            for frame in frames:
                image.set_data(_codes(grid, frame.candles))
                novice.set_data([frame.novice[1]], [frame.novice[0]])
                if frame.caregiver is None:
                    carer.set_data([], [])
                else:
                    carer.set_data([frame.caregiver[1]], [frame.caregiver[0]])
                if frame.collision is not None and frame.collision.damage:
                    bump.set_data([frame.collision.cell[1]], [frame.collision.cell[0]])
                else:
                    bump.set_data([], [])
                title.set_text(_title(grid, frame, steps))
                writer.grab_frame()
    except OSError as exc:
        raise ExportError(f"{target}: cannot write: {exc.strerror or exc}") from None
    return target
