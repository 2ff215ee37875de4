"""Implied precedences of CC-HTNs (against brute force) and the CaptainCook4D comparison."""

from __future__ import annotations

import itertools
from collections.abc import Iterator, Sequence

import numpy as np
import pytest

from supportive.experiments.captaincook.recipes import RecipeReport, compare_recipe
from supportive.io.captaincook import Recipe, load_captaincook
from supportive.learning.general.top_order import seen_top_level
from supportive.learning.learner import learn
from supportive.learning.precedence import implied_precedences, precedence_scores
from supportive.tasks.htn import (
    HTN,
    ActionNode,
    ChainNode,
    CliqueNode,
    Leaf,
    Node,
    TopLevel,
    iter_orderings,
    to_leaves,
)

Pair = tuple[Leaf, Leaf]


def A(name: str, occurrence: int = 1) -> ActionNode:
    return ActionNode(name, occurrence)


def _top_level_paths(top: TopLevel) -> Iterator[tuple[int, ...]]:
    out = top.successors()
    terminal = set(top.terminal)

    def walk(state: int, prefix: tuple[int, ...]) -> Iterator[tuple[int, ...]]:
        if state in terminal:
            yield prefix
        for root, dst in out.get(state, {}).items():
            yield from walk(dst, (*prefix, root))

    for state in top.initial:
        yield from walk(state, ())


def _executions(htn: HTN) -> Iterator[tuple[Leaf, ...]]:
    if htn.top_level is None:
        yield from iter_orderings(htn.roots[0])
        return
    for path in _top_level_paths(htn.top_level):
        for parts in itertools.product(*(list(iter_orderings(htn.roots[r])) for r in path)):
            yield tuple(leaf for part in parts for leaf in part)


def _brute_force(htn: HTN) -> frozenset[Pair]:
    common: set[Pair] | None = None
    for execution in _executions(htn):
        pairs = {(a, b) for i, a in enumerate(execution) for b in execution[i + 1 :]}
        common = pairs if common is None else common & pairs
    assert common is not None, "the HTN admits no execution"
    return frozenset(common)


def _check(htn: HTN) -> frozenset[Pair]:
    found = implied_precedences(htn)
    assert found == _brute_force(htn)
    return found


# ------------------------------------------------------------------------------------------ hand-built


def test_chain() -> None:
    found = _check(HTN("t", (ChainNode((A("a"), A("b"), A("c"))),)))
    assert found == {(("a", 1), ("b", 1)), (("a", 1), ("c", 1)), (("b", 1), ("c", 1))}


def test_clique() -> None:
    assert _check(HTN("t", (CliqueNode((A("a"), A("b"), A("c"))),))) == frozenset()


def test_nested() -> None:
    tree = ChainNode(
        (
            A("knife"),
            CliqueNode((ChainNode((A("wash"), A("carrot"))), A("celery"))),
            A("serve"),
        )
    )
    found = _check(HTN("t", (tree,)))
    assert (("wash", 1), ("carrot", 1)) in found
    assert (("wash", 1), ("celery", 1)) not in found and (("celery", 1), ("carrot", 1)) not in found
    assert (("knife", 1), ("celery", 1)) in found and (("carrot", 1), ("serve", 1)) in found


def test_repeated_action_occurrences() -> None:
    tree = ChainNode((A("stir"), CliqueNode((A("boil"), ChainNode((A("stir", 2), A("taste")))))))
    found = _check(HTN("t", (tree,)))
    assert (("stir", 1), ("stir", 2)) in found


def test_partial_with_top_level() -> None:
    # Roots: 0 = chain(a, b), 1 = c, 2 = clique(d, e). Paths: 0 1 2 and 0 2 1.
    roots: tuple[Node, ...] = (ChainNode((A("a"), A("b"))), A("c"), CliqueNode((A("d"), A("e"))))
    top = TopLevel(initial=(0,), terminal=(4,), edges=((0, 0, 1), (1, 1, 2), (2, 2, 4), (1, 2, 3), (3, 1, 4)))
    found = _check(HTN("t", roots, top))
    assert (("a", 1), ("c", 1)) in found and (("b", 1), ("e", 1)) in found
    assert (("c", 1), ("d", 1)) not in found and (("d", 1), ("c", 1)) not in found


def test_partial_ignores_dead_ends() -> None:
    # Performing root 1 first leads to state 1, from which the task cannot finish.
    roots: tuple[Node, ...] = (A("a"), A("b"))
    top = TopLevel(initial=(0,), terminal=(3,), edges=((0, 1, 1), (0, 0, 2), (2, 1, 3)))
    assert _check(HTN("t", roots, top)) == {(("a", 1), ("b", 1))}


