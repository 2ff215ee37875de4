"""The generalisation experiment's slip check: generated tasks of sizes the slip settings were not chosen on,
with mistakes put in, learned by the default learner; its trials, its scoring and its summary."""

from __future__ import annotations

import itertools
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from supportive.experiments import get
from supportive.experiments.generalisation.measure import (
    SLIP_CASES,
    SLIP_SIZES,
    SLIP_TASKS,
    make_trials,
    run_trial,
    summarize,
)
from supportive.experiments.generalisation.report import slip_check
from supportive.experiments.learner_settings import measure as slip_settings
from supportive.generate.habits import PEOPLE
from supportive.generate.mistakes import KINDS, PROFILES


def test_a_full_run_checks_every_size_number_and_case_by_every_profile_and_kind_of_people() -> None:
    trials = [t for t in make_trials(get("generalisation").default_trials, 0) if t.params["kind"] == "slip check"]
    cells = [
        (tuple(t.params["sizes"]), t.params["demonstrations"], t.params["case"], t.params["profile"], t.params["people"])
        for t in trials
    ]
    every = set(itertools.product(SLIP_SIZES, slip_settings.DEMONSTRATIONS, SLIP_CASES, PROFILES, PEOPLE))
    assert set(cells) == every
    assert len(cells) == len(every) * SLIP_TASKS // (len(PROFILES) * len(PEOPLE))  # as many of each
    assert not any(low <= slip_settings.SIZES[1] and slip_settings.SIZES[0] <= high for low, high in SLIP_SIZES)


@pytest.mark.parametrize("trials", [3, 4, 10])
def test_a_small_run_holds_a_trial_of_each_kind(trials: int) -> None:
    kinds = [t.params["kind"] for t in make_trials(trials, 0)]
    assert len(kinds) == trials and set(kinds) == {"synthetic", "recipe", "slip check"}


def test_a_trial_draws_a_task_of_its_size_and_scores_the_default_learners_slips() -> None:
    trials = make_trials(get("generalisation").default_trials, 0)
    moved = next(
        t for t in trials if t.params["kind"] == "slip check" and t.params["case"] == "moved" and t.params["sizes"][0] > 12
    )
    demos, truth, _ = slip_settings.trial_demonstrations(moved)
    low, high = moved.params["sizes"]
    assert len(demos) == moved.params["demonstrations"] and truth
    assert all(low <= len(set(d)) <= high for d in demos)  # a moved step changes no step's count
    result = run_trial(moved)
    counts = result["settings"]["default"]
    assert result["mistakes"] == len(truth) and counts["right"] <= counts["reported"]
    assert counts["found"] <= result["mistakes"]
    clean = next(t for t in trials if t.params["kind"] == "slip check" and t.params["case"] == "none")
    clean_demos, none, _ = slip_settings.trial_demonstrations(clean)
    assert len(clean_demos) == clean.params["demonstrations"] and not none


def _task(
    size: tuple[int, int], case: str, people: str, n: int, counts: tuple[int, int, int], mistakes: int, steps: int
) -> dict[str, Any]:
    reported, right, found = counts if case != "none" else (counts[0], 0, 0)  # on clean data every slip is wrong
    return {
        "kind": "slip check", "sizes": list(size), "case": case, "demonstrations": n, "people": people,
        "profile": "ikea", "steps": steps, "mistakes": mistakes if case != "none" else 0,
        "settings": {"default": {"reported": reported, "right": right, "found": found, "wrong_tasks": int(reported > right)}},
    }


COUNTS = st.integers(0, 6).flatmap(lambda r: st.tuples(st.just(r), st.integers(0, r))).flatmap(
    lambda rr: st.tuples(st.just(rr[0]), st.just(rr[1]), st.integers(0, rr[1]))
)
TASK = st.tuples(
    st.sampled_from(SLIP_SIZES),
    st.sampled_from(SLIP_CASES),
    st.sampled_from(PEOPLE),
    st.sampled_from(slip_settings.DEMONSTRATIONS),
    COUNTS,
    st.integers(0, 5),
    st.integers(10, 400),
)


