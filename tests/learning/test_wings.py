"""The two learners behind HTNLearner: a general fit builds none of the strict learner's structures, and the
alternatives a hierarchy reports are its own learner's — the general learner's admit every execution the
hierarchy admits (checked against every execution enumerated, on generated tasks)."""

from __future__ import annotations

import random
from collections.abc import Callable, Iterator, Sequence

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from supportive.errors import NotFittedError, TaskGraphError
from supportive.generate import generate_task, inject, random_partial_order
from supportive.generate.mistakes import KINDS
from supportive.learning import HTNLearner
from supportive.learning.general.alternatives import complete_alternative
from supportive.learning.strict import Compaction, StrictLearner
from supportive.tasks.executions import Progress
from supportive.tasks.htn import HTN, ActionNode, ChainNode, CliqueNode, Leaf, TopLevel, iter_orderings
from supportive.tasks.spec import Demonstration, Step
from supportive.tasks.task_graph import TaskGraph

ENUMERATION_LIMIT = 3000


def executions(htn: HTN, limit: int = ENUMERATION_LIMIT) -> Iterator[tuple[Leaf, ...]]:
    """Every leaf sequence ``htn`` admits, by walking its execution machine (at most ``limit``)."""
    machine = htn.executions
    stack: list[tuple[tuple[Leaf, ...], Progress]] = [((), state) for state in machine.initial()]
    seen: set[tuple[Leaf, ...]] = set()
    while stack:
        done, state = stack.pop()
        if machine.can_finish(state) and done not in seen:
            seen.add(done)
            if len(seen) > limit:
                return
            yield done
        stack.extend(((*done, machine.leaves[leaf]), after) for leaf, after in machine.moves(state).items())


def _interleaved(seed: int, n: int) -> list[list[str]]:
    """``n`` demonstrations drawn uniformly from a random partial order of 6–8 steps (no tree fits it)."""
    task = random_partial_order(6 + seed % 3, seed, chains=2 + seed % 2, cross=seed % 3)
    rng = random.Random(seed)
    return [list(task.sample(rng.randrange(2**32))) for _ in range(n)]


def test_a_general_fit_builds_none_of_the_strict_structures(monkeypatch: pytest.MonkeyPatch) -> None:
    def built(*_: object, **__: object) -> None:
        raise AssertionError("a strict structure was built")

    monkeypatch.setattr(StrictLearner, "of", built)
    monkeypatch.setattr(Compaction, "run", built)
    monkeypatch.setattr(TaskGraph, "add_leaves", built)  # every task graph is built through these
    monkeypatch.setattr(TaskGraph, "add_demonstration", built)
    demos = _interleaved(1, 12)
    for mode in ("general", "partial order"):
        learner = HTNLearner(mode=mode).fit(demos)
        learner.partial_fit(demos[0])
        assert learner.htn_.admits(demos[0]) and learner.reading_ == mode
        with pytest.raises(AssertionError, match="strict structure"):  # asked for: built then
            _ = learner.task_graph_


def test_the_strict_structures_asked_for_after_a_general_fit_are_the_strict_learners() -> None:
    demos = _interleaved(2, 10)
    general, strict = HTNLearner(mode="general").fit(demos[:6]), HTNLearner(mode="strict").fit(demos[:6])
    assert general.task_graph_.path_count() == strict.task_graph_.path_count()
    for demo in demos[6:]:  # built once asked for, then kept up to date
        general.partial_fit(demo)
        strict.partial_fit(demo)
    refit = HTNLearner(mode="general").fit(demos)
    for learner in (general, refit):
        assert learner.task_graph_.n_states == strict.task_graph_.n_states
        assert learner.task_graph_.path_count() == strict.task_graph_.path_count()
        assert learner.ctg_.n_edges == strict.ctg_.n_edges
        assert learner.stats_.task_graph == strict.stats_.task_graph
        assert learner.stats_.ctg == strict.stats_.ctg
    assert general.htn_ == refit.htn_


def test_an_unfitted_learner_has_no_strict_structures() -> None:
    for name in ("task_graph_", "ctg_", "stats_"):
        with pytest.raises(NotFittedError, match=name):
            getattr(HTNLearner(), name)


def test_a_general_fit_keeps_the_task_graphs_checks() -> None:
    with pytest.raises(TaskGraphError, match="d2 has no steps"):
        HTNLearner(mode="general").fit([["a", "b"], []])
    learner = HTNLearner(mode="general").fit([["a", "b"]])
    stated = Demonstration((Step("a", state=frozenset({"x"})), Step("b", state=frozenset({"x", "y"}))), "s")
    with pytest.raises(TaskGraphError, match="explicit states, or none"):
        learner.partial_fit(stated)
    assert HTNLearner().fit([stated]).learns_strictly


