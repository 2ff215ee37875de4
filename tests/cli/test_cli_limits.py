"""Command-line numbers, maps and scenarios at and past their limits (issue 15): exit 2 and one clear line, no
traceback, nothing computed first."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from supportive.io.limits import MAX_MAP_CELLS

CliRunner = Callable[[list[str]], tuple[int, str, str]]


def open_map(side: int) -> str:
    rows = ["#" * side] + ["#" + "." * (side - 2) + "#" for _ in range(side - 2)] + ["#" * side]
    rows[1] = "#B" + "." * (side - 3) + "#"
    return "\n".join(rows) + "\n"


@pytest.mark.parametrize(
    ("text", "problem"),
    [
        ("####\n#B.#\n####\n", "the play area has 1 floor cell: the novice and the caregiver need at least two"),
        (open_map(200), ":1: the map is larger than 120 × 120 cells, the limit"),
        (
            open_map(60),
            "the play area has 3,363 floor cells, more than 2,500, the limit (the caregiver's model grows with the "
            "square of it)",
        ),
    ],
)
def test_unusable_maps_are_refused_before_any_work(tmp_path: Path, cli: CliRunner, text: str, problem: str) -> None:
    path = tmp_path / "m.map"
    path.write_text(text)
    code, out, err = cli(["caregiver", "--map", str(path), "--steps", "2"])
    assert code == 2 and out == "" and err == f"supportive: error: {path}{'' if problem.startswith(':') else ': '}{problem}\n"


def test_the_largest_play_area_runs(tmp_path: Path, cli: CliRunner) -> None:
    path = tmp_path / "big.map"
    path.write_text(open_map(51))
    assert MAX_MAP_CELLS >= (51 - 2) ** 2 - 1
    code, out, err = cli(["caregiver", "--map", str(path), "--steps", "2", "--every", "5"])
    assert code == 0, err
    assert "cells explored" in out


@pytest.mark.parametrize(
    "args",
    [
        ["caregiver", "--delay", "inf"],
        ["caregiver", "--delay", "nan"],
        ["caregiver", "--seed", "-5"],
        ["generate", "--seed", "-5"],
        ["generate", "--actions", "1000000000"],
        ["teach", "x.yaml", "--seed", "-1"],
        ["workbench-sim", "--seconds", "inf"],
        ["infer", "x.yaml", "-O", "s.jsonl", "--mean-duration", "nan"],
        ["serve", "--client-timeout", "nan"],
    ],
)
def test_numbers_out_of_range_are_usage_errors(cli: CliRunner, args: list[str]) -> None:
    code, out, err = cli(args)
    assert code == 2 and out == "" and "Traceback" not in err
    assert "Invalid value for" in err


@pytest.mark.parametrize(("value", "problem"), [(".inf", "finite number"), (".nan", "finite number"), ("1e300", "expected at most 10000")])
def test_circuit_table_sizes_must_be_finite_and_sane(tmp_path: Path, cli: CliRunner, value: str, problem: str) -> None:
    path = tmp_path / "table.yaml"
    path.write_text(f"name: t\ntable: {{width: {value}, depth: 70}}\nscatter: {{seed: 1, pieces: {{battery: 2, led: 1}}}}\n")
    code, out, err = cli(["support", str(path)])
    assert code == 2 and out == "" and err.startswith(f"supportive: error: {path}:2: table.width: ") and problem in err


@pytest.mark.parametrize(
    "args",
    [
        ["reproduce", "edge-reduction", "--trials", "1"],
        ["caregiver", "--steps", "2", "--gif", "episode.gif"],
        ["support", "two-cells-led", "--render", "table.png"],
    ],
)
def test_a_missing_plot_extra_is_said_before_any_work(tmp_path: Path, cli: CliRunner, monkeypatch: pytest.MonkeyPatch, args: list[str]) -> None:
    import sys

    monkeypatch.chdir(tmp_path)
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # as if the plot extra were not installed
    code, out, err = cli([*args, "--output", "out"] if args[0] == "reproduce" else args)
    assert code == 2 and out == "", out  # nothing computed or printed first
    assert err.strip().endswith("needs matplotlib, which is not installed: pip install 'supportive[plot]'")
    assert len(err.strip().splitlines()) == 1 and list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    ("command", "text", "problem"),
    [
        (
            ["learn"],
            "name: t\ndemonstrations:\n  - steps: [{action: a, state: [x]}, {action: b, state: [y]}]\n"
            "  - steps: [{action: b, state: [x]}, {action: a, state: [z]}]\n",
            "demonstration d2: state ['x'] is reached after different actions",
        ),
        (["chat"], "name: t\nactions: [a]\n", "task 't' has no structure to enumerate states from"),
        (["serve", "--port", "1", "--task"], "name: t\nactions: [a]\n", "task 't' has no structure and no demonstrations"),
        (["serve", "--port", "1", "--lead-only", "zz", "--task"], "name: t\ndemonstrations:\n  - steps: [a, b]\n", "lead-only names that are no subtask's: zz"),
    ],
)
def test_errors_about_a_files_contents_name_the_file(tmp_path: Path, cli: CliRunner, command: list[str], text: str, problem: str) -> None:
    path = tmp_path / "t.yaml"
    path.write_text(text)
    code, out, err = cli([*command, str(path)])
    assert code == 2 and out == "" and err.startswith(f"supportive: error: {path}: ") and problem in err, err
    assert len(err.strip().splitlines()) == 1
