"""The numbers docs/experiments.md quotes from small runs match a fresh run of the same command.

The table between the ``small-runs`` markers lists commands (``supportive reproduce NAME -n N [--seed S]
[--reading R]``), a quantity of the experiment's findings (the rows of ``summary.md``), a reading (empty for
none) and the value the run gave. Each command is run again here and every value compared as text.
"""

from __future__ import annotations

import re
import shlex
from functools import cache
from pathlib import Path

import pytest

from supportive.experiments import RunResult, run_experiment

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


@cache
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


def test_the_docs_quote_small_runs() -> None:
    rows = _rows()
    assert len(rows) >= 8 and len({r[0] for r in rows}) >= 6  # every experiment's section has one


@pytest.mark.parametrize(("command", "quantity", "reading", "value"), _rows())
def test_a_quoted_number_matches_a_fresh_run(command: str, quantity: str, reading: str, value: str) -> None:
    result = _run(command)
    finding = next((f for f in result.findings if f.quantity == quantity), None)
    assert finding is not None, f"{command}: no finding {quantity!r}; it has {[f.quantity for f in result.findings]}"
    assert finding.value(reading) == value, f"{command}: {quantity} ({reading or 'no reading'})"
