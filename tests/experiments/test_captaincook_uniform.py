"""``supportive captaincook --uniform``: recordings drawn uniformly from each recipe's published graph."""

from __future__ import annotations

import itertools

import pytest

from supportive.errors import DatasetError, InvalidValueError
from supportive.experiments.captaincook import uniform
from supportive.experiments.captaincook.uniform import kept_free_pairs, published_order, uniform_draws
from supportive.io.captaincook import Recipe, load_recipe
from supportive.learning.linear_extensions import count_linear_extensions
from supportive.tasks.htn import to_leaves
from supportive.tasks.spec import Action, Demonstration, TaskSpec

SUBSET = ("zoodles", "coffee", "pinwheels")  # pinwheels repeats a step: its occurrences are steps of their own


@pytest.fixture(scope="module")
def subset() -> list[Recipe]:
    return [load_recipe(name) for name in SUBSET]


def test_the_published_order_admits_what_the_published_graph_admits(subset: list[Recipe]) -> None:
    for recipe in subset:
        order, leaves = published_order(recipe)
        steps = sorted(recipe.steps)
        index = {leaf: i for i, leaf in enumerate(steps)}
        pairs = [(index[a], index[b]) for a, b in recipe.published if a in index and b in index]
        assert set(leaves.values()) == set(steps)
        assert order.count_executions() == count_linear_extensions(len(steps), pairs)  # an independent count
        draw = order.counting_sampler()
        for seed in range(10):
            execution = to_leaves([leaves[step][0] for step in draw(seed)])
            position = {leaf: i for i, leaf in enumerate(execution)}
            assert set(position) == set(steps)
            assert all(position[a] < position[b] for a, b in recipe.published), recipe.name


def test_the_same_seed_gives_the_same_figures(subset: list[Recipe]) -> None:
    strict = {"mode": "strict"}
    first = uniform_draws(subset, 2, seed=3, learner_options=strict)
    assert first == uniform_draws(subset, 2, seed=3, learner_options=strict)
    assert first.full["n"] == first.few_shot["n"] == len(subset)
    assert 0.0 < first.few_shot["mean"] <= 1.0 and 0.0 < first.full["mean"] <= 1.0
    assert first.as_dict()["5-shot"] == first.few_shot


def test_as_many_recordings_as_the_recipe_has_are_drawn_again_for_another_seed(
    subset: list[Recipe], monkeypatch: pytest.MonkeyPatch
) -> None:
    from supportive.learning.learner import learn as real_learn

    learned: list[tuple[tuple[str, ...], ...]] = []

    def recording_learn(spec, **options):  # type: ignore[no-untyped-def]
        learned.append(tuple(demo.actions for demo in spec.demonstrations))
        return real_learn(spec, **options)

    monkeypatch.setattr(uniform, "learn", recording_learn)
    for seed in (0, 0, 1):
        uniform_draws(subset[:1], 1, seed=seed, learner_options={"mode": "strict"})
    recordings = len(subset[0].spec.demonstrations)
    assert [len(sequences) for sequences in learned] == [recordings, min(recordings, 5)] * 3
    assert learned[0] == learned[2] != learned[4]  # the same seed, the same draws; another, others
    assert learned[1] == learned[0][:5]


def test_bad_requests_are_refused(subset: list[Recipe]) -> None:
    with pytest.raises(InvalidValueError, match="draws must be 1 or more"):
        uniform_draws(subset, 0)
    with pytest.raises(DatasetError, match="no CaptainCook4D recipe"):
        uniform_draws([], 1)


def tiny_recipe(orders: list[str], published: set[tuple[str, str]]) -> Recipe:
    """Steps a, b, c (one letter each), the recordings ``orders``, the published graph's closure ``published``."""
    actions = tuple(Action(step, step) for step in "abc")
    spec = TaskSpec("tiny", actions, None, tuple(Demonstration.of(list(order), id=f"r{k}") for k, order in enumerate(orders)))
    pairs = frozenset(((a, 1), (b, 1)) for a, b in published)
    ends = {("START", (step, 1)) for step in "abc"} | {((step, 1), "END") for step in "abc"}
    return Recipe("tiny", "Tiny", spec, pairs, frozenset(ends | set(pairs)))


def brute_expected(recipe: Recipe) -> float:
    """The expected kept free pairs by listing every order of the steps (the oracle)."""
    steps = sorted(recipe.steps)
    valid = [p for p in itertools.permutations(steps) if all(p.index(a) < p.index(b) for a, b in recipe.published)]
    m = len(recipe.spec.demonstrations)
    total = 0.0
    for x, y in itertools.combinations(steps, 2):
        if (x, y) in recipe.published or (y, x) in recipe.published:
            continue
        q = sum(p.index(x) < p.index(y) for p in valid) / len(valid)
        total += q**m + (1 - q) ** m
    return total


@pytest.mark.parametrize(
    ("orders", "kept"),
    [(["abc", "cab", "acb"], 0), (["abc", "acb", "abc"], 1), (["abc", "abc"], 2)],
)
def test_kept_free_pairs_against_listing_every_order(orders: list[str], kept: int) -> None:
    recipe = tiny_recipe(orders, {("a", "b")})
    found = kept_free_pairs([recipe])
    assert (found.free, found.kept) == (2, kept)
    assert found.expected == pytest.approx(brute_expected(recipe))
