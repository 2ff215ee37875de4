"""Run an experiment: make its trials, run them (here or on dask), summarise, write the files.

A run with output directory ``DIR`` writes:

* ``DIR/metrics.json``: the metrics, as plain JSON with sorted keys and no timings, so the same experiment,
  trials and seed give the same bytes whether one process or a cluster of any size ran the trials;
* ``DIR/report.md``: the markdown report, this run's numbers beside the thesis's;
* the experiment's PNG plots;
* ``DIR/run.json``: how this run went (wall time, workers or scheduler, versions), which differs from run to
  run by design;
* ``DIR/timing.json``, when trials returned wall-clock measurements under their reserved ``"timing"`` key:
  those measurements, in trial order (they differ from run to run by design, and never reach ``summarize``
  or ``metrics.json``), and whatever the experiment's ``timing_report`` writes from them.

``run_all`` also writes ``DIR/summary.md`` and ``DIR/summary.json``: every experiment's findings (the thesis's
number beside this run's under each reading, and a verdict) in one table.
"""

from __future__ import annotations

import json
import platform
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from supportive.errors import ExperimentError
from supportive.experiments.execution import Executor, check_backend, open_executor
from supportive.experiments.output import (
    METRICS_FILE,
    REPORT_FILE,
    RUN_FILE,
    TIMING_FILE,
    check_folder,
    dump_json,
    write_folder,
    write_text,
)
from supportive.experiments.progress import progress_bar
from supportive.experiments.readings import Finding, findings_table, select_readings
from supportive.experiments.registry import (
    ALL,
    TIMING_KEY,
    Experiment,
    HeadlineRow,
    Metrics,
    TrialResult,
    get,
    names,
)
from supportive.experiments.trials import Trial

__all__ = [
    "DEFAULT_OUTPUT",
    "SUMMARY_FILE",
    "SUMMARY_JSON",
    "RunResult",
    "default_output",
    "reproduce",
    "run_all",
    "run_experiment",
    "summary_table",
]

DEFAULT_OUTPUT = Path("out/reproduce")
"""Where ``supportive reproduce`` writes when not told: ``out/reproduce/<name>``."""
SUMMARY_FILE = "summary.md"
"""Written by ``run_all``: one table of every experiment's findings."""
SUMMARY_JSON = "summary.json"
"""The same findings as plain JSON (deterministic for the same trials and seed)."""

_RESERVED = ("experiment", "title", "reference", "thesis", "seed", "trials", "readings")


@dataclass(frozen=True)
class RunResult:
    """What a run produced.

    Attributes:
        experiment: The experiment's name.
        trials: Number of trials run.
        seed: The run's seed.
        readings: The readings the run covered (the default first; empty for an experiment without).
        backend: Where the trials ran (``"in process"``, ``"dask LocalCluster, 2 worker processes"``, …).
        results: Each trial's result without its ``"timing"``, in trial order (what ``summarize`` saw).
        timings: The ``"timing"`` of each trial that returned one, in trial order (as in ``timing.json``);
            empty when no trial measured anything.
        metrics: The metrics, exactly as in ``metrics.json``.
        report: The markdown report.
        headline: A few (quantity, this run, the thesis) rows for a terminal summary.
        findings: The summary table's rows (empty when the experiment declares no ``findings``).
        output: The directory written, or ``None`` when nothing was written.
        files: The files written (metrics, report, plots, run info, timings).
        seconds: Wall time of the trials and the summary.
    """

    experiment: str
    trials: int
    seed: int
    readings: tuple[str, ...]
    backend: str
    results: tuple[TrialResult, ...]
    timings: tuple[dict[str, Any], ...]
    metrics: Metrics
    report: str
    headline: tuple[HeadlineRow, ...]
    findings: tuple[Finding, ...]
    output: Path | None
    files: tuple[Path, ...]
    seconds: float


def default_output(name: str) -> Path:
    """The default output directory of ``supportive reproduce NAME``: ``out/reproduce/<name>``, or
    ``out/reproduce`` for ``all`` (each experiment then writes into its own ``<name>/`` below it)."""
    return DEFAULT_OUTPUT if name == ALL else DEFAULT_OUTPUT / name


