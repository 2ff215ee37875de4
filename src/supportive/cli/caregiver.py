"""``supportive caregiver``: watch a novice play in a house with the caregiver robot keeping it safe."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from supportive.cli.interrupt import writing
from supportive.cli.output import finite, out, say
from supportive.errors import OptionError
from supportive.extras import require_extra
from supportive.render.terminal import markup_safe

__all__ = ["TERMINAL_DELAY", "caregiver"]

TERMINAL_DELAY = 0.1
"""Seconds between steps on a terminal by default: 200 steps take 20 s to watch, each redrawn in place (with
none, they flash past in a blink); ``--delay 0`` shows only the last."""


def caregiver(
    map_name: Annotated[
        str,
        typer.Option(
            "--map", metavar="house|playroom|apartment|FILE", help="A shipped map (house, playroom, apartment) or a map file."
        ),
    ] = "house",
    novice: Annotated[
        float, typer.Option("--novice", help="The novice's share of random moves ε, in [0, 1].")
    ] = 0.5,
    seed: Annotated[int, typer.Option("--seed", min=0, help="Random seed (same seed, same episode).")] = 0,
    steps: Annotated[int, typer.Option("--steps", min=1, max=10_000, help="Novice steps in the episode.")] = 200,
    no_caregiver: Annotated[bool, typer.Option("--no-caregiver", help="Let the novice play alone.")] = False,
    gif: Annotated[
        Path | None,
        typer.Option("--gif", help="Also draw the episode as an animated GIF (needs matplotlib)."),
    ] = None,
    every: Annotated[int, typer.Option("--every", min=1, help="Print every k-th step (and the last).")] = 1,
    delay: Annotated[
        float | None,
        typer.Option(
            "--delay",
            min=0.0,
            max=60.0,
            callback=finite,
            help=f"Seconds between printed steps (default: {TERMINAL_DELAY} on a terminal, where each step is redrawn "
            "in place; 0 when the output is not a terminal).",
        ),
    ] = None,
) -> None:
    """Watch a novice play in a house, with the caregiver robot keeping it safe (§3.5): the map and what the
    caregiver believes and does, step by step, then the episode's damage, steps until the critical damage and
    cells explored."""
    import time
    from contextlib import nullcontext

    from rich.live import Live

    from supportive.render.files import picture_path
    from supportive.render.household import LEGEND, render_frame, summary, write_gif
    from supportive.safety.episode import THRESHOLD, run_episode
    from supportive.worlds.household import load_map

    if not 0.0 <= novice <= 1.0:
        raise OptionError(f"ε must be in [0, 1] (the share of random moves), got {novice}", "--novice")
    if gif is not None:
        require_extra("drawing an episode as a GIF (--gif)", "matplotlib", "plot")
        picture_path(gif, ".gif", "a GIF")  # before the episode: a folder or a name without .gif is refused
    grid = load_map(map_name)
    with_caregiver = not no_caregiver
    result = run_episode(grid, novice, caregiver=with_caregiver, steps=steps, seed=seed, record=True)
    who = "with the caregiver" if with_caregiver else "without a caregiver"
    out.print(
        f"[bold]{markup_safe(grid.name)}[/]: a novice making {novice:.0%} random moves (ε = {novice:g}), {who}, "
        f"{steps} steps, seed {seed}"
    )
    out.print(LEGEND, markup=False)
    shown = [f for f in result.frames if f.step % every == 0 or f.step == len(result.frames)]
    if delay is None:
        delay = TERMINAL_DELAY if out.is_terminal else 0.0
    live = Live(console=out, auto_refresh=False) if delay > 0 and out.is_terminal else None
    with live or nullcontext():
        for i, frame in enumerate(shown):
            if delay > 0 and i:
                time.sleep(delay)
            if live is not None:  # a terminal: redraw the step in place
                live.update(render_frame(grid, frame, steps=steps), refresh=True)
            else:
                out.print(render_frame(grid, frame, steps=steps))
    out.print(f"[bold]{who}:[/] " + summary(result, threshold=THRESHOLD, steps=steps), highlight=False)
    if gif is not None:
        with writing(gif):
            write_gif(result.frames, grid, gif)
        say(f"wrote {gif} ({len(result.frames)} frames)", to_stderr=True)
