from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.io import parse_task_file
from supportive.language.demonstrated import _cross_validated, learn_region
from supportive.language.dnf import TruthTable
from supportive.language.states import TaskStates

CHAIR = Path(__file__).parents[2] / "examples" / "ikea-chair.yaml"


def test_cross_validation_picks_the_likeliest_bandwidth() -> None:
    # two samples one apart in 3 dimensions: the leave-one-out likelihood peaks at h = 1/sqrt(3)
    samples = np.array([[1.0, 1.0, 0.0], [0.0, 1.0, 0.0]])
    assert _cross_validated(samples, [0.3, 0.58, 1.0, 2.0]) == 0.58
    assert _cross_validated(samples[:1], [0.3, 1.0, 2.0]) == 1.0


def test_chair_screw_states_generalise_but_not_across_a_hazard() -> None:
    states = TaskStates.of(parse_task_file(CHAIR))
    table = states.table
    screws = sorted(states.during("Screw seat"), key=len)
    shown = [screws[0]]  # seat placed, no screw yet
    region = learn_region(table, shown, level=0.05)
    assert set(shown) <= region.states and len(region.states) > 1
    hazard = next(s for s in region.states if s not in shown)
    safer = learn_region(table, shown, level=0.05, hazardous=[hazard])
    assert hazard not in safer.states and hazard in safer.excluded
    assert safer.states < region.states


@given(st.integers(1, 6), st.floats(0.01, 2.0), st.integers(0, 2**16))
def test_region_invariants(marked_count: int, level: float, seed: int) -> None:
    rng = np.random.default_rng(seed)
    values = rng.random((12, 4)) < 0.5
    names = [f"s{i}" for i in range(12)]
    table = TruthTable(names, ["p", "q", "r", "t"], values)
    picks = list(rng.choice(12, size=marked_count + 2, replace=False))
    marked = [names[i] for i in picks[:marked_count]]
    hazard = [names[i] for i in picks[marked_count:]]
    region = learn_region(table, marked, hazardous=hazard, level=level)
    assert set(marked) <= region.states
    assert not set(hazard) & region.states
    if level <= 1.0:
        assert learn_region(table, marked, level=level * 0.5).states >= learn_region(table, marked, level=level).states


def test_bad_input() -> None:
    table = TruthTable.from_sets(["a", "b"], {"p": {"a"}})
    with pytest.raises(ValueError, match="mark at least one"):
        learn_region(table, [])
    with pytest.raises(ValueError, match="both marked and hazardous"):
        learn_region(table, ["a"], hazardous=["a"])
    with pytest.raises(ValueError, match="> 0"):
        learn_region(table, ["a"], bandwidths=[0.0])
    with pytest.raises(KeyError):
        learn_region(table, ["z"])
