"""Random structures: exact size, normal form, readable distinct ids, determinism, speed."""

from __future__ import annotations

import re

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import SupportiveError
from supportive.generate import (
    GenerationError,
    IkeaParams,
    Profile,
    UniformParams,
    is_normalised,
    random_structure,
)
from supportive.tasks.htn import (
    ActionNode,
    ChainNode,
    CliqueNode,
    Node,
    canonical,
    count_orderings,
    iter_orderings,
    leaf_actions,
    mean_action_depth,
    sample_ordering,
)

PROFILES: tuple[Profile, ...] = ("ikea", "uniform")
profiles: st.SearchStrategy[Profile] = st.sampled_from(PROFILES)
seeds = st.integers(0, 2**32 - 1)

IKEA_ID = re.compile(r"^(pick|place|fasten|insert|tighten)_[a-z]+(_[a-z]+)*_\d+$")


def internal_nodes(node: Node) -> list[ChainNode | CliqueNode]:
    if isinstance(node, ActionNode):
        return []
    return [node, *(inner for child in node.children for inner in internal_nodes(child))]


@given(n=st.integers(1, 400), seed=seeds, profile=profiles)
def test_exact_distinct_leaves_in_normal_form(n: int, seed: int, profile: Profile) -> None:
    node = random_structure(n, seed, profile=profile)
    actions = leaf_actions(node)
    assert len(actions) == n
    assert len(set(actions)) == n
    assert all(occurrence == 1 for _, occurrence in node.leaves)
    assert is_normalised(node)
    for inner in internal_nodes(node):
        assert len(inner.children) >= 2
        if isinstance(inner, ChainNode):
            assert not any(isinstance(child, ChainNode) for child in inner.children)


@given(n=st.integers(1, 200), seed=seeds)
def test_ikea_ids_are_readable(n: int, seed: int) -> None:
    for action in leaf_actions(random_structure(n, seed)):
        assert IKEA_ID.match(action), action


@given(n=st.integers(2, 120), seed=seeds)
def test_ikea_parts_are_picked_then_placed_and_bolts_inserted_then_tightened(n: int, seed: int) -> None:
    node = random_structure(n, seed)
    actions = set(leaf_actions(node))
    order = [a for a, _ in sample_ordering(node, seed)]
    position = {a: i for i, a in enumerate(order)}
    for action in actions:
        verb, _, rest = action.partition("_")
        follower = {"pick": "place", "insert": "tighten"}.get(verb)
        if follower is not None:
            assert position[f"{follower}_{rest}"] == position[action] + 1


@given(n=st.integers(1, 60), seed=seeds)
def test_uniform_ids_number_the_steps(n: int, seed: int) -> None:
    node = random_structure(n, seed, profile="uniform")
    assert sorted(leaf_actions(node)) == sorted(f"step_{i}" for i in range(1, n + 1))


@given(n=st.integers(2, 80), seed=seeds)
def test_uniform_alternate_kinds_alternate(n: int, seed: int) -> None:
    node = random_structure(n, seed, profile="uniform", params=UniformParams(kinds="alternate"))
    for inner in internal_nodes(node):
        assert all(child.kind != inner.kind for child in inner.children)


def test_uniform_all_cliques_nest_cliques() -> None:
    node = random_structure(30, 1, profile="uniform", params=UniformParams(clique_probability=1.0))
    assert all(isinstance(inner, CliqueNode) for inner in internal_nodes(node))
    assert count_orderings(node) > 1


def test_uniform_all_chains_is_one_flat_chain() -> None:
    node = random_structure(30, 1, profile="uniform", params=UniformParams(clique_probability=0.0))
    assert isinstance(node, ChainNode)
    assert len(node.children) == 30


@given(n=st.integers(1, 7), seed=seeds, profile=profiles)
def test_count_orderings_matches_enumeration(n: int, seed: int, profile: Profile) -> None:
    node = random_structure(n, seed, profile=profile)
    orderings = list(iter_orderings(node))
    assert count_orderings(node) == len(orderings) == len(set(orderings))


@pytest.mark.parametrize("profile", PROFILES)
def test_same_seed_same_structure(profile: Profile) -> None:
    first = random_structure(150, 42, profile=profile)
    second = random_structure(150, 42, profile=profile)
    assert first == second
    assert repr(first) == repr(second)  # names too


@pytest.mark.parametrize("profile", PROFILES)
def test_different_seeds_differ(profile: Profile) -> None:
    forms = {canonical(random_structure(60, seed, profile=profile)) for seed in range(10)}
    assert len(forms) == 10


def test_generator_seed_is_used_and_advanced() -> None:
    rng = np.random.default_rng(5)
    first = random_structure(40, rng)
    second = random_structure(40, rng)
    assert first != second
    assert first == random_structure(40, np.random.default_rng(5))


@pytest.mark.parametrize("profile", PROFILES)
def test_five_thousand_actions_are_distinct_and_normalised(profile: Profile) -> None:
    node = random_structure(5000, 0, profile=profile)  # its speed: benchmarks/bench_generate.py
    assert len(set(leaf_actions(node))) == 5000
    assert is_normalised(node)


def test_ikea_large_tasks_stay_thesis_deep() -> None:
    depths = [mean_action_depth([random_structure(1000, seed)]) for seed in range(5)]
    assert all(2.5 <= depth <= 3.4 for depth in depths)


def test_ikea_knobs_shape_the_structure() -> None:
    flat = IkeaParams(
        parts_per_step=(1.0,),
        connector_weights=(0.0, 1.0),
        two_step_probability=0.0,
        subassembly_probability=0.0,
    )
    node = random_structure(30, 0, params=flat)
    assert isinstance(node, ChainNode)
    assert count_orderings(node) == 1
    assert all(isinstance(child, ActionNode) for child in node.children)


def test_ikea_always_cliques_of_part_pairs() -> None:
    params = IkeaParams(
        parts_per_step=(0.0, 1.0),
        connector_weights=(1.0,),
        step_clique_probability=1.0,
        subassembly_probability=0.0,
    )
    node = random_structure(40, 3, params=params)
    assert isinstance(node, ChainNode)
    assert len(node.children) == 10
    for step in node.children:
        assert isinstance(step, CliqueNode)
        assert [leaf_actions(part)[0].split("_")[0] for part in step.children] == ["pick", "pick"]
    assert count_orderings(node) == 2**10


@pytest.mark.parametrize("n", [0, -3])
@pytest.mark.parametrize("profile", PROFILES)
def test_no_actions_is_an_error(n: int, profile: Profile) -> None:
    with pytest.raises(GenerationError, match="at least 1"):
        random_structure(n, profile=profile)


def test_bad_profile_and_params_are_errors() -> None:
    with pytest.raises(GenerationError, match="unknown profile"):
        random_structure(5, profile="lego")  # type: ignore[arg-type]
    with pytest.raises(GenerationError, match="IkeaParams"):
        random_structure(5, params=UniformParams())
    with pytest.raises(GenerationError, match="UniformParams"):
        random_structure(5, profile="uniform", params=IkeaParams())
    with pytest.raises(GenerationError, match="clique_probability"):
        UniformParams(clique_probability=1.5)
    with pytest.raises(GenerationError, match="max_children"):
        UniformParams(max_children=1)
    with pytest.raises(GenerationError, match="connector_weights"):
        IkeaParams(connector_weights=())
    with pytest.raises(GenerationError, match="subassemblies"):
        IkeaParams(subassemblies=(1, 2))
    assert issubclass(GenerationError, SupportiveError)
    assert issubclass(GenerationError, ValueError)