def run_experiment(
    name: str,
    trials: int | None = None,
    seed: int = 0,
    workers: int = 1,
    scheduler: str | None = None,
    output: str | Path | None = None,
    progress: bool = True,
    readings: Sequence[str] | None = None,
) -> RunResult:
    """Run the experiment registered as ``name``.

    Args:
        name: A registered experiment (see :func:`~supportive.experiments.registry.names`).
        trials: Number of trials; the experiment's ``default_trials`` (a full run) when ``None``.
        seed: The run's seed (int >= 0); each trial's own seed is spawned from it.
        workers: 1 runs the trials in this process; more starts a dask ``LocalCluster`` of that many worker
            processes (one thread each, on 127.0.0.1, no dashboard) for the run, or of as many as there are
            trials when there are fewer (one trial runs in this process: a worker would only wait).
        scheduler: Address of an existing dask scheduler (``tcp://HOST:PORT``) to run the trials on instead;
            its workers need ``supportive`` installed. Not together with ``workers`` > 1.
        output: Directory for ``metrics.json``, ``report.md``, the plots, ``run.json`` and, when trials
            measured times, ``timing.json`` and the experiment's timing files; ``None`` writes nothing.
        progress: Show a progress bar (only ever on a terminal).
        readings: Run only these of the experiment's readings (default: all of them, side by side).

    Raises:
        ExperimentError: for an unknown name or reading, bad arguments, an unreachable scheduler or an
            unwritable output.
        MissingExtraError: when dask (for ``workers`` > 1 or ``scheduler``) or matplotlib (for the plots) is
            not installed.

    >>> result = run_experiment("edge-reduction", trials=2, progress=False)
    >>> result.trials, result.metrics["experiment"], [t["subgoals"] for t in result.metrics["tasks"]]
    (2, 'edge-reduction', [10, 100])
    """
    experiment = get(name)
    chosen = select_readings(experiment.name, experiment.readings, readings)
    check_backend(workers, scheduler)
    specs = _specs(experiment, _trial_count(experiment, trials), seed, chosen)
    directory = _directory(output)
    with open_executor(_useful(workers, len(specs)), scheduler) as executor:
        return _run(experiment, executor, specs, seed, directory, progress, chosen)


def run_all(
    trials: int | None = None,
    seed: int = 0,
    workers: int = 1,
    scheduler: str | None = None,
    output: str | Path | None = None,
    progress: bool = True,
) -> list[RunResult]:
    """Run every registered experiment (every reading), in name order, on one executor; experiment ``x``
    writes into ``output/x/``, and ``output/summary.md`` (+ ``summary.json``) gathers their findings.
    Arguments as for :func:`run_experiment` (``trials`` applies to each experiment; the cluster has at most as
    many workers as the largest experiment has trials)."""
    experiments = [get(name) for name in names()]
    check_backend(workers, scheduler)
    readings = [select_readings(experiment.name, experiment.readings, None) for experiment in experiments]
    specs = [
        _specs(experiment, _trial_count(experiment, trials), seed, chosen)
        for experiment, chosen in zip(experiments, readings, strict=True)
    ]
    directory = _directory(output)
    with open_executor(_useful(workers, max(len(s) for s in specs)), scheduler) as executor:
        results = [
            _run(
                experiment,
                executor,
                trial_specs,
                seed,
                None if directory is None else directory / experiment.name,
                progress,
                chosen,
            )
            for experiment, trial_specs, chosen in zip(experiments, specs, readings, strict=True)
        ]
    if directory is not None:
        document = {
            "seed": seed,
            "trials": {r.experiment: r.trials for r in results},
            "experiments": [
                {
                    "experiment": r.experiment,
                    "reference": get(r.experiment).reference,
                    "readings": list(r.readings),
                    "findings": [f.as_json() for f in r.findings],
                }
                for r in results
            ],
        }
        table, findings = summary_table(results), dump_json(document, what="findings")
        write_folder(
            directory,
            lambda folder: [write_text(folder / SUMMARY_FILE, table), write_text(folder / SUMMARY_JSON, findings)],
        )
    return results


def summary_table(results: Sequence[RunResult]) -> str:
    """``summary.md``: one markdown table of every run's findings, with the seed and trial counts."""
    seeds = sorted({r.seed for r in results})
    counts = ", ".join(f"{r.experiment} {r.trials}" for r in results)
    rows = [(r.experiment, get(r.experiment).reference, r.findings) for r in results if r.findings]
    return (
        "# The thesis's experiments: this run beside the thesis\n\n"
        f"Seed {', '.join(map(str, seeds))}; trials: {counts}. Each experiment's `report.md` has the details, "
        "95 % confidence intervals and every reading's text.\n\n" + findings_table(rows) + "\n"
    )


def reproduce(
    name: str,
    trials: int | None = None,
    seed: int = 0,
    workers: int = 1,
    scheduler: str | None = None,
    output: str | Path | None = None,
    progress: bool = True,
    readings: Sequence[str] | None = None,
) -> list[RunResult]:
    """:func:`run_all` when ``name`` is ``"all"``, else :func:`run_experiment` (as a one-item list). What
    ``supportive reproduce`` calls; ``output`` defaults to :func:`default_output`.

    Raises:
        ExperimentError: as :func:`run_experiment`, and for ``readings`` with ``"all"``.
    """
    directory = default_output(name) if output is None else Path(output)
    if name == ALL:
        if readings:
            raise ExperimentError("readings are chosen for one experiment, not for 'all'")
        return run_all(trials, seed, workers, scheduler, directory, progress)
    return [run_experiment(name, trials, seed, workers, scheduler, directory, progress, readings or None)]


def _trial_count(experiment: Experiment, trials: int | None) -> int:
    if trials is None:
        return experiment.default_trials
    if isinstance(trials, bool) or not isinstance(trials, int) or trials < 1:
        raise ExperimentError(f"trials must be an int >= 1, got {trials!r}")
    if trials < experiment.fewest_trials:
        raise ExperimentError(
            f"{experiment.name}: at least {experiment.fewest_trials} trials (one of each kind it compares: "
            f"{', '.join(experiment.trial_kinds)}), got {trials}"
        )
    return trials


