"""Every command without the extra it needs (its modules made unimportable in a fresh interpreter): one line
on stderr naming the extra, exit status 2, no traceback, nothing written (issue 16.3)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from supportive.extras import extra_of

REPO = Path(__file__).resolve().parents[1]

# Runs the command line with some top-level modules refused, as if their extra were not installed.
WITHOUT = """
import importlib.abc, sys
refused = set(sys.argv[1].split(","))
class Refuse(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in refused:
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return None
sys.meta_path.insert(0, Refuse())
sys.argv = ["supportive", *sys.argv[2:]]
from supportive.cli import main
main()
"""

BAG = str(REPO / "examples" / "bags" / "ikea-chair")
CASES = [
    (["learn", "ikea-chair", "--format", "hddl", "-o", "out"], "unified_planning,up_aries", "planning"),
    (["reproduce", "edge-reduction", "--trials", "2", "--workers", "2", "-o", "out"], "dask,distributed", "distributed"),
    (["reproduce", "edge-reduction", "--trials", "2", "-o", "out"], "matplotlib", "plot"),
    (["support", "two-cells-led", "--render", "out.png"], "matplotlib", "plot"),
    (["caregiver", "--steps", "3", "--gif", "out.gif"], "matplotlib", "plot"),
    (["serve", "--db", "sqlite:///out.db", "--port", "1"], "sqlalchemy", "server"),
    (["serve", "--db", "sqlite:///out.db", "--port", "1"], "fastapi", "server"),
    (["serve", "--db", "sqlite:///out.db", "--port", "1"], "uvicorn", "server"),
    (["tokens", "list", "--db", "sqlite:///out.db"], "sqlalchemy", "server"),
    (["workbench-sim", "--seconds", "1"], "httpx", "server"),
    (["workbench-sim", "--seconds", "1"], "sqlalchemy", "server"),
    (["chat", "ikea-chair", "--save", "out.yaml"], "sklearn", "language"),
    (["chat", "ikea-chair", "--matcher", "embeddings", "--save", "out.yaml"], "sentence_transformers,torch", "embeddings"),
    (["bag", "import", BAG, "--segment-topic", "/task/demonstration", "-o", "out.yaml"], "rosbags", "ros"),
    (["infer", "ikea-chair", "--bag", BAG], "rosbags", "ros"),
]


def ident(case: tuple[list[str], str, str]) -> str:
    return f"{case[0][0]}-{case[1]}"


def without(refused: str, args: list[str], folder: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", WITHOUT, refused, *args],
        cwd=folder,
        input="quit\n",
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )


@pytest.mark.parametrize(("args", "refused", "extra"), CASES, ids=[ident(c) for c in CASES])
def test_a_command_without_its_extra_says_which_in_one_line(
    args: list[str], refused: str, extra: str, tmp_path: Path
) -> None:
    result = without(refused, args, tmp_path)
    lines = result.stderr.strip().splitlines()
    assert result.returncode == 2, result.stderr
    assert len(lines) == 1 and "Traceback" not in result.stderr, result.stderr
    assert lines[0].startswith("supportive: error: ") and f"pip install 'supportive[{extra}]'" in lines[0]
    assert not any(p.name.startswith("out") for p in tmp_path.iterdir())  # nothing written (reproduce checks
    # for matplotlib before running, serve builds the app before it prints anything: issue 15)


def test_the_extras_come_from_the_package_metadata() -> None:
    assert [extra_of(m) for m in ("sklearn", "distributed", "psycopg", "unified_planning.io", "rosbags")] == [
        "language",
        "distributed",
        "server",
        "planning",
        "ros",
    ]
    assert extra_of("numpy") is None and extra_of("pytest") is None  # core, and tests only
