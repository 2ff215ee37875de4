"""Shared fixtures: one seed for every RNG, printed so a failure can be replayed."""

from __future__ import annotations

import os
import random
import sys
from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import HealthCheck, settings

SEED = int(os.environ.get("SUPPORTIVE_TEST_SEED", "20261122"))

settings.register_profile(
    "supportive", deadline=None, max_examples=60, suppress_health_check=[HealthCheck.too_slow]
)
settings.load_profile("supportive")


def pytest_report_header() -> str:
    return f"supportive test seed: {SEED} (set SUPPORTIVE_TEST_SEED to change)"


@pytest.fixture(autouse=True)
def _seed_everything() -> None:
    random.seed(SEED)
    np.random.seed(SEED % 2**32)


@pytest.fixture
def rng() -> np.random.Generator:
    """A seeded generator for a test."""
    return np.random.default_rng(SEED)


CliRunner = Callable[[list[str]], tuple[int, str, str]]


@pytest.fixture
def cli(capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> CliRunner:
    """Run ``supportive ARGS`` in process: returns (exit status, stdout, stderr). The terminal is 200 columns
    wide, so a sentence stays on one line (wrapping to the terminal is tested on its own, test_cli_output.py)."""
    from supportive.cli import main

    def run(args: list[str]) -> tuple[int, str, str]:
        monkeypatch.setattr(sys, "argv", ["supportive", *args])
        monkeypatch.setenv("COLUMNS", "200")
        try:
            main()
            code = 0
        except SystemExit as exc:
            code = int(exc.code or 0)
        captured = capsys.readouterr()
        return code, captured.out, captured.err

    return run