def _directory(output: str | Path | None) -> Path | None:
    """The output folder, checked before anything runs (it may not be a file)."""
    if output is None:
        return None
    check_folder(Path(output))
    return Path(output)


def _specs(experiment: Experiment, trials: int, seed: int, readings: tuple[str, ...]) -> Sequence[Trial]:
    """The experiment's trials (each reading's, when it has readings)."""
    if experiment.readings:
        return experiment.make_trials(trials, seed, readings=readings)
    return experiment.make_trials(trials, seed)


def _useful(workers: int, trials: int) -> int:
    """The workers worth starting for ``trials`` trials: no more than there are trials."""
    return max(1, min(workers, trials))


def _run(
    experiment: Experiment,
    executor: Executor,
    specs: Sequence[Trial],
    seed: int,
    output: Path | None,
    progress: bool,
    readings: tuple[str, ...],
) -> RunResult:
    started_at = datetime.now(UTC)
    started = time.perf_counter()
    with progress_bar(experiment.name, len(specs), enabled=progress) as advance:
        returned = executor.map(experiment.run_trial, specs, advance)
    for index, result in enumerate(returned):
        if not isinstance(result, dict):
            raise ExperimentError(
                f"experiment {experiment.name}: trial {index} returned {type(result).__name__}, not a dict"
            )
    results, timings = _split_timings(returned)
    timing_text = _timing_text(experiment, timings, seed) if timings else None
    summary = experiment.summarize(results)
    clash = sorted(set(summary) & set(_RESERVED))
    if clash:
        raise ExperimentError(f"experiment {experiment.name}: summarize() may not set {', '.join(clash)}")
    document: dict[str, Any] = {
        "experiment": experiment.name,
        "title": experiment.title,
        "reference": experiment.reference,
        "thesis": dict(experiment.thesis),
        "seed": seed,
        "trials": len(specs),
        **({"readings": list(readings)} if experiment.readings else {}),
        **summary,
    }
    text = dump_json(document)
    metrics: Metrics = json.loads(text)  # what report and plots see is exactly what the file holds
    report = experiment.report(metrics)
    headline = tuple(experiment.headline(metrics))
    findings = tuple(experiment.findings(metrics)) if experiment.findings is not None else ()
    seconds = time.perf_counter() - started

    def write(folder: Path) -> list[Path]:
        """Every file of the run, into ``folder`` (moved into ``output`` together once all are written)."""
        files = [write_text(folder / METRICS_FILE, text), write_text(folder / REPORT_FILE, report)]
        files.extend(experiment.plots(metrics, folder))
        info = _run_info(
            experiment, executor, len(specs), seed, started_at, seconds, time.perf_counter() - started
        )
        files.append(write_text(folder / RUN_FILE, dump_json(info, what="run info")))
        if timing_text is not None:
            files.append(write_text(folder / TIMING_FILE, timing_text))
            if experiment.timing_report is not None:
                files.extend(experiment.timing_report(json.loads(timing_text)["trials"], folder))
        return files

    files = write_folder(output, write) if output is not None else []
    return RunResult(
        experiment=experiment.name,
        trials=len(specs),
        seed=seed,
        readings=readings,
        backend=executor.description,
        results=tuple(results),
        timings=tuple(timings),
        metrics=metrics,
        report=report,
        headline=headline,
        findings=findings,
        output=output,
        files=tuple(files),
        seconds=seconds,
    )


def _split_timings(returned: list[TrialResult]) -> tuple[list[TrialResult], list[dict[str, Any]]]:
    """The trial results without their reserved ``"timing"`` key, and those timings in trial order."""
    results = [{key: value for key, value in r.items() if key != TIMING_KEY} for r in returned]
    timings = [r[TIMING_KEY] for r in returned if TIMING_KEY in r]
    return results, timings


def _timing_text(experiment: Experiment, timings: list[dict[str, Any]], seed: int) -> str:
    """What ``timing.json`` holds (checked to be plain JSON before anything is written)."""
    document = {
        "experiment": experiment.name,
        "seed": seed,
        "note": (
            "Wall-clock measurements of the trials, in trial order. They differ from run to run by design, "
            "so they are kept out of metrics.json."
        ),
        "trials": timings,
    }
    return dump_json(document, what="timings")


def _run_info(
    experiment: Experiment,
    executor: Executor,
    trials: int,
    seed: int,
    started_at: datetime,
    seconds: float,
    total: float,
) -> Mapping[str, Any]:
    from supportive import __version__

    return {
        "experiment": experiment.name,
        "trials": trials,
        "seed": seed,
        "backend": executor.description,
        "started": started_at.isoformat(timespec="seconds"),
        "seconds": round(seconds, 3),
        "seconds_with_files": round(total, 3),
        "python": platform.python_version(),
        "supportive": __version__,
    }
