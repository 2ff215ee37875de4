from __future__ import annotations

import numpy as np
import pytest

from supportive.generate import Profile, generate_task
from supportive.inference import FlatHMM, HierarchicalHMM
from supportive.inference.accuracy import filter_accuracy, first_share, inference_accuracy
from supportive.inference.synthetic import synthetic_model, synthetic_stream
from supportive.tasks.htn import HTN


@pytest.mark.parametrize("profile", ["ikea", "uniform"])
def test_hierarchical_is_at_least_as_accurate_as_flat(profile: Profile) -> None:
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


def test_ties_share_the_credit() -> None:
    assert first_share(np.array([0.5, 0.5 * (1 + 1e-15), 0.0]), 0) == 0.5
    assert first_share(np.array([0.5, 0.49, 0.01]), 0) == 1.0
    assert first_share(np.array([0.5, 0.49, 0.01]), 1) == 0.0
    assert first_share(np.full(4, 0.25), 3) == 0.25


def test_a_moment_without_events_scores_all_actions_alike() -> None:
    spec = generate_task(6, 2)
    assert spec.structure is not None
    htn = HTN("t", (spec.structure,))
    model = synthetic_model([a.id for a in spec.actions], overlap=0.0, spurious=0.1, strength=0.9, seed=2)
    for kind in (FlatHMM, HierarchicalHMM):
        hmm = kind(htn, model).fit()
        # no event at the first moment: the two subgoals that may start are exactly as likely, so whichever
        # is the truth gets half the credit (argmax would give all or nothing, by floating-point accident)
        first = hmm.filter().update(frozenset()).subgoals
        tied = np.flatnonzero(first >= first.max() * (1 - 1e-9))
        assert len(tied) == 2
        for i in tied:
            scored = filter_accuracy(hmm, [frozenset()], [hmm.layout_.leaves[i]])
            assert scored.subgoal == 0.5 and scored.steps == 1


def test_timed_accuracy_keeps_one_time_per_update() -> None:
    spec = generate_task(15, 3)
    assert spec.structure is not None
    model = synthetic_model([a.id for a in spec.actions], overlap=0.8, spurious=1.0, strength=0.6, seed=3)
    stream = synthetic_stream(spec.structure, model, executions=2, seed=3)
    htn = HTN("t", (spec.structure,))
    timed = inference_accuracy(htn, model, stream.observations, stream.truth, timed=True)
    plain = inference_accuracy(htn, model, stream.observations, stream.truth)
    for name in ("flat", "hierarchical"):
        assert len(timed[name].seconds) == timed[name].steps == len(stream.truth)
        assert all(s >= 0 for s in timed[name].seconds) and plain[name].seconds == ()
        assert (timed[name].subgoal, timed[name].subtask) == (plain[name].subgoal, plain[name].subtask)
    with pytest.raises(ValueError, match="non-empty"):
        filter_accuracy(FlatHMM(htn, model).fit(), [], [])
