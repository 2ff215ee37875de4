"""The registry of experiments, by name.

An :class:`Experiment` says what the thesis reports and how to reproduce it: how to make its trials, a
module-level (picklable) function that runs one trial and returns plain JSON data, and how to turn the trials'
results into metrics, a markdown report (this run's numbers beside the thesis's) and plots.

Each built-in experiment is one :func:`declare` call in its package's ``__init__``: its name, title and
reference, and the modules that hold its parts under the field names (``make_trials``, ``run_trial``, …);
they register themselves the first time the registry is asked for a name.

>>> "edge-reduction" in names()
True
>>> get("edge-reduction").reference
'§2.1.7.2–2.1.7.3, Figure 2.5'
"""

from __future__ import annotations

import importlib
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType
from typing import Any, TypeAlias

from supportive.errors import ExperimentError
from supportive.experiments.readings import Finding, Reading
from supportive.experiments.trials import Trial

__all__ = [
    "ALL",
    "TIMING_KEY",
    "Experiment",
    "HeadlineRow",
    "Metrics",
    "TrialResult",
    "declare",
    "get",
    "names",
    "register",
    "unregister",
]

ALL = "all"
"""The name that stands for every registered experiment (never an experiment's own name)."""

TrialResult: TypeAlias = dict[str, Any]
"""What one trial returns: a JSON object (plain dicts, lists, str, int, float, bool, None)."""

TIMING_KEY = "timing"
"""The reserved key of a trial result that holds its wall-clock measurements (plain JSON data), which differ
from run to run: the runner keeps them out of ``summarize`` and ``metrics.json`` (see
:attr:`Experiment.timing_report`)."""

Metrics: TypeAlias = dict[str, Any]
"""What an experiment's ``summarize`` returns, and what ``metrics.json`` holds: plain JSON data."""

HeadlineRow: TypeAlias = tuple[str, str, str]
"""One line of a run's short summary: (quantity, this run, the thesis)."""

_NAME = re.compile(r"^[a-z0-9]+(?:-[a-z0-9]+)*$")
_BUILTINS = (
    "supportive.experiments.edge_reduction",
    "supportive.experiments.goal_inference",
    "supportive.experiments.active_learning",
    "supportive.experiments.captaincook",
    "supportive.experiments.captaincook_prediction",
    "supportive.experiments.generalisation",
    "supportive.experiments.learner_settings",
    "supportive.experiments.selection_settings",
    "supportive.experiments.mistake_detection",
    "supportive.experiments.transfer",
    "supportive.experiments.caregiver",
    "supportive.experiments.support_tamp",
)
_registry: dict[str, Experiment] = {}
_builtins_loaded = False


@dataclass(frozen=True)
class Experiment:
    """One of the thesis's experiments, and how to reproduce it.

    Attributes:
        name: Registry name: lowercase words joined by hyphens (``edge-reduction``); not ``all``.
        title: One line for people.
        reference: Where the thesis reports it (section, figure).
        thesis: The thesis's own numbers where it gives them (plain JSON data), for the report.
        default_trials: Trials of a full run (the thesis's sample size).
        trial_kinds: The kinds of case a run must hold a trial of each of, because its summary compares them
            (a generated task and a recipe, say); empty when any one trial will do. See :attr:`fewest_trials`.
        make_trials: ``(trials, seed) -> trials``; every trial gets its own seed (see
            :func:`~supportive.experiments.trials.spawn_trials`). An experiment with ``readings`` is called
            ``make_trials(trials, seed, readings=names)`` with the readings the run covers.
        run_trial: Runs ONE trial and returns plain JSON data (a dict; its key ``"timing"`` is reserved for
            wall-clock measurements, see ``timing_report``). A module-level function, so that it can be sent
            to worker processes.
        summarize: Trial results without their ``"timing"``, in trial order -> metrics (plain JSON data, no
            timings: the same trials give the same metrics).
        report: Metrics -> a markdown report with this run's numbers beside the thesis's.
        plots: ``(metrics, directory) -> files`` written there (PNG).
        headline: Metrics -> a few (quantity, this run, the thesis) rows for a terminal summary.
        timing_report: Optional ``(timings, directory) -> files``: writes the experiment's own files about its
            wall-clock measurements (``timing.md``, ``timing.png``, …). A trial may return its measurements,
            which are not deterministic, under the reserved key ``"timing"``; the runner removes that key
            from every result before ``summarize``, writes the timings (in trial order, of the trials that
            returned one) to ``timing.json`` and passes them here, read back from that file. Called only when
            the run writes files and some trial returned timings.
        readings: The readings of under-specified details of the thesis the experiment runs side by side
            (see :mod:`supportive.experiments.readings`), the default (closest to the thesis's text) first;
            empty when there is nothing to read two ways.
        findings: Optional metrics -> the rows of the summary table (:class:`~.readings.Finding`): quantity,
            the thesis's number, this run's number under each reading, verdict.
    """

    name: str
    title: str
    reference: str
    thesis: Mapping[str, Any]
    default_trials: int
    make_trials: Callable[..., Sequence[Trial]] = field(repr=False)
    run_trial: Callable[[Trial], TrialResult] = field(repr=False)
    summarize: Callable[[Sequence[TrialResult]], Metrics] = field(repr=False)
    report: Callable[[Mapping[str, Any]], str] = field(repr=False)
    plots: Callable[[Mapping[str, Any], Path], list[Path]] = field(repr=False)
    headline: Callable[[Mapping[str, Any]], list[HeadlineRow]] = field(repr=False)
    timing_report: Callable[[list[dict[str, Any]], Path], list[Path]] | None = field(default=None, repr=False)
    readings: tuple[Reading, ...] = ()
    trial_kinds: tuple[str, ...] = ()
    findings: Callable[[Mapping[str, Any]], list[Finding]] | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        if not _NAME.match(self.name) or self.name == ALL:
            raise ExperimentError(
                f"experiment name {self.name!r}: expected lowercase words joined by hyphens, not {ALL!r}"
            )
        if self.default_trials < 1:
            raise ExperimentError(
                f"experiment {self.name}: default_trials must be >= 1, got {self.default_trials}"
            )
        if len(set(self.trial_kinds)) != len(self.trial_kinds) or self.fewest_trials > self.default_trials:
            raise ExperimentError(
                f"experiment {self.name}: trial_kinds must be distinct and no more than default_trials "
                f"({self.default_trials}), got {list(self.trial_kinds)}"
            )
        names = [r.name for r in self.readings]
        if len(set(names)) != len(names):
            raise ExperimentError(f"experiment {self.name}: reading names must be unique, got {names}")

    @property
    def fewest_trials(self) -> int:
        """The fewest trials a run may have: one of each of :attr:`trial_kinds` (at least one); the runner
        refuses fewer before anything runs."""
        return max(1, len(self.trial_kinds))

    @property
    def default_reading(self) -> str | None:
        """The default reading's name (the first), or None without readings."""
        return self.readings[0].name if self.readings else None


