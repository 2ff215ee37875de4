from __future__ import annotations

import shutil
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from supportive import examples
from supportive.cli.teach_console import TeachingConsole
from supportive.io.taskfile import parse_task_file
from supportive.learning.active import QuerySchedule

TOWERS = ["yellow", "green", "white", "red", "blue", "purple", "black", "orange"]


def _console(path: Path, lines: list[str], shown: list[str]) -> TeachingConsole:
    script = iter(lines)

    def read() -> str:
        try:
            return next(script)
        except StopIteration:
            raise EOFError from None

    return TeachingConsole(path, read, shown.append, "distance", QuerySchedule(after_steps=(0, 2, 4)), seed=0)


def test_teaching_saves_demonstrations_and_asks_in_words(tmp_path: Path) -> None:
    path = tmp_path / "towers.yaml"
    shutil.copy(examples.path("blocks-towers"), path)
    shown: list[str] = []
    order = ["red", "blue", "purple", "black", "orange", "yellow", "green", "white"]
    spec = _console(path, [*order, *order[:2], "quit"], shown).run()
    saved = parse_task_file(path)
    assert saved == spec
    assert [d.actions for d in saved.demonstrations][-1] == tuple(order)
    assert (
        len(saved.demonstrations) == 5 and saved.demonstrations[-1].id == "d5"
    )  # the unfinished one is dropped
    questions = [line for line in shown if "robot: Can you place the" in line]
    assert questions and all(line.endswith("block next?") for line in questions)
    assert any("dropped the unfinished demonstration (2 steps)" in line for line in shown)


def test_bad_input_is_answered_not_crashed_on(tmp_path: Path) -> None:
    path = tmp_path / "towers.yaml"
    shutil.copy(examples.path("blocks-towers"), path)
    shown: list[str] = []
    _console(path, ["", "bogus", "99", "done", *TOWERS], shown).run(demonstrations=1)
    assert any("(empty line)" in line for line in shown)
    assert any("unknown action 'bogus'" in line for line in shown)
    assert any("unknown action '99'" in line for line in shown)
    assert any("nothing performed yet" in line for line in shown)
    assert parse_task_file(path).demonstrations[-1].actions == tuple(TOWERS)


def test_numbers_select_actions_and_a_new_file_starts_learning(tmp_path: Path) -> None:
    path = tmp_path / "knife.yaml"
    path.write_text("name: knife\nactions: [knife, carrots, celery]\n")
    shown: list[str] = []
    _console(path, ["1", "3", "2", "1", "2", "3"], shown).run()
    saved = parse_task_file(path)
    assert [d.actions for d in saved.demonstrations] == [
        ("knife", "celery", "carrots"),
        ("knife", "carrots", "celery"),
    ]
    assert any("hierarchy: complete" in line for line in shown)


