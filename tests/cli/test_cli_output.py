"""What a new user reads: output that fits the terminal (issue 16.6) and the small things of issue 16.8 —
bundled names everywhere, help without placeholders, --version, a LICENSE, docs that cite only what the
repository has."""

from __future__ import annotations

import io
import json
import os
import re
import subprocess
import sys
import tomllib
from collections.abc import Callable
from importlib.metadata import version
from pathlib import Path

import pytest

from supportive.cli import app
from supportive.examples import load
from supportive.experiments.captaincook.recipes import RecipeReport
from supportive.experiments.statistics import format_ci, mean_ci

REPO = Path(__file__).resolve().parents[2]
SCRIPT = Path(sys.executable).parent / "supportive"
GUIDES = re.compile(r"[│├└─╭╮╯╰┃━┏┓┗┛┡┩╇╈┳┻]+")


def supportive(*args: str, columns: int, stdin: str = "", cwd: Path | None = None) -> str:
    env = {**os.environ, "COLUMNS": str(columns)}
    result = subprocess.run(
        [str(SCRIPT), *args], input=stdin, capture_output=True, text=True, env=env, cwd=cwd, check=False
    )
    assert result.returncode == 0, result.stderr
    return result.stdout


InProcess = Callable[..., str]


@pytest.fixture
def in_process(capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> InProcess:
    """``in_process(*args, columns=N, stdin="")``: what ``supportive ARGS`` prints at a terminal N columns wide
    (given ``stdin``), run in this process (the same text as :func:`supportive`'s fresh process, without its second of start-up; the
    program is named ``supportive`` as the script names it, also under ``python -m pytest``)."""
    from supportive.cli import main

    monkeypatch.setattr(sys.modules["__main__"], "__package__", None, raising=False)

    def run(*args: str, columns: int, stdin: str = "") -> str:
        monkeypatch.setattr(sys, "argv", ["supportive", *args])
        monkeypatch.setattr(sys, "stdin", io.StringIO(stdin))
        monkeypatch.setenv("COLUMNS", str(columns))
        try:
            main()
        except SystemExit as exc:
            assert not exc.code, capsys.readouterr().err
        return capsys.readouterr().out

    return run


def words(text: str) -> list[str]:
    return GUIDES.sub(" ", text).split()


def test_captaincook_never_cuts_a_number(
    in_process: InProcess, captaincook_reports: list[RecipeReport], monkeypatch: pytest.MonkeyPatch
) -> None:
    """Issue 16.6: at 80 columns every number was cut ("0.9…"). (The recipes are learned once; each run
    shows them.)"""
    from supportive.experiments.captaincook import recipes

    monkeypatch.setattr(recipes, "captaincook_report", lambda recipes: captaincook_reports)
    rows = json.loads(in_process("captaincook", "--json", columns=200))
    assert len(rows) == 24 and all(r["admits_demonstrations"] for r in rows)  # (was test_cli's captaincook JSON test)
    assert all(0 < r["recall"] <= 1 for r in rows)
    for columns in (80, 60):
        shown = in_process("captaincook", columns=columns)
        assert "…" not in shown and all(len(line) <= columns for line in shown.splitlines())
        seen = set(shown.split())
        for row in rows:
            for value in (row["precision"], row["recall"], row["f1"]):
                assert f"{value:.3f}" in seen or f"{value:.3f}," in seen, (row["recipe"], columns, value)
    wide = " ".join(in_process("captaincook", columns=200).split())
    for setting, key in (("full", "edges"), ("5-shot", "edges_5_shot")):  # the mean F1 with its interval
        interval = format_ci(mean_ci([r[key]["f1"] for r in rows], bounds=(0.0, 1.0)))
        assert f"({setting}, the protocol of Differentiable Task Graph Learning)" in wide
        assert f"F1 {interval} (95 % interval over the recipes)" in wide, (setting, interval)


def test_captaincook_uniform_prints_both_learners_and_nests_its_json(
    in_process: InProcess, captaincook_reports: list[RecipeReport], monkeypatch: pytest.MonkeyPatch
) -> None:
    from supportive.experiments.captaincook import recipes, uniform

    asked: list[tuple[int, object]] = []

    def drawn(recipes: list[object], draws: int, seed: int = 0, learner_options: object = None) -> uniform.UniformDraws:
        asked.append((draws, learner_options))
        figure = {"mean": 0.5 if learner_options else 0.25, "low": 0.125, "high": 0.75, "n": len(recipes)}
        return uniform.UniformDraws(draws, seed, figure, figure)

    monkeypatch.setattr(recipes, "captaincook_report", lambda recipes: captaincook_reports)
    monkeypatch.setattr(uniform, "uniform_draws", drawn)
    shown = json.loads(in_process("captaincook", "--json", "--uniform", "3", columns=200))
    assert len(shown["recipes"]) == 24 and asked == [(3, None), (3, {"mode": "strict"})]
    assert shown["uniform"]["strict"]["full"]["mean"] == 0.5 and shown["uniform"]["default"]["draws"] == 3
    pairs = shown["free_pairs"]
    assert 0 < pairs["kept"] <= pairs["free"] and 0 < pairs["expected"] <= pairs["free"]
    text = " ".join(in_process("captaincook", "--uniform", "3", columns=80).split())
    assert f"every recording in one order: {pairs['kept']} (uniform draws" in text
    assert "the default learner on 3 sets of recordings drawn uniformly" in text
    assert "task-graph F1 full 0.500 [0.125, 0.750], 5-shot 0.500 [0.125, 0.750]" in text


def test_the_demo_wraps_at_words_and_cuts_nothing(in_process: InProcess) -> None:
    """Issue 16.6: the demo cut the actions' descriptions mid-word at 80 columns."""
    shown = in_process("demo", columns=80)
    assert "…" not in shown and all(len(line) <= 80 for line in shown.splitlines())
    text = " ".join(words(shown))
    for action in load("ikea-chair").actions:
        assert f"{action.id} — {action.text}" in text, action.id


@pytest.mark.parametrize("columns", [60, 100])
def test_chat_and_learn_only_move_line_breaks(
    columns: int, tmp_path: Path, in_process: InProcess, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Issue 16.6: chat wrapped mid-word; wrapped at words, the words are those of a wide terminal."""
    said = "How will you help me attach the seat?\nbehaviors\nquit\n"
    monkeypatch.chdir(tmp_path)
    narrow = in_process("chat", "ikea-chair", "--save", "a.yaml", columns=columns, stdin=said)
    wide = in_process("chat", "ikea-chair", "--save", "b.yaml", columns=1000, stdin=said)
    shown = [line.removeprefix("> ") for line in narrow.splitlines()[1:]]  # "> " is input()'s prompt
    assert all(len(line) <= columns for line in shown)  # (the first line names a file, kept whole)
    assert words(narrow)[4:] == words(wide)[4:]
    tree = in_process("learn", "ikea-chair", columns=columns)
    assert all(len(line) <= columns for line in tree.splitlines())
    assert words(tree) == words(in_process("learn", "ikea-chair", columns=1000))


def test_help_shows_no_type_placeholders(in_process: InProcess) -> None:
    """Issue 16.8: --help showed <bool>, <str>, <int range>, <path> for every option."""
    import typer

    command = typer.main.get_command(app)
    names = [[name] for name in getattr(command, "commands", {}) if name != "bag"] + [["bag", "import"], ["bag", "export"], []]
    for name in names:
        shown = in_process(*name, "--help", columns=120)
        assert not re.search(r"<(bool|str|int|float|path|int range|float range)>", shown), (name, shown)


def test_help_reads_as_text_and_answers_to_h(in_process: InProcess) -> None:
    """Issue 26: `{FILE}`, `list[str]` as a type, TEXT where the choices could be listed, line breaks where the
    docstring wrapped, and no -h."""
    import typer

    command = typer.main.get_command(app)
    names = [[name] for name in getattr(command, "commands", {}) if name not in ("bag", "tokens")]
    names += [["bag", "import"], ["bag", "export"], ["tokens", "add"], ["tokens", "list"], ["tokens", "revoke"], []]
    for name in names:
        shown = in_process(*name, "-h", columns=120)
        assert shown == in_process(*name, "--help", columns=120), name
        assert "Usage: supportive" in shown and "-h" in shown, name
        assert not re.search(r"\{[A-Z]+\}|list\[", shown), (name, shown)
    choices = {
        "teach": "distance|connectivity|random",
        "chat": "bow|embeddings",
        "support": "conservative|greedy|aggressive",
        "workbench-sim": "student|peer|instructor",
        "caregiver": "house|playroom|apartment|FILE",
        "evaluate": "loo|K",
    }
    for shown_for, listed in choices.items():
        assert listed in in_process(shown_for, "-h", columns=160), shown_for
    wide = in_process("infer", "-h", columns=400)  # a sentence is not broken where its docstring wrapped
    assert "after each observation or known action (one JSON line each" in wide


def test_a_usage_error_is_in_plain_words() -> None:
    """Issue 26: pydantic's wording ("Value error, …") leaked into error lines."""
    result = subprocess.run([str(SCRIPT), "generate", "--profile", "cubist"], capture_output=True, text=True, check=False)
    assert result.returncode == 2 and "Value error" not in result.stderr
    assert "'cubist' is not one of 'ikea', 'uniform'" in result.stderr
    for value, said in (("-1", "expected at least 0"), ("x", "expected a whole number")):
        result = subprocess.run([str(SCRIPT), "generate", "--seed", value], capture_output=True, text=True, check=False)
        assert result.returncode == 2 and f"Invalid value for '--seed': {said}" in result.stderr, result.stderr
        assert "Input should" not in result.stderr


def test_version_and_license() -> None:
    """Issue 16.8: no --version; no LICENSE although pyproject says MIT."""
    assert supportive("--version", columns=80).strip() == f"supportive {version('supportive')}"
    project = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]
    assert project["license"] == {"text": "MIT"}
    assert (REPO / "LICENSE").read_text().startswith("MIT License")


def test_python_dash_m_supportive_is_the_program() -> None:
    """``python -m supportive`` (what one tries without the console script on the PATH) runs the program."""
    result = subprocess.run([sys.executable, "-m", "supportive", "--version"], capture_output=True, text=True, check=False)
    assert (result.returncode, result.stdout.strip()) == (0, f"supportive {version('supportive')}"), result.stderr
    result = subprocess.run([sys.executable, "-m", "supportive", "learn", "no-such-task"], capture_output=True, text=True, check=False)
    assert result.returncode == 2 and len(result.stderr.strip().splitlines()) == 1, result.stderr


def test_docs_cite_only_files_the_repository_has() -> None:
    """Issue 16.8: the docs cited a DESIGN.md that is not in the repository."""
    for doc in [REPO / "README.md", *(REPO / "docs").glob("*.md")]:
        text = doc.read_text()
        assert "DESIGN.md" not in text or (REPO / "DESIGN.md").exists(), doc.name
        for link in re.findall(r"\]\(([^)#:]+)(?:#[^)]*)?\)", text):  # every relative link resolves
            assert (doc.parent / link).exists(), (doc.name, link)


def test_bundled_names_work_in_learn_and_infer() -> None:
    """Issue 16.8: a bundled example's name worked in support and caregiver but not in learn, chat, teach."""
    assert "Assemble chair" in supportive("learn", "ikea-chair", columns=200) or "Build frame" in supportive(
        "learn", "ikea-chair", columns=200
    )
    stream = str(REPO / "examples" / "ikea-chair-observations.jsonl")
    lines = supportive("infer", "ikea-chair", "--observations", stream, columns=200).splitlines()
    last = next(d for d in load("ikea-chair").demonstrations if d.id == "d6").actions[-1]
    assert len(lines) == 48 and json.loads(lines[-1])["subgoals"][0][0] == last


def test_the_readme_says_captaincook_needs_the_sibling_data_folder() -> None:
    readme = (REPO / "README.md").read_text()
    assert "`captaincook`" in readme and "data/captaincook4d" in readme and "../shared" in readme


@pytest.mark.parametrize("args", [["learn", "tea-mistakes"], ["learn", "ikea-chair", "-f", "json"], ["demo"], ["learn", "nope"]])
def test_a_terminal_that_cannot_encode_unicode_gets_no_traceback(args: list[str]) -> None:
    """Issue 26: `PYTHONIOENCODING=ascii supportive …` ended in a UnicodeEncodeError traceback."""
    env = {**os.environ, "PYTHONIOENCODING": "ascii", "COLUMNS": "100"}
    result = subprocess.run([str(SCRIPT), *args], capture_output=True, text=True, env=env, check=False)
    assert "Traceback" not in result.stderr and result.returncode == (2 if "nope" in args else 0), result.stderr
    assert result.stdout.isascii() and result.stderr.isascii()
    if "json" in args:
        assert json.loads(result.stdout)["task"] == "ikea-chair"
