"""A run's progress when stderr is not a terminal (piped, logged, CI): a line every few seconds, so a long
run is never silent (issue 16.6)."""

from __future__ import annotations

import re

import pytest

from supportive.experiments import progress, run_experiment


def test_a_run_off_a_terminal_prints_a_progress_line_every_period(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr(progress, "PERIOD", 0.005)
    result = run_experiment("edge-reduction", trials=4)
    lines = capsys.readouterr().err.splitlines()
    assert result.trials == 4 and lines
    assert all(re.fullmatch(r"edge-reduction: [0-4]/4 trials, 0:\d\d", line) for line in lines), lines
    counts = [int(line.split()[1].split("/")[0]) for line in lines]
    assert counts == sorted(counts)  # it only goes forward


def test_disabled_progress_prints_nothing(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(progress, "PERIOD", 0.005)
    run_experiment("edge-reduction", trials=2, progress=False)
    assert capsys.readouterr().err == ""
