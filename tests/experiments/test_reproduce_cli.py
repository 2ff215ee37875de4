from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

import pytest

from supportive.experiments import registry
from supportive.experiments.plotting import PNG_SIGNATURE

CliRunner = Callable[[list[str]], tuple[int, str, str]]


def test_unknown_name(cli: CliRunner) -> None:
    code, out, err = cli(["reproduce", "nope"])
    assert code == 2 and out == ""
    assert err.count("\n") == 1
    assert "unknown experiment 'nope'" in err and "edge-reduction" in err and "all" in err


def test_workers_and_scheduler_exclude_each_other(cli: CliRunner) -> None:
    args = ["reproduce", "edge-reduction", "--workers", "2", "--scheduler", "tcp://127.0.0.1:8786"]
    code, out, err = cli(args)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "--workers and --scheduler are mutually exclusive" in err


def test_bad_scheduler_address(cli: CliRunner) -> None:
    code, _, err = cli(["reproduce", "edge-reduction", "--scheduler", "localhost"])
    assert code == 2 and err.count("\n") == 1 and "expected tcp://HOST:PORT" in err


def test_small_run_writes_metrics_report_and_plots(
    tmp_path: Path, cli: CliRunner, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    code, out, _ = cli(["reproduce", "edge-reduction", "--trials", "3", "--seed", "1"])
    assert code == 0
    directory = tmp_path / "out" / "reproduce" / "edge-reduction"
    assert "out/reproduce/edge-reduction" in out and "metrics.json" in out
    assert "2.84 (1.99–3.61)" in out
    metrics = json.loads((directory / "metrics.json").read_text())
    assert metrics["trials"] == 3 and metrics["seed"] == 1
    assert "2.84" in (directory / "report.md").read_text()
    assert (directory / "edges.png").read_bytes()[:8] == PNG_SIGNATURE


QUICK = ("caregiver", "edge-reduction", "transfer")
"""Three experiments that run in seconds: the registry ``all`` runs over in the test below."""


def test_all_writes_one_directory_per_experiment_and_the_summary_table(
    tmp_path: Path, cli: CliRunner, monkeypatch: pytest.MonkeyPatch
) -> None:
    """``all`` over a registry of three quick experiments: every experiment's small run is tested in its own
    module, and every registered experiment's findings in the summary are checked against its recorded full
    run (tests/test_docs_numbers.py), so running them all again here would test nothing more (it took 50 s)."""
    assert set(QUICK) < set(registry.names())
    monkeypatch.setattr(registry, "_registry", {name: registry.get(name) for name in QUICK})
    code, out, _ = cli(["reproduce", "all", "--trials", "2", "-o", str(tmp_path)])
    assert code == 0 and "summary.md" in out
    assert sorted(p.name for p in tmp_path.iterdir() if p.is_dir()) == list(QUICK)
    for name in QUICK:
        assert (tmp_path / name / "metrics.json").is_file() and f"{name}: 2 trials" in out
    summary = (tmp_path / "summary.md").read_text()
    document = json.loads((tmp_path / "summary.json").read_text())
    assert [e["experiment"] for e in document["experiments"]] == list(QUICK)
    assert document["trials"] == dict.fromkeys(QUICK, 2)
    for entry in document["experiments"]:
        assert entry["findings"], entry["experiment"]
        assert f"| {entry['experiment']} | {entry['reference']} |" in summary
        for finding in entry["findings"]:
            assert [v["reading"] for v in finding["values"] if v["reading"]] in ([], entry["readings"], entry["readings"][:1])


def test_a_reading_is_chosen_by_name(tmp_path: Path, cli: CliRunner) -> None:
    code, _, err = cli(["reproduce", "transfer", "--reading", "sideways", "-n", "1", "-o", str(tmp_path)])
    assert code == 2 and err.count("\n") == 1 and "unknown reading 'sideways'" in err and "any-order" in err
    code, _, err = cli(["reproduce", "all", "--reading", "any-order", "-o", str(tmp_path)])
    assert code == 2 and "not for 'all'" in err
    code, _, _ = cli(["reproduce", "caregiver", "-r", "per-step", "-n", "1", "-o", str(tmp_path / "cg")])
    assert code == 0
    assert json.loads((tmp_path / "cg" / "metrics.json").read_text())["readings"] == ["per-step"]
