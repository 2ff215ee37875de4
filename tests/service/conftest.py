"""The board service under test: an in-process app, real servers on 127.0.0.1, SQLite and PostgreSQL.

PostgreSQL is a throwaway cluster made for the session with Debian's binaries (``make test`` installs
them): ``initdb`` in a temporary directory (as the ``postgres`` user when the tests run as root), listening
on 127.0.0.1 only, on a free port. The page is driven in Debian's chromium with Playwright (no browser
download); screenshots go to test-artifacts/. Missing binaries fail the tests rather than skip them.
"""

from __future__ import annotations

import io
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import httpx
import pytest
from fastapi.testclient import TestClient
from PIL import Image
from playwright.sync_api import Browser, Page, ViewportSize, expect, sync_playwright
from tests.conftest import CHROMIUM, need_system, postgres_binaries
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

from supportive.examples import path as example_path
from supportive.io.taskfile import parse_task_file
from supportive.service.app import create_app
from supportive.service.launch import free_port
from supportive.service.settings import ServiceSettings, board_of, parse_agent

TOKENS = {"alice": "tok-alice", "bob": "tok-bob", "robot": "tok-robot", "screen": "tok-screen"}
AGENTS = (
    "alice:human:lead:tok-alice",
    "bob:human:lead:tok-bob",
    "robot:robot:assistant:tok-robot",
    "screen:human:observer:tok-screen",
)
LEAD_ONLY = ("Attach seat",)


def auth(agent: str) -> dict[str, str]:
    return {"Authorization": f"Bearer {TOKENS[agent]}"}


@dataclass
class Postgres:
    port: int
    run_as: list[str]
    binaries: Path

    def fresh_database(self) -> str:
        """A new, empty database on the cluster; its URL."""
        name = f"board_{time.monotonic_ns()}"
        command = [
            str(self.binaries / "createdb"),
            "-h",
            "127.0.0.1",
            "-p",
            str(self.port),
            "-U",
            "postgres",
            name,
        ]
        subprocess.run([*self.run_as, *command], check=True, capture_output=True)
        return f"postgresql+psycopg://postgres@127.0.0.1:{self.port}/{name}"


@pytest.fixture(scope="session")
def postgres() -> Iterator[Postgres]:
    found = postgres_binaries()
    need_system("PostgreSQL", bool(found))  # absent: an error as root (CI), else a skip saying why
    binaries = Path(found[-1]).parent
    directory = Path(tempfile.mkdtemp(prefix="supportive-pg-"))
    run_as: list[str] = []
    if os.geteuid() == 0:
        shutil.chown(directory, "postgres", "postgres")
        run_as = ["runuser", "-u", "postgres", "--"]
    data = directory / "data"
    subprocess.run(
        [*run_as, str(binaries / "initdb"), "-D", str(data), "-U", "postgres", "--auth=trust"],
        check=True,
        capture_output=True,
    )
    port = free_port()
    # A commit is acknowledged before its WAL reaches the disk (synchronous_commit=off): the tests kill the
    # board's server, never PostgreSQL, so what it acknowledged is there all the same (10,000 operations: 18 s
    # to 13 s).
    options = f"-h 127.0.0.1 -p {port} -k {directory} -c fsync=on -c synchronous_commit=off -c max_connections=200"
    subprocess.run(
        [
            *run_as,
            str(binaries / "pg_ctl"),
            "-D",
            str(data),
            "-o",
            options,
            "-l",
            str(directory / "log"),
            "-w",
            "start",
        ],
        check=True,
        capture_output=True,
    )
    try:
        yield Postgres(port, run_as, binaries)
    finally:
        subprocess.run(
            [*run_as, str(binaries / "pg_ctl"), "-D", str(data), "-m", "immediate", "stop"],
            capture_output=True,
        )
        shutil.rmtree(directory, ignore_errors=True)


