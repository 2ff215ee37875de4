"""Every experiment's report, rendered from fixed metrics, is the text it was when its prose moved into
templates, byte for byte.

Each folder of ``reports/`` holds the ``metrics.json`` of a small run (``supportive reproduce NAME -n N
--seed S``; the folder name ends in ``-seed-1`` for seed 1) and the ``report.md`` the f-string builders wrote
from it before the move; ``goal-inference`` also holds a timing document (``timing.json``, as
:func:`~supportive.experiments.goal_inference.timing.timing_summary` makes it) and the ``timing.md`` written
from it. A change to a report's wording shows here first: record the new text on purpose.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from supportive.experiments import get, names
from supportive.experiments.goal_inference.report import timing_markdown

REPORTS = Path(__file__).parent / "reports"
CASES = sorted(p for p in REPORTS.iterdir() if p.is_dir())


def _read(path: Path) -> str:
    return path.read_text(encoding="utf-8")


def test_every_experiment_has_a_recorded_report() -> None:
    recorded = {json.loads(_read(case / "metrics.json"))["experiment"] for case in CASES}
    assert recorded == set(names())


@pytest.mark.parametrize("case", CASES, ids=lambda case: case.name)
def test_the_report_is_the_recorded_text(case: Path) -> None:
    metrics = json.loads(_read(case / "metrics.json"))
    assert get(metrics["experiment"]).report(metrics) == _read(case / "report.md")


def test_the_timing_report_is_the_recorded_text() -> None:
    case = REPORTS / "goal-inference"
    assert timing_markdown(json.loads(_read(case / "timing.json"))) == _read(case / "timing.md")
