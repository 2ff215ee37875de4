from __future__ import annotations

import json
import shutil
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

from supportive import examples
from supportive.io.htn_json import htn_from_dict
from supportive.io.taskfile import parse_task_file

CliRunner = Callable[[list[str]], tuple[int, str, str]]


def test_learn_prints_a_tree(cli: CliRunner) -> None:
    code, out, _ = cli(["learn", str(examples.path("blocks-v"))])
    assert code == 0
    assert "blocks-v (partial" in out or "blocks-v" in out
    assert "red — place the red block" in out


def test_learn_json_to_stdout_and_file(tmp_path: Path, cli: CliRunner) -> None:
    code, out, _ = cli(["learn", str(examples.path("knife-carrots-celery")), "--format", "json", "--mode", "strict"])
    assert code == 0
    data = json.loads(out)
    assert data["complete"] is True and data["stats"]["task_graph"]["paths"] == 2
    target = tmp_path / "htn.json"
    code, out, _ = cli(["learn", str(examples.path("two-glasses")), "-f", "json", "-o", str(target), "--mode", "strict"])
    assert code == 0 and out == ""
    assert len(htn_from_dict(json.loads(target.read_text())).alternatives) == 2


@pytest.mark.parametrize(
    ("mode", "reading"),
    [
        ("general-consistent", "general (consistent orders)"),
        ("partial-order-consistent", "partial order (consistent orders)"),
    ],
)
def test_learn_offers_every_reading_auto_may_keep(mode: str, reading: str, cli: CliRunner) -> None:
    """`--mode` lacked the consistent-orders readings, which `HTNLearner(mode=...)` and `auto` know."""
    from supportive.cli.learn import LearnMode
    from supportive.learning.selection import CANDIDATES

    assert {m.learner_mode for m in LearnMode} == {"auto", *CANDIDATES}
    code, out, _ = cli(["learn", str(examples.path("ikea-chair")), "-f", "json", "--mode", mode])
    assert code == 0
    assert json.loads(out)["reading"] == reading


def test_learn_dot_and_hddl(tmp_path: Path, cli: CliRunner) -> None:
    code, out, _ = cli(["learn", str(examples.path("blocks-towers")), "--format", "dot"])
    assert code == 0 and out.startswith("digraph htn {")
    code, _, err = cli(
        ["learn", str(examples.path("knife-carrots-celery")), "--format", "hddl", "-o", str(tmp_path / "h")]
    )
    assert code == 0 and "domain.hddl" in err
    assert "(:method" in (tmp_path / "h" / "domain.hddl").read_text()
    assert "(:htn" in (tmp_path / "h" / "problem.hddl").read_text()


def test_learn_names_the_slips_it_set_aside(tmp_path: Path, cli: CliRunner) -> None:
    rows = ["demonstration,step,action"]
    demos = ["abcdef"] * 10 + ["abdcef"] * 10 + ["bcdefa", "aebcdf"]  # one does "a" last, one "e" second
    rows += [f"r{i + 1},{j + 1},{a}" for i, demo in enumerate(demos) for j, a in enumerate(demo)]
    path = tmp_path / "demos.csv"
    path.write_text("\n".join(rows) + "\n")
    code, out, err = cli(["learn", str(path)])
    assert code == 0 and "in order a → … → f" in out
    assert "set aside as slips (2;" in err
    assert "r21 step 6 a (out of order); r22 step 2 e (out of order)" in err
    code, out, err = cli(["learn", str(path), "-f", "json"])
    data = json.loads(out)
    assert code == 0 and err == "" and len(data["deviations"]) == 2
    assert data["noise"]["slips"]["out of order"] == 2 and data["noise"]["rates"]["missing"] == 0.0
    code, out, err = cli(["learn", str(examples.path("blocks-v"))])
    assert code == 0 and "slips" not in err


def test_learn_reads_csv(tmp_path: Path, cli: CliRunner) -> None:
    path = tmp_path / "demos.csv"
    path.write_text(
        "demonstration,step,action\nd1,1,knife\nd1,2,a\nd1,3,b\nd2,1,knife\nd2,2,b\nd2,3,a\n"
        "d3,1,knife\nd3,2,a\nd3,3,b\nd4,1,knife\nd4,2,b\nd4,3,a\n"
    )
    code, out, _ = cli(["learn", str(path), "-f", "json"])
    assert code == 0 and json.loads(out)["roots"][0]["kind"] == "chain"


