from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive import examples
from supportive.errors import TaskFileError
from supportive.io.taskfile import dump_task, parse_task_file, parse_task_string, write_task_file
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, Node
from supportive.tasks.spec import Action, Demonstration, Step, TaskSpec


@pytest.mark.parametrize("name", examples.names())
@pytest.mark.parametrize("fmt", ["yaml", "json"])
def test_examples_round_trip(name: str, fmt: str, tmp_path: Path) -> None:
    spec = examples.load(name)
    path = tmp_path / f"{name}.{fmt}"
    write_task_file(spec, path)
    assert parse_task_file(path) == spec
    assert [n.name for n in _named(parse_task_file(path).structure)] == [
        n.name for n in _named(spec.structure)
    ]


@given(st.text(st.characters(exclude_categories=["Cs", "Cc"]), max_size=30))
def test_any_text_comes_back_from_yaml_as_it_was(text: str) -> None:
    """Texts with line separators, quotes, escapes and any letter a text may hold: what is written is read back."""
    spec = TaskSpec("t", actions=(Action("a", text=text or None),), demonstrations=(Demonstration((Step("a"),), "d"),))
    assert parse_task_string(dump_task(spec, "yaml"), "yaml") == spec


def _named(node: Node | None) -> list[ChainNode | CliqueNode]:
    if node is None or isinstance(node, ActionNode):
        return []
    return [node, *(n for c in node.children for n in _named(c))]


@pytest.mark.parametrize("name", examples.names())
def test_csv_round_trip_keeps_demonstrations(name: str, tmp_path: Path) -> None:
    spec = examples.load(name)
    path = tmp_path / f"{name}.csv"
    write_task_file(spec, path)
    back = parse_task_file(path)
    assert back.name == name
    assert back.demonstrations == spec.demonstrations


def test_timing_agent_and_states_round_trip(tmp_path: Path) -> None:
    spec = TaskSpec(
        "timed",
        demonstrations=(
            Demonstration((Step("a", 0.0, 1.5), Step("b", 2.0, 3.25)), "d1", "alice"),
            Demonstration((Step("b", state=frozenset({"b_done"})),), "d2", None, frozenset()),
        ),
    )
    with pytest.raises(TaskFileError, match="explicit states"):
        parse_task_string(dump_task(spec, "yaml"), "yaml")
    timed = TaskSpec("timed", demonstrations=spec.demonstrations[:1])
    for fmt in ("yaml", "json", "csv"):
        path = tmp_path / f"timed.{fmt}"
        write_task_file(timed, path)
        assert parse_task_file(path).demonstrations == timed.demonstrations


def test_shorthand_and_full_forms_agree() -> None:
    short = parse_task_string("name: t\nactions: [a, b]\ndemonstrations:\n  - steps: [a, b]\n", "yaml")
    full = parse_task_string(
        '{"name": "t", "actions": [{"id": "a"}, {"id": "b"}],'
        ' "demonstrations": [{"id": "d1", "steps": [{"action": "a"}, {"action": "b"}]}]}',
        "json",
    )
    assert short == full


BAD_YAML = {
    "empty": ("", "file is empty", None),
    "whitespace only": ("  \n\n", "file is empty", None),
    "not a mapping": ("- a\n- b\n", "expected a mapping", ":1"),
    "invalid yaml": ("name: [x\n", "invalid YAML", ":2"),
    "unknown top key": ("name: t\nfoo: 1\n", "unknown key 'foo'", ":2"),
    "unknown step key": (
        "name: t\ndemonstrations:\n  - steps:\n      - {action: a, speed: 3}\n",
        "demonstrations[0].steps[0]: unknown key 'speed'",
        ":4",
    ),
    "missing name": ("actions: [a]\n", "missing required key 'name'", None),
    "steps not a list": (
        "name: t\ndemonstrations:\n  - steps: a\n",
        "demonstrations[0].steps: expected a list",
        ":3",
    ),
    "empty steps": ("name: t\ndemonstrations:\n  - steps: []\n", "must not be empty", ":3"),
    "undeclared step": (
        "name: t\nactions: [a]\ndemonstrations:\n  - steps: [a, b]\n",
        "demonstrations[0].steps[1]: action 'b' is not declared",
        ":4",
    ),
    "undeclared structure leaf": (
        "name: t\nactions: [a, b]\nstructure:\n  chain: [a, c]\n",
        "structure.chain[1]: action 'c' is not declared",
        ":4",
    ),
    "duplicate action ids": (
        "name: t\nactions:\n  - a\n  - a\n",
        "actions[1].id: duplicate action id 'a'",
        ":4",
    ),
    "duplicate demonstration ids": (
        "name: t\ndemonstrations:\n  - {id: x, steps: [a]}\n  - {id: x, steps: [a]}\n",
        "demonstrations[1].id: duplicate demonstration id 'x'",
        ":4",
    ),
    "two kinds in one node": ("name: t\nstructure: {chain: [a], clique: [b]}\n", "exactly one of", ":2"),
    "number as action": (
        "name: t\ndemonstrations:\n  - steps: [a, 3]\n",
        "steps[1]: expected a mapping",
        ":3",
    ),
    "start after end": (
        "name: t\ndemonstrations:\n  - steps:\n    - {action: a, start: 3, end: 1}\n",
        "start 3.0 is after end 1.0",
        ":4",
    ),
}


