"""Command lines drawn at random from what still broke the promise after the hardening (issue 25): option
values at and past their limits through every command, output paths that are folders or have no suffix, and
task files that ``teach`` or ``chat`` refuse after a working copy would be made.

The promise, as in test_fuzz.py: exit 0, or exit 2 with one line ``supportive…: error: …`` on stderr and
nothing on stdout, never a traceback; on an error nothing is written; and never anything half-written (no
temporary file or staging folder left, no output that was not finished)."""

from __future__ import annotations

import contextlib
import math
from pathlib import Path
from typing import Any

import pytest
import typer
from hypothesis import given
from hypothesis import strategies as st

from supportive.cli import app

from . import strategies as fuzz
from .test_fuzz import BOUNDED, folder, run_cli, write

REPO = Path(__file__).resolve().parents[2]
OBSERVATIONS = str(REPO / "examples" / "ikea-chair-observations.jsonl")
GARBAGE = "garbage.yaml"

BASE: dict[str, dict[str, str | None]] = {
    "learn": {"": "blocks-v"},
    "infer": {"": "ikea-chair", "-O": OBSERVATIONS},
    "generate": {"--actions": "3", "-o": "{dir}/t.yaml"},
    "evaluate": {"": "two-glasses"},
    "captaincook": {"--data": "{dir}"},
    "teach": {"": f"{{dir}}/{GARBAGE}"},
    "chat": {"": f"{{dir}}/{GARBAGE}"},
    "demo": {},
    "caregiver": {"--steps": "2", "--every": "5"},
    "support": {"": "lamp-by-hand", "-e": "2"},
    "serve": {"--task": f"{{dir}}/{GARBAGE}"},  # a valid line would serve for ever: the task file ends it
    "workbench-sim": {"--role": "boss"},  # likewise: the role is checked after the numbers
    "reproduce": {"": "edge-reduction", "-n": "1", "-o": "{dir}/run"},
    "bag import": {"": str(REPO / "examples" / "bags" / "ikea-chair"), "-o": "{dir}/c.yaml"},
    "bag export": {"": "blocks-v", "-o": "{dir}/bag"},
    "tokens list": {"--db": "sqlite:///{dir}/none.db"},
    "tokens add": {"": "alice", "--db": "sqlite:///{dir}/none.db"},
    "tokens revoke": {"": "1", "--db": "sqlite:///{dir}/none.db"},
}
"""Per command, a cheap line that is valid but for what is drawn (``""``: the positional arguments)."""


def _numeric_options() -> list[tuple[str, str, type, float | None, float | None]]:
    """Every number option of every command: (command, option, int or float, least, most)."""
    found: list[tuple[str, str, type, float | None, float | None]] = []

    def walk(group: Any, prefix: str) -> None:
        for name, sub in getattr(group, "commands", {}).items():
            if hasattr(sub, "commands"):
                walk(sub, f"{prefix}{name} ")
                continue
            for param in sub.params:
                kind = getattr(getattr(param, "type_descriptor", None), "annotation", None)
                kinds = [k for k in (int, float) if kind is k or kind == k | None]
                if kinds and getattr(param, "opts", None) and param.opts[0].startswith("--"):
                    found.append((f"{prefix}{name}", param.opts[0], kinds[0], param.min, param.max))

    walk(typer.main.get_command(app), "")
    return found


NUMERIC = _numeric_options()


def line(command: str, changes: dict[str, str | None], where: Path) -> list[str]:
    """``command``'s cheap line with ``changes`` (an option given ``None`` is left out)."""
    options = {**BASE[command], **changes}
    args = command.split()
    for option, value in options.items():
        if value is None:
            continue
        args += [value] if option == "" else [option, value]
    return [arg.replace("{dir}", str(where)) for arg in args]


def leftovers(where: Path) -> list[str]:
    """Temporary files and staging folders under ``where``."""
    return sorted(p.name for p in where.rglob(".*") if ".tmp" in p.name or ".partial" in p.name)


def keeps_promise(code: int, out: str, err: str, where: Path, before: set[str]) -> None:
    assert "Traceback" not in err, err
    assert code in (0, 2), (code, err)
    assert leftovers(where) == []
    if code == 2:
        lines = err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("supportive") and ": error: " in lines[0], err
        assert out == "", out
        assert {p.name for p in where.iterdir()} == before  # nothing written


def test_every_command_has_a_cheap_line() -> None:
    assert {command for command, *_ in NUMERIC} <= set(BASE)
    assert len(NUMERIC) >= 15  # the table above is read from the app: a new option is fuzzed without a row


def past(kind: type, least: float | None, most: float | None) -> st.SearchStrategy[str]:
    """Values just and far past an option's bounds, and values that are no number."""
    beyond = [str(kind(most) + (1 if kind is int else 0.5))] if most is not None else []
    beyond += [str(kind(least) - (1 if kind is int else 0.5))] if least is not None else []
    return st.one_of(st.sampled_from(beyond or ["x"]), fuzz.PAST_A_LIMIT)


