"""The numbers docs/experiments.md quotes from small runs match a fresh run of the same command.

The table between the ``small-runs`` markers lists commands (``supportive reproduce NAME -n N [--seed S]
[--reading R]``), a quantity of the experiment's findings (the rows of ``summary.md``), a reading (empty for
none) and the value the run gave. Each command is run again here and every value compared as text, but for
the runs other tests make anyway, whose rows are compared there, on that run (:func:`check_quoted`): the
README's own ``reproduce`` lines (tests/test_new_user.py runs them with the experiment's fewest trials and
seed 0) and the runs in :data:`CHECKED_WHERE_RUN`.
"""

from __future__ import annotations

import json
import re
import shlex
from collections.abc import Sequence
from pathlib import Path

import pytest

from supportive import experiments
from supportive.experiments import RunResult, run_experiment
from supportive.experiments.readings import Finding

DOCS = Path(__file__).resolve().parents[2] / "docs" / "experiments.md"
_ROW = re.compile(r"^\| `(?P<command>supportive reproduce [^`]+)` \| (?P<quantity>.+?) \| (?P<reading>[^|]*) \| (?P<value>.+) \|$")


def _rows() -> list[tuple[str, str, str, str]]:
    text = DOCS.read_text(encoding="utf-8")
    block = text.split("<!-- small-runs -->", 1)[1].split("<!-- /small-runs -->", 1)[0]
    rows = []
    for line in block.splitlines():
        match = _ROW.match(line.strip())
        if match:
            rows.append(tuple(match.group(k).strip() for k in ("command", "quantity", "reading", "value")))
    return rows  # type: ignore[return-value]


def _run(command: str) -> RunResult:
    words = shlex.split(command)[2:]
    name, trials, seed, readings = words[0], None, 0, []
    rest = iter(words[1:])
    for word in rest:
        if word in ("-n", "--trials"):
            trials = int(next(rest))
        elif word == "--seed":
            seed = int(next(rest))
        elif word in ("-r", "--reading"):
            readings.append(next(rest))
        else:
            raise AssertionError(f"docs/experiments.md: unexpected option {word!r} in {command!r}")
    return run_experiment(name, trials=trials, seed=seed, readings=readings or None, progress=False)


CHECKED_WHERE_RUN = {
    "supportive reproduce goal-inference -n 3 --seed 4": "tests/experiments/test_goal_inference.py",
    "supportive reproduce caregiver -n 3 --seed 5": "tests/experiments/test_caregiver_experiment.py",
    "supportive reproduce transfer -n 2 --seed 1": "tests/experiments/test_transfer.py",
}
"""Commands of the table whose run the experiment's own test module makes (in process, the same trials and
seed); that module checks their rows."""


def readme_run(args: Sequence[str]) -> str | None:
    """The small-runs command a README ``reproduce`` line makes when run with its experiment's fewest trials
    (as tests/test_new_user.py runs it): ``supportive reproduce NAME -n N``; None when the line sets anything
    but the workers (a seed or a reading: another run)."""
    if args[:1] != ["reproduce"] or len(args) < 2:
        return None
    options = list(args[2:])
    if options[:1] == ["--workers"]:
        options = options[2:]
    return f"supportive reproduce {args[1]} -n {experiments.get(args[1]).fewest_trials}" if not options else None


def _readme_runs() -> set[str]:
    from tests.test_new_user import COMMANDS

    return {run for args in COMMANDS if (run := readme_run(args)) is not None}


def check_quoted(command: str, output: Path) -> int:
    """Check every value the docs quote for ``command`` against the run of it written to ``output`` (its
    metrics.json, read by the experiment's ``findings``); how many values were checked."""
    name = shlex.split(command)[2]
    metrics = json.loads((output / "metrics.json").read_text(encoding="utf-8"))
    findings = experiments.get(name).findings
    return _compare(command, findings(metrics) if findings is not None else [])


def _compare(command: str, findings: Sequence[Finding]) -> int:
    """Compare the docs' values for ``command`` with ``findings``; how many were compared."""
    checked = 0
    for quoted, quantity, reading, value in _rows():
        if quoted != command:
            continue
        finding = next((f for f in findings if f.quantity == quantity), None)
        assert finding is not None, f"{command}: no finding {quantity!r}; it has {[f.quantity for f in findings]}"
        assert finding.value(reading) == value, f"{command}: {quantity} ({reading or 'no reading'})"
        checked += 1
    return checked


def test_the_docs_quote_small_runs() -> None:
    rows = _rows()
    assert len(rows) >= 8 and len({r[0] for r in rows}) >= 6  # every experiment's section has one


@pytest.mark.parametrize("command", sorted({row[0] for row in _rows()} - _readme_runs() - set(CHECKED_WHERE_RUN)))
def test_a_quoted_number_matches_a_fresh_run(command: str) -> None:
    assert _compare(command, _run(command).findings)


def test_the_runs_checked_where_they_are_made_are_in_the_table() -> None:
    assert set(CHECKED_WHERE_RUN) <= {row[0] for row in _rows()}
