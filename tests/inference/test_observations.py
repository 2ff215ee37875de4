from __future__ import annotations

import numpy as np
import pytest

from supportive import examples
from supportive.errors import LearningError
from supportive.inference import ObservationModel
from supportive.tasks.spec import Action, TaskSpec


def test_log_likelihood_is_naive_bayes() -> None:
    model = ObservationModel({"a": {"x": 0.9, "y": 0.3}, "b": {"y": 0.8}}, noise=0.05)
    got = model.log_likelihood({"y"})
    assert got[0] == pytest.approx(np.log(0.1) + np.log(0.3))
    assert got[1] == pytest.approx(np.log(0.95) + np.log(0.8))
    assert model.log_likelihood({"y", "unknown-event"}) == pytest.approx(got)


def test_fit_recovers_frequencies() -> None:
    rng = np.random.default_rng(0)
    truth = ObservationModel({"a": {"x": 0.8, "y": 0.2}, "b": {"y": 0.7}}, noise=0.05)
    labels = [["a"] * 500 + ["b"] * 500]
    sequences = [[truth.sample(a, rng) for a in labels[0]]]
    fitted = ObservationModel.from_labelled(sequences, labels, noise=0.05)
    assert fitted.table[fitted.action_index["a"], fitted.event_index["x"]] == pytest.approx(0.8, abs=0.05)
    assert fitted.table[fitted.action_index["b"], fitted.event_index["y"]] == pytest.approx(0.7, abs=0.05)
    assert fitted.table[fitted.action_index["b"], fitted.event_index["x"]] == pytest.approx(0.05, abs=0.02)


def test_from_spec_needs_observations() -> None:
    model = ObservationModel.from_spec(examples.load("ikea-chair"))
    assert "hand-peg" in model.events and len(model.actions) == 24
    with pytest.raises(LearningError, match="without 'observations'"):
        ObservationModel.from_spec(TaskSpec("t", (Action("a"),)))


def test_bad_parameters() -> None:
    with pytest.raises(LearningError, match="noise"):
        ObservationModel({"a": {"x": 0.5}}, noise=0.7)
    with pytest.raises(LearningError, match="probability"):
        ObservationModel({"a": {"x": 1.0}})
    with pytest.raises(LearningError, match="labels"):
        ObservationModel.from_labelled([[{"x"}]], [["a", "b"]])


def test_sampling_is_seeded() -> None:
    model = ObservationModel.from_spec(examples.load("ikea-chair"))
    assert [model.sample("place_seat", s) for s in range(5)] == [
        model.sample("place_seat", s) for s in range(5)
    ]
