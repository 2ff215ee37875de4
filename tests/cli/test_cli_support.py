"""``supportive support``: the decision in words or JSON, a picture, a simulation; bad files exit 2."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

import pytest

from supportive.envs.circuits.scenario import parse_scenario_file, parse_scenario_string
from supportive.errors import ScenarioFileError
from supportive.examples import circuit_names, circuit_path
from supportive.experiments.plotting import PNG_SIGNATURE

CliRunner = Callable[[list[str]], tuple[int, str, str]]


@pytest.mark.parametrize("name", circuit_names())
def test_every_shipped_scenario_reads_and_advises(name: str, cli: CliRunner) -> None:
    path = circuit_path(name)
    scenario = parse_scenario_file(path)
    assert scenario.world.items and scenario.plans()
    code, out, err = cli(["support", str(path), "--environments", "40", "--json"])
    assert code == 0, err
    report = json.loads(out)
    assert report["scenario"] == scenario.name and report["plans"] == len(scenario.plans())
    assert report["environments"] <= 40 and report["expected_saving"] >= 0
    if report["actions"]:
        assert report["actions"][0].startswith("pick up ") and report["actions"][1].startswith("put ")


def test_words_render_and_simulation(cli: CliRunner, tmp_path: Path) -> None:
    picture = tmp_path / "table.png"
    code, out, err = cli(
        ["support", "two-cells-led", "-e", "60", "--render", str(picture), "--simulate", "--lead", "greedy"]
    )
    assert code == 0, err
    assert "known plans" in out and "Expected saving for the lead" in out and "Simulated (greedy lead)" in out
    assert picture.read_bytes().startswith(PNG_SIGNATURE)


def test_same_seed_same_advice(cli: CliRunner) -> None:
    path = str(circuit_path("lamp-by-hand"))
    runs = [cli(["support", path, "-e", "30", "--seed", "4", "--json"]) for _ in range(2)]
    assert runs[0] == runs[1] and runs[0][0] == 0


BASE = "name: t\nscatter: {seed: 1, pieces: {battery: 2, switch: 1, led: 1}}\n"


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("name: t\n", "give the pieces either as 'pieces'"),
        (BASE + "pieces: []\n", "not both"),
        (
            "name: t\nscatter: {pieces: {capacitor: 1}}\n",
            "scatter.pieces.capacitor: unknown piece kind 'capacitor'",
        ),
        (BASE + "colour: red\n", "unknown key 'colour'"),
        (BASE + "lead: {speed: 2}\n", "lead.speed"),
        (BASE + "planner: {scheme: bold}\n", "planner.scheme"),
        (
            "name: t\npieces:\n  - {id: a, kind: led, at: [10, 40]}\n  - {id: b, kind: led, at: [12, 40]}\n",
            ":4: pieces[1].at: piece b at (12.0, 40.0) overlaps a",
        ),
        (
            "name: t\npieces:\n  - {id: a, kind: led, at: [52, 14]}\n",
            "pieces[0].at: piece a at (52.0, 14.0) is off the table or on the board",
        ),
        (
            "name: t\npieces:\n  - {id: a, kind: led, at: [10, 40]}\n  - {id: a, kind: led, at: [40, 50]}\n",
            "used twice",
        ),
        ("name: [t\n", "invalid YAML"),
        ("- 1\n", "expected a mapping"),
        ("", "file is empty"),
    ],
)
def test_invalid_scenarios_name_the_place(text: str, message: str, tmp_path: Path, cli: CliRunner) -> None:
    with pytest.raises(ScenarioFileError, match=None) as caught:
        parse_scenario_string(text, path="s.yaml")
    assert message in str(caught.value) and str(caught.value).startswith("s.yaml")
    path = tmp_path / "s.yaml"
    path.write_text(text, encoding="utf-8")
    code, out, err = cli(["support", str(path)])
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith(f"supportive: error: {path}") and "Traceback" not in err


def test_missing_file_and_wrong_type(tmp_path: Path, cli: CliRunner) -> None:
    code, _, err = cli(["support", str(tmp_path / "none.yaml")])
    assert code == 2 and "no such file" in err
    other = tmp_path / "s.txt"
    other.write_text("name: t", encoding="utf-8")
    code, _, err = cli(["support", str(other)])
    assert code == 2 and "unsupported file type" in err
    code, _, err = cli(["support", "lamp-by-hand", "--scheme", "bold"])
    assert code == 2 and "unknown weighting scheme 'bold'" in err