@pytest.mark.parametrize("case", sorted(BAD_YAML))
def test_bad_yaml_is_located(case: str, tmp_path: Path) -> None:
    text, message, line = BAD_YAML[case]
    path = tmp_path / "task.yaml"
    path.write_text(text)
    with pytest.raises(TaskFileError) as info:
        parse_task_file(path)
    rendered = str(info.value)
    assert rendered.startswith(str(path) + (line or ""))
    assert message in rendered
    assert "\n" not in rendered


def test_invalid_json_names_the_line(tmp_path: Path) -> None:
    path = tmp_path / "task.json"
    path.write_text('{"name": "t",\n "actions": [,]}\n')
    with pytest.raises(TaskFileError, match=r"task\.json:2: invalid JSON"):
        parse_task_file(path)


BAD_CSV = {
    "missing column": ("demonstration,action\nd1,a\n", "missing column(s) step"),
    "unknown column": ("demonstration,step,action,colour\nd1,1,a,red\n", "unknown column(s) colour"),
    "bad step": ("demonstration,step,action\nd1,one,a\n", ":2: step must be an integer"),
    "empty action": (
        "demonstration,step,action\nd1,1,\n",
        ":2: 'demonstration' and 'action' must not be empty",
    ),
    "repeated step": ("demonstration,step,action\nd1,1,a\nd1,1,b\n", "repeats a step number"),
    "header only": ("demonstration,step,action\n", "no demonstration rows"),
    "bad time": ("demonstration,step,action,start,end\nd1,1,a,x,2\n", ":2: start must be a number"),
}


@pytest.mark.parametrize("case", sorted(BAD_CSV))
def test_bad_csv(case: str, tmp_path: Path) -> None:
    text, message = BAD_CSV[case]
    path = tmp_path / "demos.csv"
    path.write_text(text)
    with pytest.raises(TaskFileError) as info:
        parse_task_file(path)
    assert message in str(info.value) and str(info.value).startswith(str(path))


def test_csv_sorts_steps_and_groups_demonstrations(tmp_path: Path) -> None:
    path = tmp_path / "demos.csv"
    path.write_text("demonstration,step,action,agent\nd1,2,b,ann\nd2,1,b,bo\nd1,1,a,ann\nd2,2,a,bo\n")
    spec = parse_task_file(path)
    assert [d.actions for d in spec.demonstrations] == [("a", "b"), ("b", "a")]
    assert [d.agent for d in spec.demonstrations] == ["ann", "bo"]


def test_unknown_suffix_and_missing_file(tmp_path: Path) -> None:
    (tmp_path / "task.txt").write_text("name: t\n")
    with pytest.raises(TaskFileError, match=r"unsupported file type '\.txt'; expected a task file \(\.yaml, \.yml, \.json or \.csv\)"):
        parse_task_file(tmp_path / "task.txt")
    with pytest.raises(TaskFileError, match="no such file"):
        parse_task_file(tmp_path / "missing.yaml")
    # issue 26: a missing file or a folder without a suffix said "unsupported file type '(none)'"
    with pytest.raises(TaskFileError, match=r"nope: no such file; expected a task file \(\.yaml"):
        parse_task_file(tmp_path / "nope")
    with pytest.raises(TaskFileError, match=r": is a folder; expected a task file \(\.yaml"):
        parse_task_file(tmp_path)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        # issue 26: a key whose value is a block was named by the line after it
        ("name: t\nactions: [a, b]\nstructure:\n  chian:\n    - a\n    - b\n", "t.yaml:4: structure: unknown key 'chian'; did you mean 'chain'?"),
        ("name: t\nactoins: [a]\n", "t.yaml:2: unknown key 'actoins'; did you mean 'actions'?"),
        ("name: t\nactions: [a]\ndemonstrations:\n  - steps: [a]\n    id:\n      x: 1\n", "t.yaml:5: demonstrations[0].id: expected a string, got a mapping"),
        ("name: t\nactions: [a, b]\ndemonstrations:\n  - steps:\n      - a\n      - bb\n", "t.yaml:6: demonstrations[0].steps[1]: action 'bb' is not declared in 'actions'; did you mean 'b'?"),
        ("name: t\nactions: [green, red]\nstructure: {chain: [red, gren]}\n", "structure.chain[1]: action 'gren' is not declared in 'actions'; did you mean 'green'?"),
        ("name: t\nactions:\n  - id: a\n    extra: 1\n", "t.yaml:4: actions[0]: unknown key 'extra'"),
    ],
)
def test_errors_name_the_key_line_and_a_close_name(tmp_path: Path, text: str, expected: str) -> None:
    path = tmp_path / "t.yaml"
    path.write_text(text)
    with pytest.raises(TaskFileError) as caught:
        parse_task_file(path)
    assert str(caught.value).endswith(expected) and "did you mean 'text'" not in str(caught.value)
    assert "Input should" not in str(caught.value) and "Value error" not in str(caught.value)
