"""The safe loader and the validation layer on the inputs of issue 15: each hostile or careless file is refused
with one clear error naming the file and, where it can, the line; the limits let the largest real inputs by."""

from __future__ import annotations

import os
import tracemalloc
from pathlib import Path

import pytest

from supportive.errors import FileFormatError, ObservationFileError, TaskFileError
from supportive.generate import generate_task
from supportive.io.limits import MAX_DEPTH, MAX_FILE_BYTES
from supportive.io.observation_file import parse_observation_file
from supportive.io.safe_load import LIBYAML, load_json, load_yaml, read_text
from supportive.io.taskfile import dump_task, parse_task_file, parse_task_string

ALIAS_BOMB = "\n".join(
    [
        "name: bomb",
        "structure:",
        "  chain:",
        "  - &a {clique: [x, x, x, x, x, x, x, x, x]}",
        *(
            f"  - &{b} {{chain: [{', '.join(['*' + a] * 9)}]}}"
            for a, b in zip("abcdefg", "bcdefgh", strict=False)
        ),
    ]
)


def refused(text: str, fmt: str = "yaml") -> str:
    with pytest.raises(TaskFileError) as caught:
        parse_task_string(text, fmt, path=f"task.{fmt}")  # type: ignore[arg-type]
    message = str(caught.value)
    assert message.startswith(f"task.{fmt}") and "\n" not in message
    return message


def test_an_alias_bomb_is_refused_before_it_expands() -> None:
    assert len(ALIAS_BOMB) < 600
    tracemalloc.start()
    try:
        message = refused(ALIAS_BOMB)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 8 * 2**20  # 9^8 values expanded would need gigabytes: the refusal counts, it does not expand
    assert "more than 2,000,000 values once its aliases are expanded" in message


def test_a_recursive_alias_is_refused() -> None:
    assert "refers to a node that contains it" in refused("name: t\nstructure: &a {chain: [x, *a]}\n")


@pytest.mark.parametrize("fmt", ["yaml", "json"])
def test_nesting_deeper_than_the_limit_is_refused_and_the_limit_itself_is_read(fmt: str) -> None:
    def nested(depth: int) -> str:
        inner = "[" * (depth - 1) + "]" * (depth - 1)
        return f'{{"name": "t", "structure": {inner}}}'

    assert "nested deeper than 100 levels" in refused(nested(1000), fmt)
    assert "nested deeper" in refused(nested(MAX_DEPTH + 1), fmt)
    assert "nested deeper" not in refused(nested(MAX_DEPTH), fmt)  # read, then refused by the schema


@pytest.mark.parametrize(
    ("text", "fmt", "expected"),
    [
        ("name: t\nname: u\n", "yaml", "task.yaml:2: key 'name' appears twice"),
        ('{"name": "t", "name": "u"}', "json", "key 'name' appears twice"),
        ("demonstration,step,action,action\nd1,1,a,b\n", "csv", "task.csv:1: column 'action' appears twice"),
    ],
)
def test_a_key_or_column_given_twice_is_refused(text: str, fmt: str, expected: str) -> None:
    assert expected in refused(text, fmt)


@pytest.mark.parametrize(
    ("text", "fmt"),
    [
        ("name: t\ndemonstrations:\n  - steps: [{action: a, start: " + "9" * 5000 + "}]\n", "yaml"),
        ('{"name": "t", "demonstrations": [{"steps": [{"action": "a", "start": ' + "9" * 5000 + "}]}]}", "json"),
        ("demonstration,step,action\nd1," + "9" * 5000 + ",a\n", "csv"),
        ("demonstration,step,action,start\nd1,1,a," + "9" * 5000 + "\n", "csv"),
    ],
)
def test_a_number_of_thousands_of_digits_is_refused(text: str, fmt: str) -> None:
    message = refused(text, fmt)
    assert "number" in message or "integer" in message
    assert len(message) < 300


