"""Shared circuit scenarios: small thesis-size tables, built once per session."""

from __future__ import annotations

from typing import Any

import pytest

from supportive.envs.circuits.scenario import CircuitScenario, thesis_scenario


@pytest.fixture(scope="session")
def thesis_table() -> tuple[CircuitScenario, Any]:
    """The thesis-size task scattered from seed 1, and its known plans Π_T."""
    scenario = thesis_scenario(1, environments=60)
    return scenario, scenario.plans()