BAD = {
    "empty.yaml": "",
    "unknown-key.yaml": "name: t\ncolour: red\n",
    "undeclared.yaml": "name: t\nactions: [a]\ndemonstrations:\n  - steps: [a, b]\n",
    "undeclared-structure.yaml": "name: t\nactions: [a]\nstructure: {chain: [a, z]}\n",
    "duplicate.yaml": "name: t\ndemonstrations:\n  - {id: x, steps: [a]}\n  - {id: x, steps: [b]}\n",
    "steps.yaml": "name: t\ndemonstrations:\n  - steps: a\n",
    "invalid.yaml": "name: [t\n",
    "columns.csv": "demonstration,action\nd1,a\n",
    "nodemos.yaml": "name: t\nactions: [a]\n",
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_input_exits_2_with_one_line_and_writes_nothing(name: str, tmp_path: Path, cli: CliRunner) -> None:
    path = tmp_path / name
    path.write_text(BAD[name])
    target = tmp_path / "out.json"
    code, out, err = cli(["learn", str(path), "-f", "json", "-o", str(target)])
    assert code == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"supportive: error: {path}")
    assert "Traceback" not in err
    assert not target.exists()


def test_usage_errors_exit_2(cli: CliRunner) -> None:
    code, _, _ = cli(["learn"])
    assert code == 2
    code, _, _ = cli(["learn", str(examples.path("blocks-v")), "--format", "pdf"])
    assert code == 2


def test_hddl_needs_an_output_directory(cli: CliRunner) -> None:
    code, _, err = cli(["learn", str(examples.path("blocks-v")), "-f", "hddl"])
    assert code == 2 and "--output DIR" in err


def test_demo_says_what_was_and_was_not_learned_and_shows_the_caregiver(cli: CliRunner) -> None:
    code, out, _ = cli(["demo"])
    assert code == 0
    assert "Build frame" in out and "Attach seat" in out
    assert "✓ Screw seat" in out
    assert "✓ Fasten nuts and bolts (any order, inferred from 6 of 24 orders seen)" in out
    assert "288 of 768" in out
    assert "Watching a teammate" in out and "right action at the end of" in out
    assert "Teaching with questions" in out and "“Can you place the" in out
    caregiver = out[out.index("Keeping a novice safe") :]
    assert "75% random moves plays 40 steps in the playroom" in caregiver
    assert "╭─ playroom" in caregiver and "P(safe|τ)" in caregiver
    assert "with the caregiver" in caregiver and "without" in caregiver
    assert "damage over 40 steps:" in caregiver


def test_console_script_has_no_traceback(tmp_path: Path) -> None:
    script = shutil.which("supportive", path=str(Path(sys.executable).parent))
    assert script is not None
    path = tmp_path / "bad.yaml"
    path.write_text("name: t\nfoo: 1\n")
    result = subprocess.run([script, "learn", str(path)], capture_output=True, text=True, check=False)
    assert result.returncode == 2
    assert result.stderr.strip() == f"supportive: error: {path}:2: unknown key 'foo'"


def test_generate_is_seeded_and_learnable(tmp_path: Path, cli: CliRunner) -> None:
    code, first, _ = cli(["generate", "--actions", "30", "--seed", "5"])
    _, second, _ = cli(["generate", "--actions", "30", "--seed", "5"])
    _, other, _ = cli(["generate", "--actions", "30", "--seed", "6"])
    assert code == 0 and first == second != other
    target = tmp_path / "task.json"
    code, _, _ = cli(["generate", "-n", "25", "--seed", "1", "-d", "3", "-o", str(target)])
    assert code == 0
    code, out, _ = cli(["learn", str(target), "-f", "json"])
    assert code == 0 and json.loads(out)["stats"]["demonstrations"] == 3


def test_infer_prints_one_json_line_per_observation(tmp_path: Path, cli: CliRunner) -> None:
    stream = tmp_path / "stream.jsonl"
    stream.write_text(
        '["hand-left_frame"]\n["hand-left_frame", "left_frame-table"]\n{"events": ["hand-peg", "peg-left_frame"], "time": 3.5}\n'
    )
    code, out, _ = cli(
        ["infer", str(examples.path("ikea-chair")), "--observations", str(stream), "--top", "2"]
    )
    assert code == 0
    lines = [json.loads(line) for line in out.splitlines()]
    assert [r["step"] for r in lines] == [1, 2, 3]
    assert lines[0]["subgoals"][0][0] == "get_left_frame"
    assert lines[2]["subtasks"][0][0] == "Add left pegs" and lines[2]["time"] == 3.5
    assert len(lines[1]["next"]) == 2
    code, flat, _ = cli(["infer", str(examples.path("ikea-chair")), "-O", str(stream), "--model", "flat"])
    assert code == 0 and len(flat.splitlines()) == 3