def _load_builtins() -> None:
    global _builtins_loaded
    if not _builtins_loaded:
        _builtins_loaded = True
        for module in _BUILTINS:
            importlib.import_module(module)


def register(experiment: Experiment, *, replace: bool = False) -> Experiment:
    """Add ``experiment`` to the registry under its name and return it.

    Args:
        experiment: The experiment.
        replace: Replace an experiment registered under the same name instead of refusing.

    Raises:
        ExperimentError: when the name is taken and ``replace`` is false.
    """
    if not replace and experiment.name in _registry and _registry[experiment.name] is not experiment:
        raise ExperimentError(f"an experiment named {experiment.name!r} is already registered")
    _registry[experiment.name] = experiment
    return experiment


_PARTS = ("make_trials", "run_trial", "summarize", "report", "plots", "headline", "timing_report", "findings")
"""The fields :func:`declare` takes from the modules under their own names (the last two may be missing)."""
_CONSTANTS = {
    "default_trials": "DEFAULT_TRIALS",
    "trial_kinds": "TRIAL_KINDS",
    "thesis": "THESIS",
    "readings": "READINGS",
}
"""The fields :func:`declare` takes from the modules' constants (all but ``DEFAULT_TRIALS`` may be missing)."""
_OPTIONAL: dict[str, Any] = {
    "timing_report": None,
    "findings": None,
    "thesis": {},
    "readings": (),
    "trial_kinds": (),
}


def declare(
    *, name: str, title: str, reference: str, parts: Sequence[ModuleType], **given: Any
) -> Experiment:
    """Build the experiment ``name`` from its modules and register it: the one declaration of an experiment.

    Every other field of :class:`Experiment` is looked up in ``parts``: the functions under their field
    names (``make_trials``, ``run_trial``, ``summarize``, ``report``, ``plots``, ``headline`` and, when
    there, ``timing_report`` and ``findings``) and the constants ``DEFAULT_TRIALS`` and, when there,
    ``TRIAL_KINDS``, ``THESIS`` and ``READINGS``. A field given as a keyword is taken as given instead.

    Raises:
        ExperimentError: when a required part is in none of the modules, when two modules hold different
            objects under one part's name, or for what :class:`Experiment` and :func:`register` refuse.

    >>> from supportive.experiments.edge_reduction import measure, report
    >>> declare(name="edge-reduction", title="x", reference="y", parts=(measure, report))
    Traceback (most recent call last):
    ...
    supportive.errors.ExperimentError: experiment edge-reduction: no summarize in measure, report
    """
    unknown = sorted(set(given) - {*_PARTS, *_CONSTANTS})
    if unknown:
        raise ExperimentError(f"experiment {name}: declare() has no field {', '.join(unknown)}")
    values: dict[str, Any] = {}
    for key in (*_PARTS, *_CONSTANTS):
        if key in given:
            values[key] = given[key]
            continue
        attribute = _CONSTANTS.get(key, key)
        found = {id(v): v for m in parts if (v := getattr(m, attribute, None)) is not None}
        if len(found) > 1:
            raise ExperimentError(f"experiment {name}: {_where(parts, attribute)} hold different {attribute}")
        if found:
            values[key] = next(iter(found.values()))
        elif key in _OPTIONAL:
            values[key] = _OPTIONAL[key]
        else:
            raise ExperimentError(f"experiment {name}: no {attribute} in {_where(parts)}")
    return register(Experiment(name=name, title=title, reference=reference, **values))


def _where(parts: Sequence[ModuleType], attribute: str | None = None) -> str:
    return ", ".join(
        m.__name__.rsplit(".", 1)[-1] for m in parts if attribute is None or hasattr(m, attribute)
    )


def unregister(name: str) -> None:
    """Remove the experiment registered as ``name``.

    Raises:
        ExperimentError: when no experiment has that name.
    """
    _load_builtins()
    if name not in _registry:
        raise ExperimentError(_unknown(name))
    del _registry[name]


def get(name: str) -> Experiment:
    """The experiment registered as ``name``.

    Raises:
        ExperimentError: when no experiment has that name (the message lists the known names).
    """
    _load_builtins()
    try:
        return _registry[name]
    except KeyError:
        raise ExperimentError(_unknown(name)) from None


def names() -> tuple[str, ...]:
    """The registered experiments' names, sorted."""
    _load_builtins()
    return tuple(sorted(_registry))


def _unknown(name: str) -> str:
    known = ", ".join([ALL, *sorted(_registry)])
    return f"unknown experiment {name!r}: known experiments are {known}"
