"""Every subcommand on broken inputs (issue 17): exit status 2 and one line ``supportive: error: …`` on stderr
naming the file or option and what was wrong, nothing on stdout, never a traceback. The table covers every
command of the app (a new command without a row fails ``test_every_command_has_broken_inputs``); the fuzz
suite (tests/fuzz) draws malformed files for the commands that read them."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
import typer

from supportive.cli import app

CliRunner = Callable[[list[str]], tuple[int, str, str]]

FILES = {
    "garbage.yaml": ": : :\n[",
    "empty.yaml": "",
    "no-demos.yaml": "name: t\nactions: [{id: a}, {id: b}]\n",
    "one-demo.yaml": "name: t\nactions: [{id: a}, {id: b}]\ndemonstrations:\n  - steps: [a, b]\n",
    "no-events.yaml": "name: t\nactions: [{id: a}, {id: b}]\ndemonstrations:\n  - steps: [a, b]\n  - steps: [b, a]\n",
    "bad-stream.jsonl": '{"x": 1}\n',
    "actions.txt": "a\nb\n",
    "no-bin.map": "#####\n#...#\n#####\n",
    "bad.map": "####\n#?B#\n####\n",
    "both.yaml": "name: s\n",
    "unknown.csv": "x\n",
}
"""The broken files each case may name (``{dir}/NAME``), written fresh for every case."""

BROKEN: dict[str, list[tuple[list[str], str]]] = {
    "learn": [
        (["learn", "{dir}/missing.yaml"], "missing.yaml: no such file"),
        (["learn", "{dir}/garbage.yaml"], "garbage.yaml:1: invalid YAML"),
        (["learn", "{dir}/empty.yaml"], "empty.yaml: file is empty"),
        (["learn", "{dir}/no-demos.yaml"], "no-demos.yaml: demonstrations: no demonstrations to learn from"),
        (["learn", "{dir}"], "is a folder; expected a task file (.yaml, .yml, .json or .csv)"),
        (["learn", "nope"], "nope: no such file, nor a bundled example of that name; expected a task file"),
        (["learn", "{dir}/one-demo.yaml", "--format", "hddl"], "--format hddl needs --output DIR"),
        (["learn", "{dir}/one-demo.yaml", "-o", "{dir}"], "cannot write: not a regular file"),
    ],
    "infer": [
        (["infer", "{dir}/garbage.yaml", "--actions", "{dir}/actions.txt"], "garbage.yaml:1: invalid YAML"),
        (["infer", "{dir}/one-demo.yaml"], "give one source"),
        (["infer", "{dir}/one-demo.yaml", "--actions", "{dir}/missing.txt"], "missing.txt: no such file"),
        (["infer", "{dir}/one-demo.yaml", "-O", "{dir}/bad-stream.jsonl"], "bad-stream.jsonl:1: unknown key 'x'"),
        (["infer", "{dir}/no-events.yaml", "-O", "{dir}/empty.yaml"], "empty.yaml: file is empty"),
        (["infer", "{dir}/no-events.yaml", "--bag", "{dir}/missing"], "actions without 'observations'"),
        (["infer", "{dir}/one-demo.yaml", "-A", "{dir}/actions.txt", "--write-bag", "{dir}/b"], "--write-bag needs --bag"),
        (["infer", "{dir}/one-demo.yaml", "-A", "{dir}/actions.txt", "--model", "flat"], "--actions needs --model progress"),
    ],
    "generate": [
        (["generate", "-o", "{dir}"], "is a folder; expected a task file"),
        (["generate", "-o", "{dir}/task.txt"], "unsupported file type"),
    ],
    "evaluate": [
        (["evaluate", "{dir}/one-demo.yaml"], "cross-validation needs at least two demonstrations"),
        (["evaluate", "{dir}/no-events.yaml", "--folds", "one"], "--folds: expected auto, loo or a number of folds"),
        (["evaluate", "{dir}/garbage.yaml"], "garbage.yaml:1: invalid YAML"),
    ],
    "captaincook": [
        (["captaincook", "--data", "{dir}/missing"], "missing: no such directory"),
        (["captaincook", "--data", "{dir}"], "file not found"),
    ],
    "teach": [
        (["teach", "{dir}/garbage.yaml"], "garbage.yaml:1: invalid YAML"),
        (["teach", "{dir}/one-demo.yaml", "--strategy", "psychic"], "--strategy: unknown strategy 'psychic'"),
        (["teach", "{dir}/one-demo.yaml", "--ask-after", "x"], "--ask-after: expected step counts like 1,3,5"),
    ],
    "chat": [
        (["chat", "{dir}/garbage.yaml"], "garbage.yaml:1: invalid YAML"),
        (["chat", "{dir}/one-demo.yaml"], "one-demo.yaml: task 't' has no structure"),
        (["chat", "{dir}/one-demo.yaml", "--matcher", "psychic"], "--matcher: unknown matcher 'psychic'"),
    ],
    "demo": [],  # it reads nothing a user gives; an extra argument is a usage error (below)
    "caregiver": [
        (["caregiver", "--map", "{dir}/missing.map"], "missing.map: no such file"),
        (["caregiver", "--map", "{dir}/bad.map"], "bad.map:2:2: unknown map character '?'"),
        (["caregiver", "--map", "{dir}/no-bin.map"], "the map has no toy bin"),
        (["caregiver", "--novice", "2"], "--novice: ε must be in [0, 1]"),
    ],
    "support": [
        (["support", "{dir}/missing.yaml"], "missing.yaml: no such file"),
        (["support", "ikea-chair"], "(that is a bundled task, for learn, teach, chat, …); expected a scenario file"),
        (["support", "{dir}/garbage.yaml"], "garbage.yaml:1: invalid YAML"),
        (["support", "{dir}/both.yaml"], "give the pieces either as 'pieces'"),
        (["support", "two-cells-led", "--scheme", "reckless"], "reckless"),
    ],
    "serve": [
        (["serve", "--task", "{dir}/garbage.yaml", "--port", "1"], "garbage.yaml:1: invalid YAML"),
        (["serve", "--db", "nonsense://", "--port", "1"], "cannot use database 'nonsense://'"),
        (["serve", "--agent", "alice", "--port", "1"], "agent 'alice': expected name:kind:role[:token]"),
        (["serve", "--agent", "a:human:lead", "--agent", "a:robot:assistant", "--port", "1"], "named twice"),
    ],
    "workbench-sim": [
        (["workbench-sim", "--role", "boss"], "--role: unknown role 'boss'"),
    ],
    "reproduce": [
        (["reproduce", "nonexistent", "-o", "{dir}/out"], "unknown experiment 'nonexistent'"),
        (["reproduce", "edge-reduction", "-w", "2", "--scheduler", "tcp://127.0.0.1:1"], "mutually exclusive"),
        (["reproduce", "caregiver", "--reading", "nope", "-o", "{dir}/out"], "unknown reading 'nope'"),
    ],
    "tokens list": [
        (["tokens", "list", "--db", "sqlite:///{dir}/missing.db"], "no board in sqlite:///"),
        (["tokens", "list", "--db", "nonsense"], "cannot use database 'nonsense': expected a URL like"),
        (["tokens", "list", "--db", "mysql://me:secret@127.0.0.1/board"], "cannot use database 'mysql://me:***@127.0.0.1/board': a board is kept in SQLite (sqlite:///board.db) or PostgreSQL"),
        (["tokens", "list", "--db", "sqlite:///{dir}/garbage.yaml"], "garbage.yaml: file is not a database"),
    ],
    "tokens add": [
        (["tokens", "add", "alice", "--db", "sqlite:///{dir}/missing.db"], "no board in sqlite:///"),
        (["tokens", "add", "a\x1b[2J", "--kind", "human", "--role", "lead"], "control character"),
        (["tokens", "add", "alice", "--role", "lead"], "give --kind and --role together"),
    ],
    "tokens revoke": [
        (["tokens", "revoke", "1", "--db", "sqlite:///{dir}/missing.db"], "no board in sqlite:///"),
        (["tokens", "revoke"], "name the tokens to revoke by number"),
    ],
    "bag import": [
        (["bag", "import", "{dir}/missing.bag"], "missing.bag: no such bag"),
        (["bag", "import", "{dir}/garbage.yaml"], "not a ROS bag"),
        (["bag", "import", "{dir}/missing.bag", "--segment-topic", "/t", "--actions-topic", "/t"], "give two topics"),
    ],
    "bag export": [
        (["bag", "export", "{dir}/missing.yaml", "-o", "{dir}/out.bag"], "missing.yaml: no such file"),
        (["bag", "export", "{dir}/garbage.yaml", "-o", "{dir}/out.bag"], "garbage.yaml:1: invalid YAML"),
        (["bag", "export", "{dir}/one-demo.yaml", "-o", "{dir}"], "exists already"),
    ],
}

USAGE: list[list[str]] = [
    ["demo", "extra-argument"],
    ["generate", "--profile", "cubist"],
    ["learn"],
    ["bag", "import"],
    ["nonexistent-command"],
]
"""Usage errors click reports itself (a usage panel, exit 2)."""


def _commands(command: Any, prefix: str = "") -> set[str]:
    """The app's leaf commands, as ``"bag import"`` (typer's groups have ``commands``)."""
    names: set[str] = set()
    for name, sub in getattr(command, "commands", {}).items():
        names |= _commands(sub, f"{prefix}{name} ") if hasattr(sub, "commands") else {f"{prefix}{name}"}
    return names


def test_every_command_has_broken_inputs() -> None:
    commands = _commands(typer.main.get_command(app))
    assert "bag import" in commands and "learn" in commands
    assert commands == set(BROKEN)


def _cases() -> list[tuple[list[str], str]]:
    return [case for cases in BROKEN.values() for case in cases]


@pytest.mark.parametrize(("args", "problem"), _cases(), ids=[" ".join(a) for a, _ in _cases()])
def test_a_broken_input_is_one_line_without_a_traceback(
    tmp_path: Path, cli: CliRunner, args: list[str], problem: str
) -> None:
    for name, text in FILES.items():
        (tmp_path / name).write_text(text)
    before = sorted(tmp_path.iterdir())
    code, out, err = cli([arg.format(dir=tmp_path) for arg in args])
    assert "Traceback" not in err, err
    assert code == 2, (code, out, err)
    assert out == "", out
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("supportive: error: "), err
    assert problem in lines[0], err
    assert sorted(tmp_path.iterdir()) == before  # nothing written on an error


@pytest.mark.parametrize("args", USAGE, ids=[" ".join(a) for a in USAGE])
def test_a_usage_error_is_one_line_without_a_traceback(cli: CliRunner, args: list[str]) -> None:
    code, out, err = cli(args)
    assert code == 2 and out == "" and "Traceback" not in err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("supportive") and ": error: " in lines[0], err