def test_teach_command_reads_stdin(tmp_path: Path) -> None:
    path = tmp_path / "towers.yaml"
    shutil.copy(examples.path("blocks-towers"), path)
    script = shutil.which("supportive", path=str(Path(sys.executable).parent))
    assert script is not None
    order = ["purple", "black", "orange", "yellow", "green", "white", "red", "blue"]
    result = subprocess.run(
        [script, "teach", str(path), "--strategy", "connectivity", "--ask-after", "0,3"],
        input="\n".join([*order, "nonsense"]) + "\n",
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stderr
    assert "robot: Can you place the" in result.stdout
    assert "unknown action 'nonsense'" in result.stdout
    copy = tmp_path / "towers.edited.yaml"  # the file given is read, never changed
    assert result.stdout.startswith(f"Saving to {copy}, a new copy of {path} (which is not changed), made at the first change.")
    assert parse_task_file(copy).demonstrations[-1].actions == tuple(order)
    assert path.read_bytes() == examples.path("blocks-towers").read_bytes()
    bad = subprocess.run(
        [script, "teach", str(path), "--strategy", "psychic"], capture_output=True, text=True, check=False
    )
    assert bad.returncode == 2 and bad.stderr.strip().startswith(
        "supportive: error: --strategy: unknown strategy 'psychic'"
    )


TOWER = ["red", "yellow", "green", "white", "orange", "purple", "black", "blue"]


def _tower(tmp_path: Path) -> Path:
    path = tmp_path / "tower.yaml"
    shutil.copy(examples.path("blocks-tower"), path)
    return path


def test_a_repeated_action_is_refused_and_the_demonstration_is_whole(tmp_path: Path) -> None:
    """Issue 16.1: a repeat used to be recorded, and the demonstration then ended one action short."""
    path = _tower(tmp_path)
    shown: list[str] = []
    _console(path, ["red", "red", *TOWER[1:]], shown).run(demonstrations=1)
    assert parse_task_file(path).demonstrations[-1].actions == tuple(TOWER)  # blue placed, red once
    assert "  red is already done (once) in this demonstration; type another action" in shown


def test_done_before_every_action_says_what_is_left(tmp_path: Path) -> None:
    """Issue 16.1: `done` after one step used to save a one-step demonstration."""
    path = _tower(tmp_path)
    before = parse_task_file(path).demonstrations
    shown: list[str] = []
    _console(path, ["blue", "done", "quit"], shown).run()
    assert parse_task_file(path).demonstrations == before
    assert any(
        line.startswith("  not finished: still to do red, yellow, green, white, orange, purple, black")
        for line in shown
    )


def test_yes_performs_what_the_robot_asked_and_no_declines(tmp_path: Path) -> None:
    """Issue 16.1: the robot asks yes/no questions; "no" used to be read as an unknown action."""
    path = _tower(tmp_path)
    shown: list[str] = []

    def asked() -> str:
        question = [line for line in shown if "robot: Can you" in line][-1]
        return next(a for a in TOWER if f"place the {a} block" in question)

    def script() -> Iterator[str]:
        yield "red"
        declined = asked()  # the question after the first step
        yield "no"
        instead = next(a for a in TOWER[1:-1] if a != declined)
        yield instead
        third = asked()
        yield "yes"
        yield from (a for a in TOWER if a not in ("red", instead, third))

    feed = script()
    console = TeachingConsole(path, lambda: next(feed), shown.append, "distance", QuerySchedule(after_steps=(1, 2)))
    console.run(demonstrations=1)
    assert "  all right: type the action you do instead" in shown
    assert not any("unknown action" in line for line in shown)
    steps = parse_task_file(path).demonstrations[-1].actions
    assert steps[0] == "red" and sorted(steps) == sorted(TOWER)
    assert f"place the {steps[2]} block" in [line for line in shown if "robot: Can you" in line][-1]


def test_typos_get_a_did_you_mean_and_case_does_not_matter(tmp_path: Path) -> None:
    """Issue 16.1: names were case-sensitive and a typo got no suggestion."""
    path = _tower(tmp_path)
    shown: list[str] = []
    lines = ["RED", "gren", "Place the Yellow Block", "3", *TOWER[3:]]
    _console(path, lines, shown).run(demonstrations=1)
    assert "  unknown action 'gren'; did you mean 'green'? ('help' lists them)" in shown
    assert parse_task_file(path).demonstrations[-1].actions == tuple(TOWER)


def test_an_action_the_task_repeats_may_be_repeated(tmp_path: Path) -> None:
    path = tmp_path / "soup.yaml"
    path.write_text("name: soup\nactions: [pour, stir, taste]\ndemonstrations:\n  - {id: d1, steps: [pour, stir, taste, stir]}\n")
    shown: list[str] = []
    _console(path, ["pour", "stir", "stir", "stir", "taste"], shown).run(demonstrations=1)
    assert parse_task_file(path).demonstrations[-1].actions == ("pour", "stir", "stir", "taste")
    assert "  stir is already done (2 times) in this demonstration; type another action" in shown


def _teach(args: list[str], cwd: Path, lines: list[str]) -> subprocess.CompletedProcess[str]:
    script = Path(sys.executable).parent / "supportive"
    return subprocess.run(
        [str(script), "teach", *args], cwd=cwd, input="\n".join(lines) + "\n", capture_output=True, text=True, check=False
    )


def test_teaching_a_bundled_example_never_writes_into_the_package(tmp_path: Path) -> None:
    """Issue 16.2: the README's teach line used to rewrite the package's own example."""
    bundled = examples.path("blocks-tower")
    before = bundled.read_bytes()
    result = _teach(["blocks-tower"], tmp_path, [*TOWER, "quit"])  # by name: the bundled file
    assert result.returncode == 0, result.stderr
    copy = tmp_path / "blocks-tower.edited.yaml"
    assert bundled.read_bytes() == before
    assert len(parse_task_file(copy).demonstrations) == len(parse_task_file(bundled).demonstrations) + 1
    again = _teach(["blocks-tower"], tmp_path, [*reversed(TOWER[1:-1]), "quit"])
    assert again.stdout.startswith(f"Carrying on in {copy.name}")  # a second session adds to the first
    into = _teach(["blocks-tower", "--save", str(bundled)], tmp_path, ["quit"])
    assert into.returncode == 2 and "inside the installed supportive package" in into.stderr
    assert bundled.read_bytes() == before


def test_save_names_the_copy_and_refuses_another_tasks_file(tmp_path: Path) -> None:
    mine = tmp_path / "mine.yaml"
    result = _teach(["blocks-tower", "--save", str(mine)], tmp_path, [*TOWER, "quit"])
    assert result.returncode == 0 and parse_task_file(mine).demonstrations[-1].actions == tuple(TOWER)
    other = _teach(["knife-carrots-celery", "--save", str(mine)], tmp_path, ["quit"])
    assert other.returncode == 2
    assert other.stderr.strip() == (
        f"supportive: error: {mine}: it holds task 'blocks-tower', not 'knife-carrots-celery': choose another "
        "file with --save PATH"
    )


def test_the_robot_never_asks_for_what_the_structure_rules_out(tmp_path: Path) -> None:
    """Issue 26: "yes" to "Can you place the blue block next?" after red recorded an order the tower's own
    structure forbids. Whatever the strategy and seed, saying yes to every question now gives a demonstration
    the structure admits."""
    from supportive.tasks.htn import HTN

    path = _tower(tmp_path)
    structure = parse_task_file(path).structure
    assert structure is not None
    for strategy in ("distance", "connectivity", "random"):
        for seed in range(4):
            shown: list[str] = []
            done: list[str] = []

            def answer(shown: list[str] = shown, done: list[str] = done) -> str:
                waiting = shown[-1].removeprefix("  robot: ") if "robot: Can you" in shown[-1] else None
                if waiting is not None:
                    done.append(next(a for a in TOWER if f"place the {a} block" in waiting))
                    return "yes"
                done.append(next(a for a in TOWER if a not in done))
                return done[-1]

            schedule = QuerySchedule(after_steps=tuple(range(8)), max_per_demonstration=8)
            TeachingConsole(path, answer, shown.append, strategy, schedule, seed).run(demonstrations=1)
            steps = parse_task_file(path).demonstrations[-1].actions
            assert HTN("tower", (structure,)).admits(steps), (strategy, seed, steps)
            assert not any("note:" in line for line in shown)


def test_a_demonstration_is_numbered_as_saved_and_echoed(tmp_path: Path) -> None:
    """Issue 26: teach showed "Demonstration 1" and saved d5, and did not say what it recorded."""
    path = _tower(tmp_path)
    shown: list[str] = []
    _console(path, [*TOWER], shown).run(demonstrations=1)
    assert "Demonstration d5:" in shown and not any(line.startswith("Demonstration 1") for line in shown)
    assert f"  recorded: {', '.join(TOWER)}" in shown
    assert parse_task_file(path).demonstrations[-1].id == "d5"


def test_an_order_the_structure_rules_out_is_recorded_with_a_note(tmp_path: Path) -> None:
    path = _tower(tmp_path)
    shown: list[str] = []
    order = ["red", "blue", *TOWER[1:-1]]
    _console(path, order, shown).run(demonstrations=1)
    assert any(line.startswith("  note: the task's structure has no order with blue here") for line in shown)
    assert parse_task_file(path).demonstrations[-1].actions == tuple(order)  # the person's word is recorded


def test_a_session_that_records_nothing_makes_no_copy(tmp_path: Path) -> None:
    """Issue 26: teach and chat made their copy even on a bare quit."""
    script = Path(sys.executable).parent / "supportive"
    for command, task in (("teach", "blocks-tower"), ("chat", "ikea-chair")):
        result = subprocess.run(
            [str(script), command, task, "--save", "c.yaml"],
            cwd=tmp_path, input="quit\n", capture_output=True, text=True, check=False,
        )
        assert result.returncode == 0, result.stderr
        assert "made at the first change" in result.stdout
    assert list(tmp_path.iterdir()) == []


def test_the_consoles_get_line_editing_on_a_terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    """Issue 26: no line editing (readline) in teach or chat."""
    import importlib.util
    import io

    from supportive.cli.output import line_editing

    monkeypatch.setattr(sys, "stdin", io.StringIO("red\n"))
    assert line_editing() is False  # a pipe: nothing to edit
    fake = io.StringIO()
    monkeypatch.setattr(fake, "isatty", lambda: True)
    monkeypatch.setattr(sys, "stdin", fake)
    assert line_editing() is (importlib.util.find_spec("readline") is not None)
    if line_editing():
        assert "readline" in sys.modules
