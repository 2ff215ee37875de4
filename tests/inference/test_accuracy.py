from __future__ import annotations

import numpy as np
import pytest

from supportive.generate import generate_task
from supportive.inference.accuracy import inference_accuracy
from supportive.inference.synthetic import synthetic_model, synthetic_stream
from supportive.tasks.htn import HTN


@pytest.mark.parametrize("profile", ["ikea", "uniform"])
def test_hierarchical_is_at_least_as_accurate_as_flat(profile: str) -> None:
    scores: dict[str, list[float]] = {"flat": [], "hierarchical": []}
    parents: dict[str, list[float]] = {"flat": [], "hierarchical": []}
    for seed in range(6):
        spec = generate_task(30, seed, profile=profile)
        assert spec.structure is not None
        model = synthetic_model(
            [a.id for a in spec.actions], overlap=0.8, spurious=1.0, strength=0.6, seed=seed
        )
        stream = synthetic_stream(spec.structure, model, executions=3, seed=seed)
        for name, accuracy in inference_accuracy(
            HTN("t", (spec.structure,)), model, stream.observations, stream.truth
        ).items():
            scores[name].append(accuracy.subgoal)
            parents[name].append(accuracy.subtask)
    assert np.mean(scores["hierarchical"]) >= np.mean(scores["flat"])
    assert np.mean(parents["hierarchical"]) >= np.mean(parents["flat"])
    assert np.mean(parents["hierarchical"]) > np.mean(scores["hierarchical"])  # the subtask is easier to tell


def test_clear_observations_are_read_almost_perfectly() -> None:
    spec = generate_task(20, 1)
    assert spec.structure is not None
    model = synthetic_model([a.id for a in spec.actions], overlap=0.0, spurious=0.1, strength=0.95, seed=1)
    stream = synthetic_stream(spec.structure, model, executions=2, seed=1)
    result = inference_accuracy(HTN("t", (spec.structure,)), model, stream.observations, stream.truth)
    assert result["hierarchical"].subgoal > 0.95 and result["hierarchical"].steps == len(stream.truth)
