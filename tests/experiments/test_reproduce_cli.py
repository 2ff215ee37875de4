from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

from supportive.cli import main
from supportive.experiments.plotting import PNG_SIGNATURE


def run(
    args: list[str], capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> tuple[int, str, str]:
    monkeypatch.setattr(sys, "argv", ["supportive", *args])
    try:
        main()
        code = 0
    except SystemExit as exc:
        code = int(exc.code or 0)
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_unknown_name(capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    code, out, err = run(["reproduce", "nope"], capsys, monkeypatch)
    assert code == 2 and out == ""
    assert err.count("\n") == 1
    assert "unknown experiment 'nope'" in err and "edge-reduction" in err and "all" in err


def test_workers_and_scheduler_exclude_each_other(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    args = ["reproduce", "edge-reduction", "--workers", "2", "--scheduler", "tcp://127.0.0.1:8786"]
    code, out, err = run(args, capsys, monkeypatch)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "--workers and --scheduler are mutually exclusive" in err


def test_bad_scheduler_address(capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    code, _, err = run(["reproduce", "edge-reduction", "--scheduler", "localhost"], capsys, monkeypatch)
    assert code == 2 and err.count("\n") == 1 and "expected tcp://HOST:PORT" in err


def test_small_run_writes_metrics_report_and_plots(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    code, out, _ = run(["reproduce", "edge-reduction", "--trials", "3", "--seed", "1"], capsys, monkeypatch)
    assert code == 0
    directory = tmp_path / "out" / "reproduce" / "edge-reduction"
    assert "out/reproduce/edge-reduction" in out and "metrics.json" in out
    assert "2.84 (1.99–3.61)" in out
    metrics = json.loads((directory / "metrics.json").read_text())
    assert metrics["trials"] == 3 and metrics["seed"] == 1
    assert "2.84" in (directory / "report.md").read_text()
    assert (directory / "edges.png").read_bytes()[:8] == PNG_SIGNATURE


def test_all_writes_one_directory_per_experiment(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    code, _, _ = run(["reproduce", "all", "--trials", "2", "-o", str(tmp_path)], capsys, monkeypatch)
    assert code == 0
    assert (tmp_path / "edge-reduction" / "metrics.json").is_file()
