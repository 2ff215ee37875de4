"""``declare``: an experiment is one declaration; its parts come from its modules by their field names."""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

from supportive.errors import ExperimentError
from supportive.experiments import (
    Reading,
    Trial,
    declare,
    get,
    names,
    run_experiment,
    spawn_trials,
    unregister,
)
from supportive.experiments.templates import render, section


def _make_trials(trials: int, seed: int) -> tuple[Trial, ...]:
    return spawn_trials(seed, [{} for _ in range(trials)])


def _run_trial(trial: Trial) -> dict[str, Any]:
    return {"index": trial.index}


def _summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    return {"indices": [r["index"] for r in results]}


def _report(metrics: Mapping[str, Any]) -> str:
    return f"# {metrics['title']}\n"


def _plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    return []


def _headline(metrics: Mapping[str, Any]) -> list[tuple[str, str, str]]:
    return [("trials", str(metrics["trials"]), "–")]


def _module(name: str, **attributes: Any) -> ModuleType:
    module = ModuleType(name)
    vars(module).update(attributes)
    return module


def _modules() -> tuple[ModuleType, ModuleType]:
    """A ``measure`` and a ``report`` module as an experiment package splits its parts (``summarize`` is in
    both, as when one imports it from the other: the same object is no clash)."""
    measure = _module(
        "toy.measure", make_trials=_make_trials, run_trial=_run_trial, summarize=_summarize, DEFAULT_TRIALS=3
    )
    report = _module("toy.report", report=_report, plots=_plots, headline=_headline, summarize=_summarize)
    return measure, report


@pytest.fixture
def cleanup() -> Iterator[list[str]]:
    declared: list[str] = []
    yield declared
    for name in declared:
        if name in names():
            unregister(name)


def test_parts_come_from_the_modules_and_optional_ones_default(cleanup: list[str]) -> None:
    experiment = declare(name="toy-declared", title="A toy", reference="nowhere", parts=_modules())
    cleanup.append(experiment.name)
    assert get("toy-declared") is experiment
    assert experiment.make_trials is _make_trials and experiment.report is _report
    assert experiment.default_trials == 3 and dict(experiment.thesis) == {} and experiment.readings == ()
    assert experiment.findings is None and experiment.timing_report is None
    result = run_experiment("toy-declared", progress=False)
    assert result.metrics["indices"] == [0, 1, 2] and result.report == "# A toy\n"


def test_constants_and_given_fields(cleanup: list[str]) -> None:
    measure, report = _modules()
    vars(report)["THESIS"] = {"answer": 42}
    vars(measure)["READINGS"] = (Reading("plain", "as written", "the text"),)

    def other_plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
        return []

    experiment = declare(
        name="toy-given", title="A toy", reference="nowhere", parts=(measure, report), plots=other_plots
    )
    cleanup.append(experiment.name)
    assert experiment.thesis == {"answer": 42} and experiment.default_reading == "plain"
    assert experiment.plots is other_plots


def test_a_missing_part_is_named() -> None:
    measure, report = _modules()
    del report.headline
    with pytest.raises(ExperimentError, match=r"experiment toy-missing: no headline in measure, report"):
        declare(name="toy-missing", title="A toy", reference="nowhere", parts=(measure, report))
    assert "toy-missing" not in names()


def test_two_modules_with_different_parts_of_one_name_are_refused() -> None:
    measure, report = _modules()
    vars(report)["make_trials"] = lambda trials, seed: ()
    with pytest.raises(ExperimentError, match="measure, report hold different make_trials"):
        declare(name="toy-twice", title="A toy", reference="nowhere", parts=(measure, report))


def test_an_unknown_field_is_refused() -> None:
    with pytest.raises(ExperimentError, match="declare\\(\\) has no field plot"):
        declare(name="toy-typo", title="A toy", reference="nowhere", parts=_modules(), plot=_plots)


def test_every_builtin_is_declared_once_with_its_parts() -> None:
    for name in names():
        experiment = get(name)
        assert experiment.findings is not None, name  # every built-in has a summary row
        assert callable(experiment.report) and callable(experiment.headline), name


PACKAGE = "supportive.experiments.learner_settings"


def test_render_needs_exactly_the_placeholders() -> None:
    with pytest.raises(ExperimentError, match=r"missing values \['chosen', .*values it has no place for \['nope'\]"):
        render(PACKAGE, "report.md", nope="x")
    with pytest.raises(ExperimentError, match="no package"):
        render(None, "report.md")


def test_render_fills_in_text_and_lines() -> None:
    values = {
        "sizes": "1–2", "share": "5%", "clean_demonstrations": "3–4", "grid": "g", "chosen": "c",
        "resamples": "9", "untold": "u.",
    }
    text = render(PACKAGE, "report.md", table=["| a |", "| b |"], spread=["| s |"], **values)
    assert text.startswith("# Learner settings") and "Chosen: **c**.\n\n| a |\n| b |\n\nHow sure" in text
    assert text.endswith("the best worst F1. u.\n\n| s |\n")
    assert "Generated tasks of 1–2 steps" in text and "resampled 9 times" in text and "$" not in text
    part = section(PACKAGE, "report.md", table="t", spread="s", **values)
    assert part.startswith("\n\n# Learner settings") and part.endswith("the best worst F1. u.\n\ns")
