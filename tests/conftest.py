"""Shared fixtures: one seed for every RNG, printed so a failure can be replayed."""

from __future__ import annotations

import glob
import os
import pickle
import random
import sys
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pytest
from filelock import FileLock
from hypothesis import HealthCheck, settings

if TYPE_CHECKING:
    from supportive.experiments.captaincook.recipes import RecipeReport

SEED = int(os.environ.get("SUPPORTIVE_TEST_SEED", "20261122"))

settings.register_profile(  # derandomized: the same examples on every run, so CI fails only for a change
    "supportive", deadline=None, max_examples=60, suppress_health_check=[HealthCheck.too_slow], derandomize=True
)
settings.register_profile("explore", settings.get_profile("supportive"), derandomize=False)  # new examples
settings.load_profile("supportive")


def _without_local_constants() -> None:
    """Hypothesis (recent versions) now and then draws a constant it found in the project's imported modules; which
    of them a run has imported depends on the tests collected, so the derandomized examples were not the same in
    every run (a subset of the suite drew a clean sample that the whole suite never did). Keep that set empty:
    derandomized then means the same examples in every run, whatever else is collected."""
    from hypothesis.internal.conjecture import providers

    if hasattr(providers, "_get_local_constants"):
        empty = providers._local_constants
        providers._get_local_constants = lambda: empty


_without_local_constants()


CHROMIUM = "/usr/bin/chromium"
"""Debian's chromium, which the browser tests drive (``make system`` installs it, as root)."""


def postgres_binaries() -> list[str]:
    """Debian's PostgreSQL ``initdb`` programs, newest last (``make system`` installs them, as root)."""
    return sorted(glob.glob("/usr/lib/postgresql/*/bin/initdb"))


def system_missing() -> list[str]:
    """The system programs some tests need that are not installed: chromium, PostgreSQL."""
    return [name for name, there in (("chromium", Path(CHROMIUM).exists()), ("PostgreSQL", bool(postgres_binaries()))) if not there]


def need_system(name: str, present: bool) -> None:
    """Go on when the system program ``name`` is installed. Without it, a root user (CI, and `make test`,
    which installs it with apt-get) gets an error — those tests must run there — and anyone else a skip that
    says why (apt-get needs root)."""
    if present:
        return
    if os.geteuid() == 0:
        raise RuntimeError(f"{name} is not installed: run `make test` (as root it installs it with apt-get)")
    pytest.skip(f"{name} is not installed, and installing it (make system: apt-get) needs root")


def pytest_report_header() -> list[str]:
    lines = [f"supportive test seed: {SEED} (set SUPPORTIVE_TEST_SEED to change)"]
    missing = system_missing()
    if missing and os.geteuid() != 0:
        lines.append(
            f"not root and {' and '.join(missing)} not installed: the browser and PostgreSQL tests that need "
            "them are skipped (as root, `make test` installs them)"
        )
    return lines


@pytest.fixture(autouse=True)
def _seed_everything() -> None:
    random.seed(SEED)
    np.random.seed(SEED % 2**32)


@pytest.fixture
def rng() -> np.random.Generator:
    """A seeded generator for a test."""
    return np.random.default_rng(SEED)


@pytest.fixture(scope="session")
def captaincook_reports(tmp_path_factory: pytest.TempPathFactory, worker_id: str) -> list[RecipeReport]:
    """The CaptainCook4D report of every recipe (the dataset beside the repository), for the tests that check
    it, print it and compare it with its record: computed once per test run, the xdist workers sharing it
    through a file in the run's temporary directory (the first to ask computes it, under a lock)."""
    from supportive.experiments.captaincook.recipes import captaincook_report
    from supportive.io.captaincook import load_captaincook

    if worker_id == "master":  # not under xdist
        return captaincook_report(load_captaincook())
    shared = tmp_path_factory.getbasetemp().parent / "captaincook-reports.pickle"
    with FileLock(f"{shared}.lock"):
        if shared.is_file():
            reports: list[RecipeReport] = pickle.loads(shared.read_bytes())
            return reports
        reports = captaincook_report(load_captaincook())
        shared.write_bytes(pickle.dumps(reports))
        return reports


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