@given(data=st.data(), case=st.sampled_from(NUMERIC))
@BOUNDED
def test_option_values_past_their_limits_keep_the_promise(data: st.DataObject, case: tuple[str, str, type, float | None, float | None]) -> None:
    command, option, kind, least, most = case
    value = data.draw(past(kind, least, most))
    with folder() as where:
        write(where / GARBAGE, ": : :\n[")
        before = {p.name for p in where.iterdir()}
        code, out, err = run_cli(line(command, {option: value}, where))
        keeps_promise(code, out, err, where, before)
        number = _number(value)
        if number is None or (most is not None and number > most) or (least is not None and number < least):
            assert code == 2 and option in err.splitlines()[0], (value, err)  # refused, naming the option


def _number(text: str) -> float | None:
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


AT_LIMITS: list[tuple[list[str], str]] = [
    (["generate", "--actions", "100000", "--demonstrations", "10000"], "--demonstrations: 100,000 actions × 10,000"),
    (["generate", "--actions", "100000", "--demonstrations", "4"], "more than the 300,000 a generated task may have"),
    (["support", "lamp-by-hand", "--environments", "100000"], "duration estimates per decision, more than planner.estimate_limit"),
    (["support", "lamp-by-hand", "--workers", "256"], "--workers: 256 processes on a machine with"),
    (["reproduce", "edge-reduction", "--trials", "1000000", "--workers", "256"], "--workers: 256 processes"),
    (["bag", "export", "blocks-v", "-o", "{dir}/bag", "--start", "2147483647"], "a bag holds times from 0 to 2,147,483,647 s"),
]
"""Options at their most, whose run would take minutes or more, or break a format: refused at once."""


@pytest.mark.parametrize(("args", "problem"), AT_LIMITS, ids=[" ".join(a[:4]) for a, _ in AT_LIMITS])
def test_options_at_their_limits_are_refused_before_the_work_when_it_would_not_end(
    tmp_path: Path, args: list[str], problem: str
) -> None:
    code, out, err = run_cli([a.replace("{dir}", str(tmp_path)) for a in args])
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and problem in err, err
    assert list(tmp_path.iterdir()) == []


def test_options_at_their_limits_that_end_soon_run(tmp_path: Path) -> None:
    for args in (
        ["infer", "ikea-chair", "-O", OBSERVATIONS, "--top", "10000", "--mean-duration", "1000000"],
        ["generate", "--actions", "2", "--demonstrations", "10000", "-o", str(tmp_path / "t.yaml")],
        ["caregiver", "--steps", "1", "--delay", "60", "--seed", str(2**63)],
        ["bag", "export", "blocks-v", "-o", str(tmp_path / "bag"), "--start", "2147483000"],
    ):
        code, _, err = run_cli(args)
        assert code == 0, (args, err)
    assert leftovers(tmp_path) == []


OUTPUTS: dict[str, tuple[str, str]] = {
    "learn": ("learn", "-o"),
    "learn hddl": ("learn", "-o"),
    "generate": ("generate", "-o"),
    "caregiver": ("caregiver", "--gif"),
    "support": ("support", "--render"),
    "reproduce": ("reproduce", "-o"),
    "bag import": ("bag import", "-o"),
    "bag export": ("bag export", "-o"),
    "infer": ("infer", "--write-bag"),
    "teach": ("teach", "--save"),
    "chat": ("chat", "--save"),
    "serve": ("serve", "--db"),
}
"""Every option that names a file or folder to write, and the command it belongs to."""
EXTRA: dict[str, dict[str, str | None]] = {
    "learn hddl": {"--format": "hddl"},
    "infer": {"-O": None, "--bag": str(REPO / "examples" / "bags" / "ikea-chair")},
    "teach": {"": "blocks-tower"},
    "chat": {"": "ikea-chair"},
    "serve": {"--port": "1"},
}
PATHS = st.sampled_from(["{dir}", ".", "{dir}/", "{dir}/folder", "{dir}/noext", "{dir}/name.txt", "{dir}/missing/x.yaml"])


@given(case=st.sampled_from(list(OUTPUTS)), target=PATHS)
@BOUNDED
def test_output_paths_that_are_folders_or_have_no_suffix_keep_the_promise(case: str, target: str) -> None:
    command, option = OUTPUTS[case]
    with folder() as where, contextlib.chdir(where):
        (where / "folder").mkdir()
        write(where / GARBAGE, ": : :\n[")
        before = {p.name for p in where.iterdir()}
        value = f"sqlite:///{target}" if option == "--db" else target
        code, out, err = run_cli(line(command, {**EXTRA.get(case, {}), option: value}, where), stdin="quit\n")
        keeps_promise(code, out, err, where, before)
        if code == 0 and case in ("caregiver", "support"):
            raise AssertionError(f"{case} {option} {target}: a picture needs a file name with its suffix")


@given(task=fuzz.session_refused_tasks(), command=st.sampled_from(["teach", "chat"]))
@BOUNDED
def test_a_task_a_session_refuses_leaves_no_working_copy(task: tuple[str, str], command: str) -> None:
    suffix, text = task
    with folder() as where:
        path = write(where / f"t{suffix}", text)
        code, out, err = run_cli([command, str(path)], stdin="quit\n")
        assert "Traceback" not in err, err
        assert code in (0, 2), (code, err)
        if code == 2:
            assert out == "" and err.startswith(f"supportive: error: {path}") and len(err.strip().splitlines()) == 1, err
            assert [p.name for p in where.iterdir()] == [path.name]  # no working copy