@pytest.fixture(params=["sqlite", "postgresql"])
def database(request: pytest.FixtureRequest, tmp_path: Path) -> str:
    """A fresh database of each kind."""
    if request.param == "sqlite":
        return f"sqlite:///{tmp_path / 'board.db'}"
    cluster: Postgres = request.getfixturevalue("postgres")
    return cluster.fresh_database()


def chair_settings(database: str) -> ServiceSettings:
    spec = parse_task_file(example_path("ikea-chair"))
    return ServiceSettings(database, board_of(spec, LEAD_ONLY), tuple(parse_agent(a) for a in AGENTS), spec)


@pytest.fixture
def client(database: str) -> Iterator[TestClient]:
    with TestClient(create_app(chair_settings(database))) as test_client:
        yield test_client


@dataclass
class Server:
    """A `supportive serve` process."""

    url: str
    database: str
    port: int
    process: subprocess.Popen[bytes]

    def kill(self) -> None:
        self.process.send_signal(signal.SIGKILL)
        self.process.wait(10)

    def stop(self) -> None:
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(10)
            except subprocess.TimeoutExpired:
                self.kill()


def serve_command(database: str, port: int, *args: str) -> list[str]:
    """``supportive serve`` of the board in ``database`` on ``port``, with ``args``."""
    return [sys.executable, "-m", "supportive.cli", "serve", "--db", database, "--port", str(port), *args]


def wait_until_answers(
    url: str, process: subprocess.Popen[Any], headers: dict[str, str] | None = None, seconds: float = 30
) -> None:
    """Poll ``url`` until it answers 200; fail when the process exits first (with what it wrote on stderr) or
    after ``seconds`` (the process killed)."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if process.poll() is not None:
            log = process.stderr.read() if process.stderr else ""
            raise RuntimeError(f"server exited: {log.decode() if isinstance(log, bytes) else log}")
        try:
            if httpx.get(url, headers=headers, timeout=1).status_code == 200:
                return
        except httpx.HTTPError:
            time.sleep(0.05)
    process.kill()
    raise RuntimeError(f"server did not answer {url} within {seconds:g} s")


def start_server(database: str, port: int | None = None, extra: tuple[str, ...] = ()) -> Server:
    port = port or free_port()
    agents = [x for a in AGENTS for x in ("--agent", a)]
    lead_only = [x for name in LEAD_ONLY for x in ("--lead-only", name)]
    command = serve_command(database, port, "--host", "127.0.0.1", *agents, *lead_only, *extra)
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    url = f"http://127.0.0.1:{port}"
    wait_until_answers(f"{url}/api/me", process, auth("screen"))
    return Server(url, database, port, process)


BANNER_END = "  API docs at "
"""The start of the last line of the banner ``serve`` prints (and flushes) before it serves."""


class ServeProcess:
    """``supportive serve`` of the chair's board on a database, run in a folder with the options a test gives:
    started, its banner read, waited on until its page answers, stopped with SIGTERM (which must exit 0)."""

    def __init__(self, database: str, cwd: Path) -> None:
        self.database, self.cwd, self.port = database, cwd, free_port()
        self.process: subprocess.Popen[str] | None = None
        self.banner: list[str] = []
        self.stderr = ""
        """What the last run that was stopped wrote on stderr (its log)."""

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def start(self, *args: str) -> dict[str, str]:
        """Start it with ``args``; the tokens its banner shows, by agent (none when every agent has one)."""
        command = serve_command(self.database, self.port, *args)
        self.process = subprocess.Popen(command, cwd=self.cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        assert self.process.stdout is not None
        self.banner = []
        while not self.banner or not self.banner[-1].startswith(BANNER_END):
            line = self.process.stdout.readline()
            assert line, self.process.communicate()
            self.banner.append(line.rstrip("\n"))
        wait_until_answers(f"{self.url}/", self.process)
        return dict(re.findall(r"new token for (\w+) \([^)]*\): (\S+)$", "\n".join(self.banner), re.MULTILINE))

    def stop(self) -> None:
        if self.process is not None and self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            _, self.stderr = self.process.communicate(timeout=30)
            assert self.process.returncode == 0, self.stderr

    def post(self, path: str, token: str) -> int:
        """The status of a POST to ``path`` with the token."""
        return httpx.post(f"{self.url}{path}", headers={"Authorization": f"Bearer {token}"}, timeout=10).status_code

    def me(self, token: str, key: str) -> Any:
        """``key`` of who the token signs in as over HTTP (``/api/me``), or the status when it is refused."""
        response = httpx.get(f"{self.url}/api/me", headers={"Authorization": f"Bearer {token}"}, timeout=10)
        return response.json()[key] if response.status_code == 200 else response.status_code

    def socket(self, token: str, key: str) -> Any:
        """``key`` of the first message a WebSocket with the token gets, or the code it is closed with."""
        with connect(f"ws://127.0.0.1:{self.port}/api/ws?token={token}", open_timeout=10) as ws:
            try:
                return json.loads(ws.recv(timeout=10))[key]
            except ConnectionClosed as closed:
                assert closed.rcvd is not None
                return closed.rcvd.code


@pytest.fixture
def served(database: str, tmp_path: Path) -> Iterator[ServeProcess]:
    """A :class:`ServeProcess` in the test's folder, stopped after the test."""
    server = ServeProcess(database, tmp_path)
    yield server
    server.stop()


