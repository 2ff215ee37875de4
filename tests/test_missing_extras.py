"""Every command without the extra it needs (its modules made unimportable, in an interpreter that has not
imported them): one line on stderr naming the extra, exit status 2, no traceback, nothing written (issue
16.3)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

from supportive.extras import extra_of

REPO = Path(__file__).resolve().parents[1]

# One interpreter per worker imports the command line and the core libraries once (none of them an extra's),
# then forks a child per command: the child refuses some top-level modules, as if their extra were not
# installed, and runs the command with its own folder, input and output files. What a command imports from
# an extra it imports in the child, so the refusal holds as in a fresh interpreter; the parent checks that it
# holds no module of any extra the cases refuse. Each line on stdin is one command (JSON); each line out,
# its exit status.
SERVER = """
import importlib.abc, json, os, sys
refusable = set(sys.argv[1].split(","))
import numpy, scipy.sparse, networkx, pydantic, yaml, lark, typer, rich  # the core install: no extra
from supportive.cli import main
held = sorted(m for m in sys.modules if m.split(".")[0] in refusable)
assert not held, f"the parent holds modules of an extra: {held}"
class Refuse(importlib.abc.MetaPathFinder):
    def __init__(self, refused):
        self.refused = refused
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in self.refused:
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return None
for line in sys.stdin:
    case = json.loads(line)
    pid = os.fork()
    if pid == 0:
        os.chdir(case["folder"])
        sys.meta_path.insert(0, Refuse(set(case["refused"].split(","))))
        for fd, name, mode in ((0, "in.txt", os.O_RDONLY), (1, "..stdout", os.O_WRONLY | os.O_CREAT), (2, "..stderr", os.O_WRONLY | os.O_CREAT)):
            os.dup2(os.open(os.path.join(case["io"], name), mode), fd)
        sys.stdin, sys.stdout, sys.stderr = open(0, closefd=False), open(1, "w", closefd=False), open(2, "w", closefd=False)
        sys.argv = ["supportive", *case["args"]]
        code = 0
        try:
            main()
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
        except BaseException:
            import traceback; traceback.print_exc(); code = 1
        sys.stdout.flush(); sys.stderr.flush()
        os._exit(code)
    _, status = os.waitpid(pid, 0)
    print(os.waitstatus_to_exitcode(status), flush=True)
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


@dataclass
class Server:
    """The forking interpreter of one worker."""

    process: subprocess.Popen[str]

    def run(self, refused: str, args: list[str], folder: Path, io: Path) -> tuple[int, str]:
        """Run ``supportive ARGS`` in ``folder`` with ``refused`` unimportable; its status and stderr."""
        assert self.process.stdin is not None and self.process.stdout is not None
        (io / "in.txt").write_text("quit\n")
        line = json.dumps({"refused": refused, "args": args, "folder": str(folder), "io": str(io)})
        self.process.stdin.write(line + "\n")
        self.process.stdin.flush()
        status = self.process.stdout.readline()
        assert status, f"the server ended: {self.process.stderr.read() if self.process.stderr else ''}"
        return int(status), (io / "..stderr").read_text()


@pytest.fixture(scope="module")
def server() -> Iterator[Server]:
    refusable = sorted({name for _, refused, _ in CASES for name in refused.split(",")})
    process = subprocess.Popen(
        [sys.executable, "-c", SERVER, ",".join(refusable)],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "COLUMNS": "200"},
    )
    yield Server(process)
    assert process.stdin is not None
    process.stdin.close()
    process.wait(timeout=60)


@pytest.mark.parametrize(("args", "refused", "extra"), CASES, ids=[ident(c) for c in CASES])
def test_a_command_without_its_extra_says_which_in_one_line(
    args: list[str], refused: str, extra: str, tmp_path: Path, server: Server
) -> None:
    folder, io = tmp_path / "run", tmp_path / "io"
    folder.mkdir()
    io.mkdir()
    code, stderr = server.run(refused, args, folder, io)
    lines = stderr.strip().splitlines()
    assert code == 2, stderr
    assert len(lines) == 1 and "Traceback" not in stderr, stderr
    assert lines[0].startswith("supportive: error: ") and f"pip install 'supportive[{extra}]'" in lines[0]
    assert not any(p.name.startswith("out") for p in folder.iterdir())  # nothing written (reproduce checks
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