def test_two_interleaved_chains_between_a_first_and_a_last_step() -> None:
    """x, then a1<a2<a3 and b1<b2<b3 interleaved, then y: the partial order's alternative is the chain of its
    blocks, x, every order of the chains' steps, y (the steps of one chain are not contiguous, so no subtask
    of a chain fits)."""
    task = random_partial_order(6, 0, chains=2)
    rng = random.Random(0)
    demos = [["x", *task.sample(rng.randrange(2**32)), "y"] for _ in range(40)]
    learner = HTNLearner(mode="general").fit(demos)
    assert not learner.htn_.complete
    (alternative,) = learner.htn_.alternatives
    root = alternative.roots[0]
    assert isinstance(root, ChainNode) and [child.kind for child in root.children] == ["action", "clique", "action"]
    middle = root.children[1]
    assert isinstance(middle, CliqueNode) and sorted(a for a, _ in middle.leaves) == sorted(task.steps)
    assert all(alternative.admits(demo) for demo in demos)


def test_the_alternative_settings_bound_the_general_alternatives_too() -> None:
    demos = _interleaved(3, 12)
    roots = len(HTNLearner(mode="general").fit(demos).htn_.roots)
    assert roots > 1 and len(HTNLearner(mode="general").fit(demos).htn_.alternatives) == 1
    assert HTNLearner(mode="general", alternatives=0).fit(demos).htn_.alternatives == ()
    assert HTNLearner(mode="general", max_alternative_roots=roots - 1).fit(demos).htn_.alternatives == ()
    assert len(HTNLearner(mode="general", max_alternative_roots=roots).fit(demos).htn_.alternatives) == 1


def test_a_root_the_top_level_may_leave_out_is_optional_in_the_alternative() -> None:
    """A strict top level ends after ``chain(a, b)`` or after ``c`` too; its roots carry no optional flag
    (found by hypothesis: the demonstrations ``abc`` ×4 and ``abcb``, kept by ``auto`` in the strict reading)."""
    first, second = ChainNode((ActionNode("a"), ActionNode("b"))), ActionNode("c")
    top = TopLevel((0,), (1, 2), ((0, 0, 1), (1, 1, 2)))
    alternative = HTN("", (complete_alternative((first, second), top),))
    assert top.required_roots(2) == {0}
    assert alternative.admits(["a", "b"]) and alternative.admits(["a", "b", "c"])
    demos = [["a", "b", "c"]] * 4 + [["a", "b", "c", "b"]]
    htn = HTNLearner(slips=False).fit(demos).htn_
    assert not htn.complete and all(htn.alternatives[0].admits_leaves(e) for e in executions(htn))


def test_an_initial_state_with_no_move_requires_no_root() -> None:
    assert TopLevel((0,), (), ()).required_roots(2) == set()
    assert TopLevel((0,), (2,), ((0, 0, 1), (1, 1, 2))).required_roots(2) == {0, 1}


def test_strict_alternatives_are_still_restrictions_of_the_known_executions() -> None:
    """§2.1.5.3's two glasses: the strict learner's readings each admit known executions only."""
    from supportive.examples import load

    learner = HTNLearner(mode="strict").fit(load("two-glasses"))
    assert len(learner.htn_.alternatives) >= 2
    for alternative in learner.htn_.alternatives:
        assert all(learner.task_graph_.contains([a for a, _ in o]) for o in iter_orderings(alternative.roots[0]))


@st.composite
def generated(draw: st.DrawFn) -> list[list[str]]:
    """Demonstrations of a generated task: a partial order of interleaved chains, or a chain/clique structure
    sampled from a few times (too few for subtasks: a partial order of steps); in a fifth of them, sometimes,
    a step moved, repeated or dropped (slips, optional steps)."""
    seed = draw(st.integers(0, 2**16))
    if draw(st.booleans()):
        task = random_partial_order(draw(st.integers(3, 7)), seed, chains=draw(st.integers(2, 3)), cross=draw(st.integers(0, 2)))
        rng = random.Random(seed)
        demos = [list(task.sample(rng.randrange(2**32))) for _ in range(draw(st.integers(1, 30)))]
        valid: Callable[[Sequence[str]], bool] = task.admits
    else:
        spec = generate_task(draw(st.integers(3, 8)), seed, demonstrations=draw(st.integers(1, 12)), profile="uniform")
        assert spec.structure is not None
        demos = [list(d.actions) for d in spec.demonstrations]
        valid = HTN("", (spec.structure,)).admits
    kind = draw(st.sampled_from([None, *KINDS]))
    if kind is None or max(map(len, demos)) < 3:
        return demos
    return inject(demos, kind, 0.2, valid, seed)[0]


@settings(max_examples=100, deadline=None)
@given(generated(), st.sampled_from(["general", "partial order", "auto"]), st.booleans())
def test_general_alternatives_admit_every_execution_the_hierarchy_admits(
    demos: list[list[str]], mode: str, slips: bool
) -> None:
    htn = HTNLearner(mode=mode, slips=slips).fit(demos).htn_  # type: ignore[arg-type]
    if htn.complete:
        assert htn.alternatives == ()
        return
    assume(htn.count_orderings() <= ENUMERATION_LIMIT)
    (alternative,) = htn.alternatives
    assert alternative.complete
    assert sorted(alternative.leaves) == sorted(htn.leaves), "the same steps"
    admitted = list(executions(htn))
    assert admitted, "the hierarchy admits some execution"
    for execution in admitted:
        assert alternative.admits_leaves(execution), execution
    for d, demo in enumerate(demos):
        if htn.admits(demo):
            assert alternative.admits(demo), f"demonstration {d + 1}"
