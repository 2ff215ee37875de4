"""``supportive evaluate FILE --mistakes`` on the bundled labelled example, and its refusals (one line, exit
2, nothing written)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from tests.conftest import CliRunner

from supportive import examples
from supportive.errors import TaskFileError
from supportive.evaluation.mistakes import STRUCTURE_REFERENCE, evaluate_mistakes


def test_the_bundled_example_scores_the_detector_beside_both_baselines_and_the_files_structure(
    cli: CliRunner, tmp_path: Path
) -> None:
    code, out, _ = cli(["evaluate", "tea-mistakes", "--mistakes", "--json"])
    assert code == 0
    report = json.loads(out)
    spec = examples.load("tea-mistakes")
    assert report["held_out"] == len(spec.demonstrations) and report["learned_from"] == "all"  # the default
    methods = report["methods"]
    assert set(methods) == {"progress-aware", "precondition", "unseen bigram", STRUCTURE_REFERENCE}
    detector = methods["progress-aware"]
    assert detector["positives"] == 4  # one skipped step, two too early, one repeated
    assert detector["clean_flagged"] == 0.0  # no step of the twelve correct demonstrations is called a mistake
    assert detector["f1"] >= max(methods["precondition"]["f1"], methods["unseen bigram"]["f1"])
    # The file's structure, scored as a reference: knowing the rules finds both steps done too early and calls
    # no step of a correct demonstration a mistake; a repeated step breaks no order, so it is not found.
    reference = methods[STRUCTURE_REFERENCE]
    assert reference["kinds"]["order"]["recall"] == 1.0 and reference["clean_flagged"] == 0.0
    assert reference["kinds"]["repeated"]["recall"] == 0.0
    code, out, err = cli(["evaluate", "tea-mistakes", "--mistakes"])
    assert code == 0 and "given structure: a reference, not a method" in " ".join((out + err).split())
    # Without a structure in the file there is no reference to score (learned from the correct demonstrations,
    # the quicker way: the reference does not depend on it).
    source = examples.path("tea-mistakes").read_text(encoding="utf-8")
    path = tmp_path / "tea.yaml"
    path.write_text(_without_structure(source), encoding="utf-8")
    code, out, _ = cli(["evaluate", str(path), "--mistakes", "--learn-from", "correct", "--json"])
    assert code == 0 and STRUCTURE_REFERENCE not in json.loads(out)["methods"]


def _without_structure(source: str) -> str:
    """The task file with its ``structure:`` block (up to the next top-level key) taken out."""
    lines = source.splitlines(keepends=True)
    start = next(i for i, line in enumerate(lines) if line.startswith("structure:"))
    end = next(i for i in range(start + 1, len(lines)) if lines[i][:1].isalpha())
    return "".join(lines[:start] + lines[end:])


def test_the_reference_may_not_take_a_methods_name() -> None:
    spec = examples.load("tea-mistakes")
    with pytest.raises(TaskFileError, match="the reference cannot be called 'precondition'"):
        evaluate_mistakes(spec, truth=set(), reference="precondition")


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


@pytest.mark.parametrize("command", [["evaluate", "tea-mistakes"], ["captaincook"]])
def test_learn_from_without_mistakes_is_one_line_and_exit_2(command: list[str], cli: CliRunner) -> None:
    code, out, err = cli([*command, "--learn-from", "correct"])
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and "give --mistakes too" in err
