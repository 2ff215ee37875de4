"""Shared fixtures: one seed for every RNG, printed so a failure can be replayed."""

from __future__ import annotations

import os
import random

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
