"""``supportive evaluate FILE --mistakes`` on the bundled labelled example, and its refusals (one line, exit
2, nothing written)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from tests.conftest import CliRunner

from supportive import examples


def test_the_bundled_example_scores_the_detector_beside_both_baselines(cli: CliRunner) -> None:
    code, out, _ = cli(["evaluate", "tea-mistakes", "--mistakes", "--json"])
    assert code == 0
    report = json.loads(out)
    spec = examples.load("tea-mistakes")
    assert report["held_out"] == len(spec.demonstrations)
    methods = report["methods"]
    assert set(methods) == {"progress-aware", "precondition", "unseen bigram"}
    detector = methods["progress-aware"]
    assert detector["positives"] == 4  # one skipped step, two too early, one repeated
    assert detector["clean_flagged"] == 0.0  # no step of the twelve correct demonstrations is called a mistake
    assert detector["f1"] >= max(methods["precondition"]["f1"], methods["unseen bigram"]["f1"])


@pytest.mark.parametrize(
    ("change", "problem"),
    [
        (lambda text: text.replace("mistake: repeated", "mistake: twice"), "unknown mistake label 'twice'"),
        (lambda text: text.replace("{action: stir, mistake: repeated}", "{action: dance, mistake: repeated}"), "dance"),
        (lambda text: text.split("  - id: sugar-forgotten")[0], "no step carries a mistake label"),
    ],
    ids=["unknown label", "step not in the task", "no labelled step"],
)
def test_a_bad_mistake_file_is_one_line_and_exit_2(
    change: object, problem: str, tmp_path: Path, cli: CliRunner
) -> None:
    assert callable(change)
    source = examples.path("tea-mistakes").read_text(encoding="utf-8")
    path = tmp_path / "tea.yaml"
    path.write_text(change(source), encoding="utf-8")
    before = sorted(tmp_path.iterdir())
    code, out, err = cli(["evaluate", str(path), "--mistakes"])
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and problem in err and "Traceback" not in err
    assert sorted(tmp_path.iterdir()) == before


def test_learning_from_the_correct_demonstrations_only_is_said_and_in_the_json(cli: CliRunner) -> None:
    code, out, _ = cli(["evaluate", "tea-mistakes", "--mistakes", "--learn-from", "correct", "--json"])
    assert code == 0 and json.loads(out)["learned_from"] == "correct"
    code, out, err = cli(["evaluate", "tea-mistakes", "--mistakes", "--learn-from", "correct"])
    assert code == 0 and "learned from the correct ones among the others" in " ".join((out + err).split())
    code, out, _ = cli(["evaluate", "tea-mistakes", "--mistakes", "--json"])
    assert code == 0 and json.loads(out)["learned_from"] == "all"


@pytest.mark.parametrize("command", [["evaluate", "tea-mistakes"], ["captaincook"]])
def test_learn_from_without_mistakes_is_one_line_and_exit_2(command: list[str], cli: CliRunner) -> None:
    code, out, err = cli([*command, "--learn-from", "correct"])
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and "give --mistakes too" in err