@pytest.mark.parametrize(
    ("text", "fmt"),
    [
        ("name: t\ndemonstrations:\n  - steps: [{action: a, start: .nan}]\n", "yaml"),
        ("name: t\ndemonstrations:\n  - steps: [{action: a, end: .inf}]\n", "yaml"),
        ('{"name": "t", "demonstrations": [{"steps": [{"action": "a", "start": 1e400}]}]}', "json"),
        ('{"name": "t", "demonstrations": [{"steps": [{"action": "a", "start": NaN}]}]}', "json"),
        ("demonstration,step,action,start,end\nd1,1,a,nan,\n", "csv"),
        ("demonstration,step,action,start,end\nd1,1,a,0,inf\n", "csv"),
        ("name: t\ndemonstrations:\n  - steps: [{action: a, start: 1e300}]\n", "yaml"),
    ],
)
def test_step_times_must_be_finite_and_in_range(text: str, fmt: str) -> None:
    message = refused(text, fmt)
    assert any(word in message for word in ("finite", "between", "NaN is not", "at most"))


def test_an_action_id_may_not_collide_with_repeat_numbering() -> None:
    message = refused("name: t\nactions: [a, 'a#2']\n")
    assert "task.yaml:2: actions[1].id: an action id may not contain '#'" in message
    assert "may not contain '#'" in refused("demonstration,step,action\nd1,1,a#2\n", "csv")


@pytest.mark.parametrize(
    ("text", "fmt"),
    [
        ('{"name": "t", "actions": ["a\\u001b[31m"]}', "json"),
        ('{"name": "t", "actions": ["\\udc80"]}', "json"),
        ('name: t\nactions: ["a\\e[2J"]\n', "yaml"),
        ('name: t\nactions: ["\\udc80"]\n', "yaml"),
    ],
)
def test_ids_hold_no_control_character_or_lone_surrogate(text: str, fmt: str) -> None:
    message = refused(text, fmt)
    assert "control character" in message or "lone surrogate" in message or "invalid Unicode" in message


def test_an_unterminated_csv_quote_is_refused_not_swallowed() -> None:
    text = 'demonstration,step,action\nd1,1,"a\nd1,2,b\nd2,1,b\n'
    assert "task.csv:2: invalid CSV: a quoted field is never closed" in refused(text, "csv")


def test_a_csv_field_over_the_limit_is_refused() -> None:
    text = "demonstration,step,action\nd1,1," + "a" * 200_000 + "\n"
    assert "task.csv:2: invalid CSV: a field longer than 131,072 characters" in refused(text, "csv")


def test_devices_fifos_directories_and_huge_files_are_refused_before_reading(tmp_path: Path) -> None:
    zero = tmp_path / "zero.yaml"
    zero.symlink_to("/dev/zero")
    fifo = tmp_path / "fifo.yaml"
    os.mkfifo(fifo)
    folder = tmp_path / "folder.yaml"
    folder.mkdir()
    big = tmp_path / "big.yaml"
    with big.open("wb") as handle:
        handle.truncate(MAX_FILE_BYTES + 1)
    for path, problem in (
        (zero, "not a regular file (a device or socket)"),
        (fifo, "not a regular file (a FIFO)"),  # used to wait forever for a writer
        (folder, "is a folder; expected a task file (.yaml, .yml, .json or .csv)"),
        (big, "file is larger than 16,777,216 bytes"),
    ):
        with pytest.raises(TaskFileError) as caught:
            parse_task_file(path)
        assert str(caught.value) == f"{path}: {problem}" + (", the limit" if path is big else "")


def test_text_that_is_not_utf8_names_its_line(tmp_path: Path) -> None:
    path = tmp_path / "latin.yaml"
    path.write_bytes(b"name: t\nactions: [caf\xe9]\n")
    with pytest.raises(TaskFileError, match=r"latin.yaml:2: not UTF-8 text: byte 0xe9"):
        read_text(path, TaskFileError)


@pytest.mark.parametrize(
    ("line", "problem"),
    [
        ('{"events": ["a"], "time": ' + "9" * 5000 + "}", "a number of 5,000 characters"),
        ('{"events": ["a"], "time": 1e300}', "time must be between"),
        ('{"events": ["a"], "time": 2e11}', "time must be between -1e+11 and 1e+11, got 2e+11"),
        ('{"events": ["a"], "time": 1e400}', "time must be a finite number"),
        ("[" * 1000 + "]" * 1000, "nested deeper than 100 levels"),
        ('{"events": ["a"], "events": ["b"]}', "key 'events' appears twice"),
        ('["hand\\u001b[2J"]', "control character"),
    ],
)
def test_bad_observation_moments_are_refused_with_their_line(tmp_path: Path, line: str, problem: str) -> None:
    path = tmp_path / "stream.jsonl"
    path.write_text('["a"]\n' + line + "\n")
    with pytest.raises(ObservationFileError) as caught:
        parse_observation_file(path)
    assert str(caught.value).startswith(f"{path}:2: ") and problem in str(caught.value)


