"""Schemathesis against the running service (a `supportive serve` process on 127.0.0.1, SQLite): requests
generated from the OpenAPI schema, valid and invalid, as a lead, an assistant and an observer; every answer
must conform to the schema (status, content type, body) and none may be a 5xx. Bounded: 25 examples per
operation and role."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import schemathesis
from hypothesis import HealthCheck, given, settings
from schemathesis.core.result import Ok
from tests.service.conftest import Server, auth, start_server


@pytest.fixture(scope="module")
def running(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    directory: Path = tmp_path_factory.mktemp("schemathesis")
    server = start_server(f"sqlite:///{directory / 'board.db'}")
    yield server
    server.stop()


@pytest.mark.parametrize("agent", ["alice", "robot", "screen"])
def test_the_api_keeps_its_schema(running: Server, agent: str) -> None:
    """Every operation of the schema, as a lead, an assistant and an observer."""
    schema = schemathesis.openapi.from_url(f"{running.url}/openapi.json")
    results = list(schema.get_all_operations())
    assert all(isinstance(result, Ok) for result in results), results
    operations = [result.ok() for result in results if isinstance(result, Ok)]
    assert len(operations) >= 10
    for operation in operations:

        @given(case=operation.as_strategy())
        @settings(max_examples=25, deadline=None, suppress_health_check=list(HealthCheck), database=None)
        def keeps_schema(case: schemathesis.Case[Any]) -> None:
            case.call_and_validate(headers=auth(agent))

        keeps_schema()
