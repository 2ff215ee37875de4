"""The CaptainCook4D learning-curve experiment: registration, a small deterministic run, the instructor."""

from __future__ import annotations

import dataclasses
import functools
from pathlib import Path

import numpy as np
import pytest

from supportive.experiments import get, names, run_experiment
from supportive.experiments.captaincook.measure import (
    CONDITIONS,
    make_trials,
    partial_order,
    run_trial,
    summarize,
)
from supportive.experiments.captaincook.recipes import compare_recipe
from supportive.experiments.registry import register, unregister
from supportive.io.captaincook import load_captaincook, load_recipe
from supportive.learning.instructors import SimulatedInstructor, demonstrate
from supportive.tasks.htn import to_leaves

SUBSET = ("zoodles", "panfriedtofu", "coffee")


def test_registered() -> None:
    assert "captaincook" in names()
    assert get("captaincook").default_trials >= 1


@pytest.fixture(scope="module")
def small_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    experiment = dataclasses.replace(
        get("captaincook"),
        name="captaincook-subset",
        make_trials=functools.partial(make_trials, recipes=SUBSET),
    )
    register(experiment)
    try:
        outs = []
        for label in ("a", "b"):
            out = tmp_path_factory.mktemp(label)
            run_experiment("captaincook-subset", trials=1, seed=3, output=out, progress=False)
            outs.append(out)
    finally:
        unregister("captaincook-subset")
    return outs[0], outs[1]


def test_small_run_is_deterministic(small_run: tuple[Path, Path]) -> None:
    a, b = small_run
    assert (a / "metrics.json").read_bytes() == (b / "metrics.json").read_bytes()
    assert (a / "report.md").read_text() == (b / "report.md").read_text()
    assert (a / "curves.png").exists()
    report = (a / "report.md").read_text()
    assert "no numbers" in report or "no CaptainCook4D" in report


def test_small_run_curves() -> None:
    results = [run_trial(t) for t in make_trials(1, 3, recipes=SUBSET)]
    metrics = summarize(results)
    assert metrics["recipes_run"] == 3
    assert metrics["active_demonstrations_valid"]
    for row in metrics["curves"].values():
        for cond in CONDITIONS:
            for cell in row[cond].values():
                assert 0.0 <= cell["mean"] <= 1.0
    # A recipe's result does not depend on which other recipes the trial runs.
    alone = run_trial(make_trials(1, 3, recipes=("zoodles",))[0])["recipes"][0]
    assert alone == next(r for r in results[0]["recipes"] if r["recipe"] == "zoodles")


def test_passive_recall_at_last_k_matches_learning_on_all_recordings() -> None:
    result = run_trial(make_trials(1, 5, recipes=SUBSET)[0])
    for entry in result["recipes"]:
        full = compare_recipe(load_recipe(entry["recipe"]), {"mode": "strict"}).score  # the curves' learner
        curve = entry["curves"]["passive"]
        assert len(curve["recall"]) == entry["demonstrations"]
        assert curve["recall"][-1] == pytest.approx(full.recall)
        assert curve["precision"][-1] == pytest.approx(full.precision)


def test_partial_order_instructor_respects_published_order() -> None:
    rng = np.random.default_rng(0)
    for recipe in load_captaincook():
        order = partial_order(recipe)
        for demo in recipe.spec.demonstrations[:3]:
            path = order.linearize(demo.actions)
            assert order.admits(to_leaves(path))
            person = SimulatedInstructor(order, path, perturbation=0.0)
            assert tuple(demonstrate(person)) == path
            # Answer random queries: every demonstration still follows the published order.
            person.begin_demonstration()
            done: list[str] = []
            actions = [a.id for a in recipe.spec.actions]
            while (step := person.next_action(tuple(done), str(rng.choice(actions)))) is not None:
                done.append(step)
            leaves = to_leaves(done)
            assert order.admits(leaves)
            position = {leaf: i for i, leaf in enumerate(leaves)}
            assert all(position[a] < position[b] for a, b in recipe.published)