def test_the_largest_benchmark_task_passes_the_limits() -> None:
    """bench_learn's largest case (5,000 actions, 4 demonstrations), in both profiles and both formats."""
    for profile in ("ikea", "uniform"):
        spec = generate_task(5000, 0, demonstrations=4, profile=profile)
        for fmt in ("yaml", "json"):
            assert parse_task_string(dump_task(spec, fmt), fmt) == spec


def test_loaders_keep_ordinary_data() -> None:
    assert load_yaml("a: &x [1, 2]\nb: *x\n<<: {c: 3}\n", None, FileFormatError) == {
        "a": [1, 2],
        "b": [1, 2],
        "c": 3,
    }
    assert load_json('{"a": {"b": [1.5, "x"]}}', None, FileFormatError) == {"a": {"b": [1.5, "x"]}}


@pytest.mark.parametrize(
    ("text", "line", "character"),
    [
        ("a: ééé\nb: ü\nc: \x07\n", 3, "U+0007"),  # libyaml counts bytes: two per letter before it
        ("a: ééé\n\n\nb: \x7f", 4, "U+007F"),
        ("a: é\nb: \ud800\n", 2, "U+D800"),  # a lone surrogate, which UTF-8 (and so libyaml) cannot hold
        ("\ud800", 1, "U+D800"),
    ],
)
def test_a_character_yaml_does_not_allow_names_its_line(text: str, line: int, character: str) -> None:
    with pytest.raises(FileFormatError) as caught:
        load_yaml(text, "t.yaml", FileFormatError)
    assert str(caught.value) == f"t.yaml:{line}: invalid YAML: character {character} is not allowed in YAML"


WITHOUT_LIBYAML = """
import json, sys
sys.modules["yaml._yaml"] = None  # as a PyYAML built without libyaml: importing it fails
from supportive.errors import FileFormatError
from supportive.io import safe_load
from supportive.io.taskfile import _Dumper, dump_task
from supportive.generate import generate_task
import yaml
assert not safe_load.LIBYAML and safe_load._Events is safe_load._PythonEvents
assert _Dumper.__bases__ == (yaml.SafeDumper,)
answers = []
for text in json.loads(sys.stdin.read()):
    try:
        answers.append(["ok", safe_load.load_yaml(text, "t.yaml", FileFormatError)])
    except FileFormatError as exc:
        answers.append(["refused", str(exc)])
print(json.dumps([answers, dump_task(generate_task(30, 1, demonstrations=3), "yaml")]))
"""
TEXTS = [
    "a: 1\nb: [x, y]\n",
    "a: ééé\n\n\nb: \x7f",
    "a: é\nb: \ud800\n",
    "a: 1\na: 2",
    "a: &x [1]\nb: *x\n",
    "- " * (MAX_DEPTH + 1) + "1",
    "x: [\n",
]


def test_without_libyaml_the_loader_and_the_dumper_give_the_same_answers() -> None:
    """PyYAML's wheels have libyaml; built without it, the Python parser and emitter give the same data, the
    same refusals with the same lines (a syntax error in libyaml's words or in PyYAML's), and the same file."""
    import json
    import subprocess
    import sys

    def answer(text: str) -> list[object]:
        try:
            return ["ok", load_yaml(text, "t.yaml", FileFormatError)]
        except FileFormatError as exc:
            return ["refused", str(exc)]

    assert LIBYAML  # here, as from PyYAML's wheels: the other reading runs in the subprocess
    payload = json.dumps(TEXTS)
    result = subprocess.run([sys.executable, "-c", WITHOUT_LIBYAML], input=payload, capture_output=True, text=True, check=True)
    answers, dumped = json.loads(result.stdout)

    def said(answer: list[object]) -> list[object]:  # a syntax error's words are libyaml's or PyYAML's
        syntax = "invalid YAML: " in str(answer[1]) and "is not allowed in YAML" not in str(answer[1])
        return [answer[0], str(answer[1]).split("invalid YAML: ")[0]] if syntax else answer

    assert [said(a) for a in answers] == [said(answer(text)) for text in TEXTS]
    assert [a[0] for a in answers] == ["ok", "refused", "refused", "refused", "ok", "refused", "refused"]
    assert dumped == dump_task(generate_task(30, 1, demonstrations=3), "yaml")
