"""Mistake labels in task files: read, written back exactly (YAML, JSON, CSV), refused when unknown, ignored by
learning, and kept by the editor ``teach`` and ``chat`` save through."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import TaskFileError
from supportive.io.htn_json import htn_to_dict
from supportive.io.task_edit import update_task_file
from supportive.io.taskfile import Format, dump_task, parse_task_file, parse_task_string, task_to_dict
from supportive.learning import HTNLearner
from supportive.tasks.spec import MISTAKE_LABELS, Demonstration, Step, TaskSpec

CliRunner = Callable[[list[str]], tuple[int, str, str]]

LABELLED = """\
name: soup
actions: [boil, chop, stir, salt, serve]
demonstrations:
  - id: d1              # a clean one
    steps: [boil, chop, stir, salt, serve]
  - id: d2
    steps: [chop, boil, stir, salt, serve]
  - id: d3
    steps:
      - boil
      - {action: chop, mistake: missing}    # never chopped
      - {action: salt, mistake: order}
      - stir
      - {action: serve, mistake: true, start: 3.5, end: 4.0}
  - id: d4
    steps:
      - {action: chop, mistake: technique}
      - boil
      - stir
      - {action: stir, mistake: repeated}
      - salt
      - {action: serve, mistake: missing}
"""


def test_labels_and_placeholders_are_read() -> None:
    spec = parse_task_string(LABELLED, "yaml")
    d1, _, d3, d4 = spec.demonstrations
    assert not d1.labelled and d3.labelled and d4.labelled
    assert d3.actions == ("boil", "salt", "stir", "serve") and d3.skipped == ((1, "chop"),)
    assert [s.mistake for s in d3.steps] == [None, "order", None, "true"]
    assert (d3.steps[3].start, d3.steps[3].end) == (3.5, 4.0)
    assert d4.skipped == ((5, "serve"),) and [s.mistake for s in d4.steps][3] == "repeated"


@pytest.mark.parametrize("fmt", ["yaml", "json", "csv"])
def test_labels_round_trip_inline(fmt: Format) -> None:
    spec = parse_task_string(LABELLED, "yaml")
    text = dump_task(spec, fmt)
    back = parse_task_string(text, fmt, name="soup")
    assert back.demonstrations == spec.demonstrations
    if fmt != "csv":
        assert back == spec
        assert task_to_dict(spec)["demonstrations"][2]["steps"][:3] == [
            "boil",
            {"action": "chop", "mistake": "missing"},
            {"action": "salt", "mistake": "order"},
        ]
    else:
        assert text.splitlines()[0] == "demonstration,step,action,start,end,mistake"
        assert "d3,2,chop,,,missing" in text.splitlines() and "d3,5,serve,3.5,4.0,true" in text.splitlines()


def test_without_labels_nothing_changes_in_the_written_file() -> None:
    clean = TaskSpec("t", demonstrations=(Demonstration.of(["a", "b"], id="d1"),))
    assert "mistake" not in dump_task(clean, "yaml") + dump_task(clean, "json") + dump_task(clean, "csv")


@st.composite
def labelled_specs(draw: st.DrawFn) -> TaskSpec:
    demos = []
    for index in range(draw(st.integers(1, 3))):
        listed: list[Step] = []
        for _ in range(draw(st.integers(1, 6))):
            action = draw(st.sampled_from(["a", "b", "c", "long_name"]))
            label = draw(st.none() | st.sampled_from(MISTAKE_LABELS))
            if label == "missing":
                listed.append(Step(action, mistake=label))
            else:
                start = draw(st.none() | st.floats(0, 1e4, allow_nan=False, allow_infinity=False))
                end = None if start is None else start + draw(st.floats(0, 100, allow_nan=False))
                listed.append(Step(action, start, end, mistake=label))
        if all(step.placeholder for step in listed):
            listed.append(Step("a"))
        demos.append(Demonstration.from_entries(listed, f"d{index + 1}", draw(st.none() | st.just("ann"))))
    return TaskSpec("t", demonstrations=tuple(demos))


@given(labelled_specs(), st.sampled_from(["yaml", "json", "csv"]))
def test_any_labelled_task_round_trips(spec: TaskSpec, fmt: Format) -> None:
    assert parse_task_string(dump_task(spec, fmt), fmt, name="t") == spec


BAD = {
    "unknown label": (
        "      - {action: salt, mistake: order}", "      - {action: salt, mistake: oder}",
        ":12: demonstrations[2].steps[2].mistake: unknown mistake label 'oder'; expected one of order, missing,",
    ),
    "a number as label": (
        "      - {action: salt, mistake: order}", "      - {action: salt, mistake: 2}",
        ":12: demonstrations[2].steps[2].mistake: unknown mistake label int 2",
    ),
    "placeholder not declared": (
        "      - {action: chop, mistake: missing}", "      - {action: dice, mistake: missing}",
        ":11: demonstrations[2].steps[1]: action 'dice' is not declared in 'actions'",
    ),
    "placeholder with times": (
        "      - {action: chop, mistake: missing}", "      - {action: chop, mistake: missing, start: 1}",
        ":11: demonstrations[2].steps[1]: step 'chop' is labelled missing, so it was not performed",
    ),
    "nothing performed": (
        "    steps: [chop, boil, stir, salt, serve]", "    steps: [{action: chop, mistake: missing}]",
        ":7: demonstrations[1].steps: no step was performed: every step is labelled missing",
    ),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_labels_give_one_located_line(case: str, tmp_path: Path) -> None:
    old, new, message = BAD[case]
    assert old in LABELLED
    path = tmp_path / "soup.yaml"
    path.write_text(LABELLED.replace(old, new))
    with pytest.raises(TaskFileError) as info:
        parse_task_file(path)
    assert str(info.value).startswith(str(path) + message) and "\n" not in str(info.value)


def test_bad_label_in_json_and_csv(tmp_path: Path) -> None:
    data = task_to_dict(parse_task_string(LABELLED, "yaml"))
    data["demonstrations"][3]["steps"][0]["mistake"] = "sloppy"
    path = tmp_path / "soup.json"
    path.write_text(json.dumps(data, indent=2))
    with pytest.raises(TaskFileError, match=r"soup\.json:\d+: demonstrations\[3\]\.steps\[0\]\.mistake: unknown mistake label 'sloppy'"):
        parse_task_file(path)
    csv = tmp_path / "soup.csv"
    csv.write_text("demonstration,step,action,mistake\nd1,1,a,\nd1,2,b,sloppy\n")
    with pytest.raises(TaskFileError, match=r"soup\.csv:3: mistake: unknown mistake label 'sloppy'"):
        parse_task_file(csv)
    csv.write_text("demonstration,step,action,start,mistake\nd1,1,a,,\nd1,2,b,2.0,missing\n")
    with pytest.raises(TaskFileError, match=r"soup\.csv:3: mistake: step 'b' is labelled missing"):
        parse_task_file(csv)
    csv.write_text("demonstration,step,action,mistake\nd1,1,a,missing\n")
    with pytest.raises(TaskFileError, match=r"soup\.csv: demonstration 'd1': no step was performed"):
        parse_task_file(csv)


def test_csv_reads_flags_and_placeholders_by_step_number(tmp_path: Path) -> None:
    csv = tmp_path / "demos.csv"
    csv.write_text("demonstration,step,action,mistake\nd1,3,c,TRUE\nd1,1,a,false\nd1,2,b,missing\nd1,4,d,\n")
    (demo,) = parse_task_file(csv).demonstrations
    assert demo.actions == ("a", "c", "d") and demo.skipped == ((1, "b"),)
    assert [s.mistake for s in demo.steps] == [None, "true", None]


def test_the_command_line_refuses_an_unknown_label(tmp_path: Path, cli: CliRunner) -> None:
    path = tmp_path / "soup.yaml"
    path.write_text(LABELLED.replace("mistake: order", "mistake: late"))
    code, out, err = cli(["learn", str(path)])
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert f"{path}:12: demonstrations[2].steps[2].mistake: unknown mistake label 'late'" in err


def _without_labels(text: str) -> str:
    """The file with every placeholder line dropped and every label removed."""
    lines = [line for line in text.splitlines() if "mistake: missing" not in line]
    out = []
    for line in lines:
        if "mistake:" in line:
            line = line.split("{action: ")[0] + line.split("{action: ")[1].split(",")[0]
        out.append(line)
    return "\n".join(out) + "\n"


def test_learning_never_sees_placeholders_or_labels() -> None:
    labelled = parse_task_string(LABELLED, "yaml")
    plain = parse_task_string(_without_labels(LABELLED), "yaml")
    assert not any(d.labelled for d in plain.demonstrations)
    assert [d.actions for d in plain.demonstrations] == [d.actions for d in labelled.demonstrations]
    with_labels, without = HTNLearner().fit(labelled), HTNLearner().fit(plain)
    assert with_labels.htn_ == without.htn_
    assert htn_to_dict(with_labels.htn_) == htn_to_dict(without.htn_)
    assert "chop" in {a for d in plain.demonstrations for a in d.actions}  # the placeholders' actions still occur


def _add(steps: list[str]) -> Callable[[TaskSpec], TaskSpec]:
    def change(spec: TaskSpec) -> TaskSpec:
        return spec.with_demonstrations([*spec.demonstrations, Demonstration.of(steps, id="late")])

    return change


def test_the_editor_keeps_labels_and_placeholders(tmp_path: Path) -> None:
    path = tmp_path / "soup.yaml"
    path.write_text(LABELLED)
    update_task_file(path, _add(["boil", "chop", "stir", "salt", "serve"]))
    after = path.read_text()
    assert after.startswith(LABELLED)  # every labelled line, its comment and its flow style as written
    assert after[len(LABELLED) :] == "  - id: late\n    steps:\n" + "".join(
        f"      - {a}\n" for a in ("boil", "chop", "stir", "salt", "serve")
    )  # in the style of the demonstration before it

    def label_d2(spec: TaskSpec) -> TaskSpec:
        listed = [Step("chop", mistake="order"), Step("boil"), Step("stir", mistake="missing"), Step("salt"), Step("serve")]
        marked = Demonstration.from_entries(listed, "d2")
        return spec.with_demonstrations([spec.demonstrations[0], marked, *spec.demonstrations[2:]])

    saved = update_task_file(path, label_d2)
    again = path.read_text()
    assert parse_task_file(path) == saved and saved.demonstrations[1].skipped == ((2, "stir"),)
    kept = [line for line in LABELLED.splitlines() if "d2" not in line and "[chop, boil" not in line]
    assert all(line in again.splitlines() for line in kept)  # d3 and d4 untouched, comments included
    assert "mistake: order" in again.split("id: d3")[0] and "mistake: missing" in again.split("id: d3")[0]


def test_the_editor_keeps_labels_in_json(tmp_path: Path) -> None:
    path = tmp_path / "soup.json"
    spec = parse_task_string(LABELLED, "yaml")
    path.write_text(dump_task(spec, "json"))
    saved = update_task_file(path, _add(["boil"]))
    back = parse_task_file(path)
    assert back == saved and back.demonstrations[:4] == spec.demonstrations
    assert json.loads(path.read_text())["demonstrations"][2]["steps"][4] == {
        "action": "serve", "start": 3.5, "end": 4.0, "mistake": True,
    }
