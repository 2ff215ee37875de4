"""The fuzz suite: malformed task files, maps, scenarios, observation streams (through the CLI, in process) and
API bodies (through the app) must get the promised answer.

CLI: exit 0, or exit 2 with one line ``supportive: error: FILE…`` on stderr and nothing on stdout, never a
traceback, and nothing written on an error. API: a 2xx, or a 4xx with a JSON ``detail``, and a refused request
leaves the board as it was. Each test draws at most 40 examples (``make test`` stays well under its budget)."""

from __future__ import annotations

import contextlib
import io
import os
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from supportive import examples
from supportive.cli import main

from . import strategies as fuzz

BOUNDED = settings(
    max_examples=int(os.environ.get("SUPPORTIVE_FUZZ_EXAMPLES", "40")),  # raise it to fuzz for longer
    deadline=None, suppress_health_check=list(HealthCheck), database=None)


def run_cli(args: list[str], stdin: str = "") -> tuple[int, str, str]:
    """``supportive ARGS`` in this process, reading ``stdin``: (exit status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    argv, given = sys.argv, sys.stdin
    sys.argv = ["supportive", *args]
    sys.stdin = io.StringIO(stdin)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                main()
                code = 0
            except SystemExit as exc:
                code = int(exc.code or 0)
    finally:
        sys.argv, sys.stdin = argv, given
    return code, out.getvalue(), err.getvalue()


@contextlib.contextmanager
def folder() -> Iterator[Path]:
    with tempfile.TemporaryDirectory(prefix="supportive-fuzz-") as name:
        yield Path(name)


def write(path: Path, text: str) -> Path:
    path.write_bytes(text.encode("utf-8", "surrogatepass"))  # a lone surrogate becomes bytes that are not UTF-8
    return path


def assert_promise(code: int, out: str, err: str, named: Path, *, written: Path | None = None) -> None:
    assert "Traceback" not in err, err
    assert code in (0, 2), (code, err)
    if code == 2:
        lines = err.strip().splitlines()
        assert len(lines) == 1, err
        assert lines[0].startswith(f"supportive: error: {named}"), err
        assert out == "", out
        if written is not None:
            assert not written.exists()


@given(fuzz.task_files())
@BOUNDED
def test_malformed_task_files_get_one_line_and_write_nothing(task: tuple[str, str]) -> None:
    suffix, text = task
    with folder() as where:
        path = write(where / f"task{suffix}", text)
        target = where / "htn.json"
        code, out, err = run_cli(["learn", str(path), "-f", "json", "-o", str(target)])
        assert_promise(code, out, err, path, written=target)
        if code == 0:
            assert target.read_text().startswith("{")


@given(fuzz.map_texts())
@BOUNDED
def test_malformed_maps_get_one_line(text: str) -> None:
    with folder() as where:
        path = write(where / "house.map", text)
        code, out, err = run_cli(["caregiver", "--map", str(path), "--steps", "3", "--every", "10"])
        assert_promise(code, out, err, path)


@given(fuzz.scenario_files())
@BOUNDED
def test_malformed_scenarios_get_one_line(scenario: tuple[str, str]) -> None:
    suffix, text = scenario
    with folder() as where:
        path = write(where / f"table{suffix}", text)
        code, out, err = run_cli(["support", str(path), "--environments", "2"])
        assert_promise(code, out, err, path)


@given(fuzz.observation_streams())
@BOUNDED
def test_malformed_observation_streams_get_one_line(stream: tuple[str, str]) -> None:
    suffix, text = stream
    with folder() as where:
        path = write(where / f"stream{suffix}", text)
        code, out, err = run_cli(["infer", str(examples.path("ikea-chair")), "-O", str(path)])
        assert_promise(code, out, err, path)


@pytest.fixture(scope="module")
def app_client(tmp_path_factory: pytest.TempPathFactory) -> Iterator[TestClient]:
    from tests.service.conftest import chair_settings

    from supportive.service.app import create_app

    database = f"sqlite:///{tmp_path_factory.mktemp('fuzz-api') / 'board.db'}"
    with TestClient(create_app(chair_settings(database))) as client:
        yield client


ENDPOINTS = ["/api/nodes/n5/progress", "/api/nodes/n1/claim", "/api/nodes/n3/complete", "/api/hands", "/api/observations"]


@given(
    endpoint=st.sampled_from(ENDPOINTS),
    agent=st.sampled_from(["alice", "robot", "screen", None]),
    body=fuzz.API_BODIES,
    raw=st.booleans(),
)
@BOUNDED
def test_malformed_api_bodies_get_a_4xx_json_error_and_change_nothing(
    app_client: TestClient, endpoint: str, agent: str | None, body: object, raw: bool
) -> None:
    from tests.service.conftest import auth

    headers = {"Content-Type": "application/json", **(auth(agent) if agent else {})}
    before = app_client.get("/api/board", headers=auth("screen")).json()
    content = repr(body).encode("utf-8", "surrogatepass") if raw else None
    if content is None:
        import json

        try:
            content = json.dumps(body).encode("utf-8", "surrogatepass")
        except (ValueError, OverflowError):
            content = b"{"
    response = app_client.post(endpoint, headers=headers, content=content)
    assert response.status_code < 500, response.text
    if response.status_code >= 400:
        assert response.headers["content-type"] == "application/json"
        assert "detail" in response.json()
        if endpoint.startswith("/api/nodes"):
            assert app_client.get("/api/board", headers=auth("screen")).json() == before
