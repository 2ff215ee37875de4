"""People with habits (generate/habits.py): valid executions, a shared habit, and the steps a task allows next
against listing its executions."""

from __future__ import annotations

import itertools
from collections import Counter

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from supportive.errors import GenerationError
from supportive.generate.habits import HABIT_STRENGTHS, HabitualPeople, executions_by
from supportive.generate.mistakes import PROFILES, KnownTask, random_known_task


def _valid(task: KnownTask) -> list[tuple[str, ...]]:
    steps = task.sample(0)
    return sorted({p for p in itertools.permutations(steps) if task.admits(p)})


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 10_000), profile=st.sampled_from(PROFILES), steps=st.integers(3, 6))
def test_the_steps_allowed_next_are_those_some_valid_execution_does_next(seed: int, profile: str, steps: int) -> None:
    task = random_known_task(profile, steps, seed)  # type: ignore[arg-type]
    valid = _valid(task)
    for execution in valid:
        for k in range(len(execution) + 1):
            prefix = execution[:k]
            expected = sorted({v[k] for v in valid if v[:k] == prefix and k < len(v)})
            assert task.allowed_next(prefix) == expected


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 10_000), profile=st.sampled_from(PROFILES), strength=st.sampled_from([0.0, 1.0, 4.0]))
def test_habitual_people_only_do_valid_executions_and_a_seed_fixes_them(seed: int, profile: str, strength: float) -> None:
    task = random_known_task(profile, 7, seed)  # type: ignore[arg-type]
    people = HabitualPeople.of(task, strength, seed)
    demos = [people.demonstration(s) for s in range(10)]
    assert all(task.admits(d) for d in demos)
    assert demos == [people.demonstration(s) for s in range(10)]
    assert people == HabitualPeople.of(task, strength, seed)


def test_strong_habits_make_the_preferred_order_common_and_none_makes_every_order_possible() -> None:
    task = random_known_task("partial order", 6, seed=3)
    valid = _valid(task)
    rng = np.random.default_rng(0)
    strong = HabitualPeople.of(task, 8.0, 1, person_noise=0.0)
    assert all(strong.demonstration(rng) == list(strong.preferred) for _ in range(20))
    loose = Counter(tuple(HabitualPeople.of(task, 0.0, 1).demonstration(rng)) for _ in range(40 * len(valid)))
    assert set(loose) == set(valid)
    habitual = Counter(tuple(HabitualPeople.of(task, 2.0, 1).demonstration(rng)) for _ in range(400))
    assert habitual.most_common(1)[0][0] == HabitualPeople.of(task, 2.0, 1).preferred
    assert len(habitual) > 1  # people differ from one another, not only from the habit


def test_a_bad_population_is_refused() -> None:
    task = random_known_task("ikea", 5, seed=2)
    with pytest.raises(GenerationError, match="strength"):
        HabitualPeople.of(task, -1.0, 0)
    with pytest.raises(GenerationError, match="not a valid execution"):
        HabitualPeople(task, tuple(reversed(task.sample(0))), 1.0)


def test_executions_by_people_draw_as_the_settings_experiments_did_before_it_was_shared() -> None:
    # uniform people are the task's own uniform draw; people with habits take a strength from the generator,
    # then their preferred order from it (the learner-settings trials' recorded order of draws)
    task = random_known_task("partial order", 7, 3)
    rng, expected = np.random.default_rng(5), np.random.default_rng(5)
    assert executions_by(task, "uniform", rng)(rng) == task.sample(expected)
    draw = executions_by(task, "habits", rng)
    people = HabitualPeople.of(task, float(expected.choice(HABIT_STRENGTHS)), expected)
    assert [draw(rng) for _ in range(5)] == [people.demonstration(expected) for _ in range(5)]
    assert all(task.admits(draw(seed)) for seed in range(20))
    with pytest.raises(GenerationError, match="people must be one of uniform, habits, got 'experts'"):
        executions_by(task, "experts")