def _scores(cell: list[dict[str, Any]]) -> tuple[float, float, int]:
    """Precision, recall and mistakes of ``cell``'s tasks pooled, counted here directly."""
    reported, right, found = (sum(t["settings"]["default"][k] for t in cell) for k in ("reported", "right", "found"))
    mistakes = sum(t["mistakes"] for t in cell)
    return (right / reported if reported else 1.0), (found / mistakes if mistakes else 1.0), mistakes


@settings(max_examples=60, deadline=None)
@given(st.lists(TASK, min_size=1, max_size=24))
def test_the_summary_pools_each_size_and_kind_of_peoples_counts(drawn: list[Any]) -> None:
    tasks = [_task(*task) for task in drawn]
    summary = summarize(tasks)["slip_sizes"]
    assert [tuple(size["steps"]) for size in summary] == sorted({tuple(t["sizes"]) for t in tasks})
    worst: dict[str, list[tuple[float, float, float]]] = {}
    for size in summary:
        assert list(size["people"]) == [p for p in PEOPLE if any(t["people"] == p and t["sizes"] == size["steps"] for t in tasks)]
        for people, row in size["people"].items():
            mine = [t for t in tasks if t["sizes"] == size["steps"] and t["people"] == people]
            cells = []
            for kind in KINDS:
                precision, recall, mistakes = _scores([t for t in mine if t["case"] == kind])
                assert row["kinds"][kind] == {
                    "precision": pytest.approx(precision, abs=1e-4), "recall": pytest.approx(recall, abs=1e-4),
                    "mistakes": mistakes, "tasks": sum(t["case"] == kind for t in mine),
                }
                for n in slip_settings.DEMONSTRATIONS:
                    p, r, m = _scores([t for t in mine if t["case"] == kind and t["demonstrations"] == n])
                    if m:
                        cells.append((p, r))
            clean = [t for t in mine if t["case"] == "none"]
            steps = sum(t["steps"] for t in clean)
            flagged = sum(t["settings"]["default"]["reported"] for t in clean) / steps if steps else 0.0
            assert row["clean_flagged"] == pytest.approx(flagged, abs=1e-6)
            assert row["clean_tasks_flagged"] == sum(t["settings"]["default"]["reported"] > 0 for t in clean)
            worst.setdefault(people, []).append(
                (min((p for p, _ in cells), default=1.0), min((r for _, r in cells), default=1.0), flagged)
            )
    expected = {people: (min(w[0] for w in rows), min(w[1] for w in rows), max(w[2] for w in rows)) for people, rows in worst.items()}
    checked = slip_check(summary)
    assert list(checked) == sorted(expected)
    for people, values in expected.items():
        assert checked[people] == pytest.approx(values, abs=1e-4)


def test_the_finding_judges_the_uniform_people_by_issue_23s_bar_and_says_when_there_are_none() -> None:
    from supportive.experiments.generalisation.report import findings

    def finding(tasks: list[dict[str, Any]]) -> Any:
        metrics = {**summarize(tasks), "captaincook": {}, "synthetic": {}}
        return findings(metrics)[-1]

    good = [_task((3, 5), "moved", "uniform", 20, (2, 2, 2), 2, 40), _task((3, 5), "moved", "habits", 20, (4, 2, 2), 2, 40)]
    assert finding(good).verdict.startswith("meets")  # the people with habits are shown, not judged
    assert [people for people, _ in finding(good).values] == ["uniform", "habits"]  # the judged one first
    assert dict(finding(good).values)["habits"].startswith("0.50 / 1.00")
    missed = [_task((3, 5), "moved", "uniform", 20, (1, 1, 1), 2, 40)]
    assert finding(missed).verdict.startswith("below")
    assert finding(good[1:]).verdict == "no task drawn uniformly in this run"
