"""``supportive reproduce``: run a thesis experiment and write its report beside the thesis's numbers."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from supportive.cli.interrupt import changes, explained
from supportive.cli.output import local_workers, out, say
from supportive.errors import OptionError
from supportive.extras import require_extra

__all__ = ["reproduce"]


def reproduce(
    name: Annotated[str, typer.Argument(help="Experiment to run (e.g. edge-reduction), or 'all'.")],
    trials: Annotated[
        int | None,
        typer.Option("--trials", "-n", min=1, max=1_000_000, help="Trials per experiment (default: a full run)."),
    ] = None,
    seed: Annotated[int, typer.Option("--seed", min=0, help="Random seed (same seed, same metrics).")] = 0,
    workers: Annotated[
        int | None,
        typer.Option(
            "--workers",
            "-w",
            min=1,
            max=256,
            help="Worker processes on a local dask cluster (default: 1, in process).",
        ),
    ] = None,
    scheduler: Annotated[
        str | None, typer.Option("--scheduler", help="Run on an existing dask cluster: tcp://HOST:PORT.")
    ] = None,
    output: Annotated[
        Path | None,
        typer.Option("--output", "-o", help="Directory to write (default: out/reproduce/<name>)."),
    ] = None,
    reading: Annotated[
        list[str] | None,
        typer.Option(
            "--reading",
            "-r",
            help="Run only this reading of the experiment (repeatable; default: every reading side by side).",
        ),
    ] = None,
) -> None:
    """Reproduce a thesis experiment: write metrics.json, report.md and PNG plots, the thesis's numbers beside
    this run's (for 'all', also summary.md: every experiment's findings in one table)."""
    from supportive.experiments import ALL, default_output, names
    from supportive.experiments import reproduce as run_reproduce
    from supportive.experiments.output import RUN_FILE
    from supportive.render.tables import fitted_table

    local_workers(workers)
    if workers is not None and scheduler is not None:
        raise OptionError("--workers and --scheduler are mutually exclusive: give one or the other")
    require_extra("plotting experiment results", "matplotlib", "plot")
    folder = default_output(name) if output is None else output
    runs = {n: folder / n for n in names()} if name == ALL else {name: folder}
    changed = changes([path / RUN_FILE for path in runs.values()])

    def stopped() -> str:
        """What an interruption kept: each experiment's folder that was written, whole (each is written in
        one step once its run is over)."""
        done = [n for n, path in runs.items() if path / RUN_FILE in changed()]
        if not done:
            return f"nothing written to {folder} (a run's files are written once it is over)"
        if name != ALL:
            return f"kept {folder}: the run was over"
        return f"kept {', '.join(done)} in {folder}, each whole; nothing written for the {len(runs) - len(done)} others"

    with explained(stopped):
        results = run_reproduce(name, trials, seed, workers or 1, scheduler, output, readings=reading or None)
    for result in results:
        files = ", ".join(path.name for path in result.files)
        say(f"{result.experiment}: {result.trials} trials ({result.backend}) -> {result.output}/: {files}")
        rows = [list(row) for row in result.headline]
        title = f"{result.experiment}: this run beside the thesis"
        out.print(fitted_table(out, title, ["quantity", "this run", "thesis"], rows))
    if name == "all" and results and results[0].output is not None:
        out.print(
            f"findings of every experiment, beside the thesis: {results[0].output.parent / 'summary.md'}"
        )
