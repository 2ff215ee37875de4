from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import LearningError
from supportive.generate import Profile, random_structure
from supportive.inference import FlatHMM, HierarchicalHMM, ObservationModel
from supportive.inference.synthetic import synthetic_model, synthetic_stream
from supportive.inference.transitions import DENSE_BELOW, FlatTransitions, HierarchicalTransitions, TaskLayout
from supportive.learning import HTNLearner
from supportive.tasks.htn import HTN, ActionNode, ChainNode, CliqueNode

A, B, C, D = (ActionNode(x) for x in "abcd")


def _model(actions: str) -> ObservationModel:
    return ObservationModel({a: {f"see-{a}": 0.9} for a in actions}, noise=0.05)


def _arrivals(model: FlatHMM | HierarchicalHMM, leaf: int) -> np.ndarray:
    leaving = np.zeros(model.layout_.n_leaves)
    leaving[leaf] = 1.0
    return model.transitions_(leaving)


def test_hierarchical_moves_follow_the_tree() -> None:
    # chain[clique{a, b}, c]: after a, the clique goes on with b (1/2) or ends (1/2) and c starts
    htn = HTN("t", (ChainNode((CliqueNode((A, B)), C)),))
    hier = HierarchicalHMM(htn, _model("abc")).fit()
    assert _arrivals(hier, 0) == pytest.approx([0.0, 0.5, 0.5])
    assert _arrivals(hier, 2) == pytest.approx([0.5, 0.5, 0.0])  # the task ends and starts again
    flat = FlatHMM(htn, _model("abc")).fit()
    assert _arrivals(flat, 0) == pytest.approx([0.0, 0.5, 0.5])  # valid successors of a: b, c


def test_flat_and_hierarchical_differ_where_structure_matters() -> None:
    # chain[clique{a, b}, clique{c, d, e}]: flat spreads a's exit evenly over b, c, d, e
    e = ActionNode("e")
    htn = HTN("t", (ChainNode((CliqueNode((A, B)), CliqueNode((C, D, e)))),))
    assert _arrivals(FlatHMM(htn, _model("abcde")).fit(), 0) == pytest.approx([0, 0.25, 0.25, 0.25, 0.25])
    assert _arrivals(HierarchicalHMM(htn, _model("abcde")).fit(), 0) == pytest.approx([0, 0.5, 1 / 6, 1 / 6, 1 / 6])


@given(st.integers(5, 60), st.integers(0, 1000), st.sampled_from(["ikea", "uniform"]))
def test_transitions_conserve_mass_in_every_representation(n: int, seed: int, profile: Profile) -> None:
    htn = HTN("t", (random_structure(n, seed, profile=profile),))
    layout = TaskLayout.of(htn)
    moves = HierarchicalTransitions(htn, layout)
    rng = np.random.default_rng(seed)
    leaving = rng.random(layout.n_leaves)
    arriving = moves(leaving)
    assert arriving.sum() == pytest.approx(leaving.sum())
    assert (arriving >= 0).all()
    assert moves.start.sum() == pytest.approx(1.0)
    flat = FlatTransitions(htn, layout)
    assert flat(leaving).sum() == pytest.approx(leaving.sum())
    assert flat.start.sum() == pytest.approx(1.0)


def test_representations_agree() -> None:
    htn = HTN("t", (random_structure(3 * DENSE_BELOW, 4, profile="uniform"),))
    layout = TaskLayout.of(htn)
    moves = HierarchicalTransitions(htn, layout)
    leaving = np.random.default_rng(1).random(layout.n_leaves)
    down, across, up = moves.factors if len(moves.factors) == 3 else (None, None, None)
    assert down is not None, "a deep uniform task is routed through the tree"
    compiled = (down @ across @ up).toarray()
    assert moves(leaving) == pytest.approx(np.maximum(compiled @ leaving, 0))


def test_partial_hierarchy_uses_its_top_level() -> None:
    htn = HTNLearner(subtask_demonstrations=3).fit([list("abcd"), list("bdac")]).htn_  # orders only
    assert not htn.complete
    model = HierarchicalHMM(htn, _model("abcd")).fit()
    assert model.transitions_.start.sum() == pytest.approx(1.0)
    flat = FlatHMM(htn, _model("abcd")).fit()
    running = flat.filter()
    for step in "aaabbbcccddd":
        belief = running.update({f"see-{step}"})
    assert running.subgoal_labels[int(np.argmax(belief.subgoals))] == "d"


def test_filter_is_stable_over_ten_thousand_steps() -> None:
    structure = random_structure(40, 3)
    htn = HTN("t", (structure,))
    actions = [a for a, _ in htn.leaves]
    model = synthetic_model(actions, overlap=0.5, spurious=1.0, seed=3)
    stream = synthetic_stream(structure, model, executions=60, seed=3)
    assert len(stream.observations) > 10_000
    for cls in (FlatHMM, HierarchicalHMM):
        running = cls(htn, model).fit().filter()
        for observation in stream.observations:
            belief = running.update(observation)
        assert np.isfinite(running.log_likelihood) and running.log_likelihood < 0
        assert belief.subgoals.sum() == pytest.approx(1.0)
        assert np.isfinite(belief.subtasks).all() and belief.enclosing.sum() == pytest.approx(1.0)


def test_estimator_api() -> None:
    structure = ChainNode((A, CliqueNode((B, C)), D))
    htn = HTN("t", (structure,))
    truth_model = _model("abcd")
    rng = np.random.default_rng(0)
    sequences, labels = [], []
    for _ in range(20):
        stream = synthetic_stream(structure, truth_model, seed=rng)
        sequences.append(list(stream.observations))
        labels.append([a for a, _ in stream.truth])
    model = HierarchicalHMM(htn).fit(sequences, labels)
    assert model.mean_duration_ == pytest.approx(5.0, rel=0.3) and model.observations_ is not None
    probabilities = model.predict_proba(sequences[0])
    assert probabilities.shape == (len(sequences[0]), 4)
    assert np.allclose(probabilities.sum(axis=1), 1.0)
    predicted = [a for a, _ in model.predict(sequences[0])]
    assert np.mean([p == t for p, t in zip(predicted, labels[0], strict=True)]) > 0.9
    good = model.score(sequences[0])
    shuffled = list(reversed(sequences[0]))
    assert good > model.score(shuffled)  # a reversed task is less likely


def test_missing_observation_model_is_an_error() -> None:
    htn = HTN("t", (ChainNode((A, B)),))
    with pytest.raises(LearningError, match="no observation model"):
        HierarchicalHMM(htn).fit().filter()
    with pytest.raises(LearningError, match="no row for action"):
        HierarchicalHMM(htn, _model("a")).fit().filter()
    with pytest.raises(LearningError, match="mean_duration"):
        FlatHMM(htn, _model("ab"), mean_duration=0.5)


def test_next_subgoals_predict_the_chain() -> None:
    htn = HTN("t", (ChainNode((A, B, C)),))
    running = HierarchicalHMM(htn, _model("abc")).fit().filter()
    belief = running.update({"see-a"})
    assert running.top(belief.next_subgoals, running.subgoal_labels, 1)[0][0] == "b"
    assert list(itertools.islice(running.subtask_labels, 1)) == ["a → b → c"]