def _random_tree(leaves: Sequence[Leaf], rng: np.random.Generator) -> Node:
    if len(leaves) == 1:
        return ActionNode(*leaves[0])
    parts = int(rng.integers(2, min(3, len(leaves)) + 1))
    cuts = sorted(rng.choice(np.arange(1, len(leaves)), size=parts - 1, replace=False).tolist())
    bounds = [0, *cuts, len(leaves)]
    children = tuple(_random_tree(leaves[lo:hi], rng) for lo, hi in itertools.pairwise(bounds))
    return ChainNode(children) if rng.random() < 0.5 else CliqueNode(children)


def _random_top_level(n_roots: int, rng: np.random.Generator) -> TopLevel:
    orders = list(itertools.permutations(range(n_roots)))
    chosen = [orders[i] for i in rng.choice(len(orders), size=int(rng.integers(1, 5)), replace=True)]
    return seen_top_level(range(n_roots), chosen)  # every order is of all the roots: one terminal state


def test_random_hierarchies_match_brute_force(rng: np.random.Generator) -> None:
    for _ in range(150):
        n = int(rng.integers(1, 7))
        leaves = [(f"x{i}", 1) for i in rng.permutation(n)]
        n_roots = int(rng.integers(1, min(n, 4) + 1))
        cuts = sorted(rng.choice(np.arange(1, n), size=n_roots - 1, replace=False).tolist()) if n > 1 else []
        bounds = [0, *cuts, n]
        roots = tuple(_random_tree(leaves[lo:hi], rng) for lo, hi in itertools.pairwise(bounds))
        top = _random_top_level(n_roots, rng) if n_roots > 1 else None
        _check(HTN("t", roots, top))


# ------------------------------------------------------------------------------------------ scores


def test_scores() -> None:
    ab, bc, ac = (("a", 1), ("b", 1)), (("b", 1), ("c", 1)), (("a", 1), ("c", 1))
    score = precedence_scores({ab, bc, (("c", 1), ("a", 1))}, {ab, bc, ac, (("c", 1), ("d", 1))})
    assert (score.true_positives, score.learned, score.published) == (2, 3, 4)
    assert score.precision == pytest.approx(2 / 3) and score.recall == pytest.approx(0.5)
    assert score.f1 == pytest.approx(2 * (2 / 3) * 0.5 / (2 / 3 + 0.5))
    perfect = precedence_scores({ab}, {ab})
    assert (perfect.precision, perfect.recall, perfect.f1) == (1.0, 1.0, 1.0)


def test_score_conventions() -> None:
    ab, bc = (("a", 1), ("b", 1)), (("b", 1), ("c", 1))
    empty = precedence_scores(set(), {ab})
    assert (empty.precision, empty.recall, empty.f1) == (1.0, 0.0, 0.0)
    assert precedence_scores(set(), set()).f1 == 1.0
    wrong = precedence_scores({bc}, {ab})
    assert (wrong.precision, wrong.recall, wrong.f1) == (0.0, 0.0, 0.0)


# ------------------------------------------------------------------------------------------ CaptainCook4D


@pytest.fixture(scope="module")
def recipes() -> list[Recipe]:
    return load_captaincook()


def test_every_recipe_admits_its_demonstrations(recipes: list[Recipe], captaincook_reports: list[RecipeReport]) -> None:
    reports = captaincook_reports
    assert [r.recipe for r in reports] == [r.name for r in recipes]
    failing = [r.recipe for r in reports if not r.admits_demonstrations]
    assert not failing, f"invariant 1 broken for {failing}"
    for report, recipe in zip(reports, recipes, strict=True):
        assert report.demonstrations == len(recipe.spec.demonstrations)
        assert report.complete == (report.roots == 1)
        assert report.score.published == len(recipe.published)
        assert 0.0 <= report.score.precision <= 1.0 and 0.0 <= report.score.recall <= 1.0


def test_implied_pairs_hold_in_every_demonstration(recipes: list[Recipe]) -> None:
    for recipe in recipes:
        learner = learn(recipe.spec)
        pairs = implied_precedences(learner.htn_)
        deviating = {d.demonstration for d in learner.deviations_}
        for i, demo in enumerate(recipe.spec.demonstrations):
            if i in deviating:
                continue
            position = {leaf: i for i, leaf in enumerate(to_leaves(demo.actions))}
            assert all(position[a] < position[b] for a, b in pairs), (recipe.name, demo.id)


def test_compare_recipe_options(recipes: list[Recipe]) -> None:
    report = compare_recipe(recipes[0], {"alternatives": 0})
    assert report.recipe == recipes[0].name and report.known_paths >= 1