@pytest.fixture
def server_factory() -> Iterator[Callable[..., Server]]:
    started: list[Server] = []

    def make(database: str, port: int | None = None, extra: tuple[str, ...] = ()) -> Server:
        server = start_server(database, port, extra)
        started.append(server)
        return server

    yield make
    for server in started:
        server.stop()


@pytest.fixture(scope="session")
def headers() -> Callable[[str], dict[str, str]]:
    """``headers("alice")``: the Authorization header of an agent."""
    return auth


FLAGS = [
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--force-color-profile=srgb",
]
ARTIFACTS = Path(__file__).resolve().parents[2] / "test-artifacts"
SCREEN: ViewportSize = {"width": 1920, "height": 1080}
"""The workcell's monitor the page is designed for (the other size tested is a 1280 × 800 laptop)."""


@pytest.fixture(scope="session")
def browser() -> Iterator[Browser]:
    need_system("chromium", Path(CHROMIUM).exists())  # absent: an error as root (CI), else a skip saying why
    with sync_playwright() as playwright:
        launched = playwright.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
        yield launched
        launched.close()


@pytest.fixture
def board_server(tmp_path: Path, server_factory: Callable[..., Server]) -> Server:
    """A `supportive serve` of the chair (``Attach seat`` lead-only) on SQLite."""
    return server_factory(f"sqlite:///{tmp_path / 'board.db'}")


@pytest.fixture(scope="module")
def untouched_board(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    """A fresh board that the tests using it only look at (none claims, reports or stops it): one server
    for a test module's tests (on each worker that runs some), instead of one each."""
    server = start_server(f"sqlite:///{tmp_path_factory.mktemp('untouched') / 'board.db'}")
    yield server
    server.stop()


@pytest.fixture
def open_page(browser: Browser) -> Iterator[Callable[..., Page]]:
    """``open_page(url, token, viewport=None)``: the page signed in with the token given in its address (as
    ``serve`` prints it), once it is live; closed after the test."""
    pages: list[Page] = []

    def make(url: str, token: str, viewport: ViewportSize | None = None) -> Page:
        page = browser.new_page(viewport=viewport or SCREEN)
        pages.append(page)
        page.goto(f"{url}/#token={token}")
        expect(page.get_by_test_id("live")).to_have_text("live", timeout=15_000)
        return page

    yield make
    for page in pages:
        page.close()


@pytest.fixture(scope="session")
def snap() -> Callable[[Page, str], Image.Image]:
    """``snap(page, name)``: the viewport written to test-artifacts/NAME.png, and the picture."""

    def take(page: Page, name: str) -> Image.Image:
        ARTIFACTS.mkdir(exist_ok=True)
        data = page.screenshot(path=str(ARTIFACTS / f"{name}.png"))
        return Image.open(io.BytesIO(data)).convert("RGB")

    return take