def test_infer_says_each_mistake_and_the_help_it_calls_for(tmp_path: Path, cli: CliRunner) -> None:
    shipped = examples.path("ikea-chair").with_name("ikea-chair-actions.txt")
    steps = [line for line in shipped.read_text().splitlines() if line != "peg_left_rear"]
    actions = tmp_path / "actions.txt"
    actions.write_text("\n".join(steps) + "\n")
    code, out, _ = cli(["infer", str(examples.path("ikea-chair")), "--actions", str(actions)])
    assert code == 0
    records = [json.loads(line) for line in out.splitlines()]
    assert len(records) == len(steps) and all("mistake" in r for r in records)
    flagged = [r["mistake"] for r in records if r["mistake"]["mistake"]]
    assert [(m["action"], m["kind"], m["skipped"]) for m in flagged] == [("get_right_frame", "missing", ["peg_left_rear"])]
    assert flagged[0]["help"]["say"].startswith("You skipped pushing a wooden peg into the left frame's rear hole")


def test_infer_bad_inputs_exit_2(tmp_path: Path, cli: CliRunner) -> None:
    bad = tmp_path / "bad.jsonl"
    bad.write_text('["a"]\n[1]\n')
    code, out, err = cli(["infer", str(examples.path("ikea-chair")), "-O", str(bad)])
    assert (
        code == 2
        and out == ""
        and err.strip()
        == f"supportive: error: {bad}:2: expected a list of contact events (non-empty strings)"
    )
    good = tmp_path / "good.jsonl"
    good.write_text("[]\n")
    code, _, err = cli(["infer", str(examples.path("blocks-v")), "-O", str(good)])
    assert code == 2 and "without 'observations'" in err and len(err.strip().splitlines()) == 1


def test_infer_warns_once_per_unknown_name_and_strict_refuses(tmp_path: Path, cli: CliRunner) -> None:
    """Issue 26: unknown events and actions were accepted without a word."""
    steps = tmp_path / "steps.txt"
    steps.write_text("get_left_frame\nfoo\nfoo\nbar\nplace_left_frame\n")
    code, out, err = cli(["infer", "ikea-chair", "--actions", str(steps)])
    assert code == 0 and len(out.splitlines()) == 5
    assert err.count("unknown action 'foo'") == 1 and err.count("unknown action 'bar'") == 1
    assert f"supportive: warning: {steps}: step 2: unknown action 'foo'" in err
    code, out, err = cli(["infer", "ikea-chair", "--actions", str(steps), "--strict"])
    assert code == 2 and out == ""
    assert err.strip() == f"supportive: error: {steps}: step 2: unknown action 'foo': the task has no such action (--strict refuses it)"
    stream = tmp_path / "stream.jsonl"
    stream.write_text('["hand-left_frame", "zzz"]\n["zzz"]\n["hand-left_frame"]\n')
    code, out, err = cli(["infer", "ikea-chair", "-O", str(stream)])
    assert code == 0 and len(out.splitlines()) == 3 and err.count("unknown event 'zzz'") == 1
    code, out, err = cli(["infer", "ikea-chair", "-O", str(stream), "--strict"])
    assert code == 2 and out == "" and "moment 1: unknown event 'zzz'" in err
    known = tmp_path / "known.txt"
    known.write_text("get_left_frame\n")
    code, _, err = cli(["infer", "ikea-chair", "--actions", str(known), "--strict"])
    assert code == 0 and err == ""


def test_infer_leaves_out_entries_at_probability_zero(tmp_path: Path, cli: CliRunner) -> None:
    """Issue 26: `infer --actions` printed "(top level) 0.0, Assemble chair 0.0" after the subtask it knew."""
    steps = tmp_path / "steps.txt"
    steps.write_text("get_left_frame\nplace_left_frame\n")
    code, out, _ = cli(["infer", "ikea-chair", "--actions", str(steps)])
    records = [json.loads(line) for line in out.splitlines()]
    assert code == 0 and records[0]["subtasks"] == [["Prepare left frame", 1.0]]
    for record in records:
        for key in ("subgoals", "subtasks", "next"):
            assert record[key] and all(p > 0 for _, p in record[key][1:]), record[key]


def test_a_csv_says_what_it_leaves_out(tmp_path: Path, cli: CliRunner) -> None:
    """Issue 26: CSV output dropped the structure without saying so."""
    code, _, err = cli(["generate", "--actions", "5", "-o", str(tmp_path / "g.csv")])
    assert code == 0
    assert err.strip() == (
        f"supportive: note: {tmp_path / 'g.csv'} holds the demonstrations only: the structure and the actions and "
        "their texts are not written (.yaml or .json keeps them)"
    )
    code, _, err = cli(["generate", "--actions", "5", "-o", str(tmp_path / "g.yaml")])
    assert code == 0 and err == ""
    flat = tmp_path / "flat.yaml"
    flat.write_text("name: t\ndemonstrations:\n  - steps: [a, b]\n")
    from supportive.io.taskfile import csv_leaves_out

    assert csv_leaves_out(parse_task_file(flat)) == []  # nothing to leave out, nothing said
