"""Several agents' social force combined (by max)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import SocialError
from supportive.social import ForceField, SocialForce

POINTS = np.array([(0.2, 0.3), (0.22, 0.3), (1.2, 0.3), (0.7, 0.3)])


def two_people() -> ForceField:
    field = ForceField(min_radius=0.05)
    for i in range(10):
        field.update("alice", i / 30, (0.2, 0.3))
        field.update("bob", i / 30, (1.2, 0.3))
    return field


def test_the_field_is_the_strongest_agent_at_each_point() -> None:
    field = two_people()
    assert field.agents == ("alice", "bob")
    each = field.forces_at(POINTS)
    assert set(each) == {"alice", "bob"}
    assert each["alice"] == pytest.approx([1.0, 0.6, 0.0, 0.0])
    assert each["bob"] == pytest.approx([0.0, 0.0, 1.0, 0.0])
    assert field.field(POINTS) == pytest.approx([1.0, 0.6, 1.0, 0.0])
    assert field.field(POINTS, agents=["bob"]) == pytest.approx([0.0, 0.0, 1.0, 0.0])
    assert field.field(POINTS, agents=[]).tolist() == [0.0] * 4


def test_overlapping_agents_do_not_add_up() -> None:
    field = ForceField(min_radius=0.1)
    field.update("alice", 0.0, (0.0, 0.0))
    field.update("bob", 0.0, (0.1, 0.0))
    assert field.field([(0.05, 0.0)])[0] == pytest.approx(0.5)  # each reads 0.5 there: the max, not 1.0


def test_each_agent_keeps_its_own_window_and_the_clock_moves_them_all() -> None:
    field = two_people()
    field.update("alice", 1.1, (0.25, 0.3))
    assert len(field.force("alice")) == 1 and len(field.force("bob")) == 10
    field.advance(1.2)
    assert len(field.force("bob")) == 0
    assert field.field(POINTS)[2] == 0.0 and field.field([(0.25, 0.3)])[0] == pytest.approx(1.0)
    with pytest.raises(SocialError, match="before the latest"):
        field.advance(0.5)


def test_unknown_agents_and_bad_parameters() -> None:
    field = two_people()
    with pytest.raises(SocialError, match=r"no agent 'carol'.*alice, bob"):
        field.field(POINTS, agents=["carol"])
    with pytest.raises(SocialError, match="none yet"):
        ForceField().force("alice")
    with pytest.raises(SocialError, match="window must be a positive number"):
        ForceField(window=0.0)
    with pytest.raises(SocialError, match=r"\(n, 2\)"):
        field.forces_at([1.0, 2.0])


@given(st.lists(st.tuples(st.sampled_from("abc"), st.floats(-1, 1), st.floats(-1, 1)), min_size=1, max_size=30))
def test_combined_field_is_the_maximum_of_separate_forces(rows: list[tuple[str, float, float]]) -> None:
    field, separate = ForceField(), {name: SocialForce() for name, _, _ in rows}
    for i, (name, x, y) in enumerate(rows):
        field.update(name, i * 0.05, (x, y))
        separate[name].update(i * 0.05, (x, y))
    queries = np.array([(x, y) for _, x, y in rows] + [(0.0, 0.0)])
    expected = np.max([force.field(queries) for force in separate.values()], axis=0)
    assert field.field(queries) == pytest.approx(expected)
    assert np.all((field.field(queries) >= 0) & (field.field(queries) <= 1))
