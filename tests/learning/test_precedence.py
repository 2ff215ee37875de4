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
    """The pairs of steps every execution doing both keeps in that order, its steps named as executions name
    them: by action and how many times the action was done so far (whichever leaf of the tree performed
    it)."""
    executions = [to_leaves([action for action, _ in execution]) for execution in _executions(htn)]
    assert executions, "the HTN admits no execution"
    steps = set(htn.leaves)  # a step no execution does keeps every order with the others, vacuously
    broken: set[Pair] = set()
    for execution in executions:
        broken.update((b, a) for i, a in enumerate(execution) for b in execution[i + 1 :])
    return frozenset((a, b) for a in steps for b in steps if a != b and (a, b) not in broken)


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


def _with_repeats(node: Node, repeated: set[str], blocks: set[str]) -> Node:
    """``node`` with each leaf whose action is in ``repeated`` made a clique of repeats: of that action done
    three times (a learned ``3 × stir``), or for an action also in ``blocks``, of two blocks of it and a
    second action (``2 × (heat → stir)``)."""
    if isinstance(node, ActionNode):
        if node.action not in repeated:
            return node
        if node.action not in blocks:
            return CliqueNode(tuple(A(node.action, k) for k in (1, 2, 3)))
        then = node.action + "'"
        return CliqueNode(tuple(ChainNode((A(node.action, k), A(then, k))) for k in (1, 2)))
    children = tuple(_with_repeats(child, repeated, blocks) for child in node.children)
    return ChainNode(children) if isinstance(node, ChainNode) else CliqueNode(children)


def test_a_clique_of_repeats_orders_its_performances() -> None:
    # CaptainCook4D's pinwheels: pull the floss ends, slice three times, plate. The learner keeps the three
    # slices as a clique of repeats; the first slice still comes before the second, and the plate after the
    # third, in every execution (before, the pairs of the tree's labels left the slices unordered)
    tree = ChainNode((A("pull"), CliqueNode((A("slice"), A("slice", 2), A("slice", 3))), A("plate")))
    found = _check(HTN("t", (tree,)))
    assert {(("slice", 1), ("slice", 2)), (("slice", 2), ("slice", 3)), (("slice", 3), ("plate", 1))} <= found


def test_a_clique_of_repeated_blocks_is_done_block_after_block() -> None:
    # dressedupmeatballs: microwave, stir, microwave again, stir again, learned as 2 × (microwave → stir); the
    # block done first holds the first microwave and the first stir, so the four come in one order
    blocks = CliqueNode((ChainNode((A("heat"), A("stir"))), ChainNode((A("heat", 2), A("stir", 2)))))
    found = _check(HTN("t", (ChainNode((A("pour"), blocks)),)))
    assert {(("heat", 1), ("stir", 1)), (("stir", 1), ("heat", 2)), (("heat", 2), ("stir", 2))} <= found


def test_random_hierarchies_with_cliques_of_repeats_match_brute_force(rng: np.random.Generator) -> None:
    for _ in range(100):
        n = int(rng.integers(1, 5))
        leaves = [(f"x{i}", 1) for i in rng.permutation(n)]
        repeated = {name for name, _ in leaves if rng.random() < 0.4}
        blocks = {name for name in repeated if rng.random() < 0.5}
        n_roots = int(rng.integers(1, min(n, 3) + 1))
        cuts = sorted(rng.choice(np.arange(1, n), size=n_roots - 1, replace=False).tolist()) if n > 1 else []
        bounds = [0, *cuts, n]
        roots = tuple(
            _with_repeats(_random_tree(leaves[lo:hi], rng), repeated, blocks) for lo, hi in itertools.pairwise(bounds)
        )
        top = _random_top_level(n_roots, rng) if n_roots > 1 else None
        _check(HTN("t", roots, top))


def _random_top_level_skipping(n_roots: int, rng: np.random.Generator) -> TopLevel:
    """A top level of orders seen in which some paths leave roots out (a step a few recordings did)."""
    orders = []
    for _ in range(int(rng.integers(1, 5))):
        order = [int(r) for r in rng.permutation(n_roots)]
        kept = [r for r in order if rng.random() < 0.8] or order[:1]
        orders.append(kept)
    return seen_top_level(range(n_roots), orders)


def test_random_hierarchies_with_repeated_actions_claim_no_order_some_execution_breaks(rng: np.random.Generator) -> None:
    # the same action at several leaves anywhere in the tree, in roots some paths skip: every pair claimed
    # holds in every execution doing both (where a clique keeps blocks of them together, the count can hold
    # orders the pairs do not find)
    for _ in range(300):
        n = int(rng.integers(1, 7))
        names = [f"x{int(rng.integers(max(1, n // 2)))}" for _ in range(n)]
        leaves = [(name, names[: i + 1].count(name)) for i, name in enumerate(names)]
        leaves = [leaves[i] for i in rng.permutation(n)]
        n_roots = int(rng.integers(1, min(n, 4) + 1))
        cuts = sorted(rng.choice(np.arange(1, n), size=n_roots - 1, replace=False).tolist()) if n > 1 else []
        bounds = [0, *cuts, n]
        roots = tuple(_random_tree(leaves[lo:hi], rng) for lo, hi in itertools.pairwise(bounds))
        top = (_random_top_level_skipping if rng.random() < 0.5 else _random_top_level)(n_roots, rng)
        htn = HTN("t", roots, top if n_roots > 1 else None)
        assert implied_precedences(htn) <= _brute_force(htn)


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
