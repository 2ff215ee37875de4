"""HDDL export: round trips through unified-planning's writer and reader, solved by Aries."""

from __future__ import annotations

import importlib.util
import itertools
import re
from pathlib import Path
from typing import Any

import pytest

from supportive import examples
from supportive.errors import ExportError
from supportive.io.hddl import hddl_strings, htn_to_problem, read_hddl, solve_hddl, write_hddl
from supportive.learning import learn
from supportive.tasks.htn import HTN, ActionNode, ChainNode, CliqueNode, Node, TopLevel, to_leaves

NAME = re.compile(r"^[a-z][a-z0-9_-]*$")


def chain(*children: Node | str) -> ChainNode:
    return ChainNode(tuple(ActionNode(c) if isinstance(c, str) else c for c in children))


def clique(*children: Node | str) -> CliqueNode:
    return CliqueNode(tuple(ActionNode(c) if isinstance(c, str) else c for c in children))


def round_trip(htn: HTN, folder: Path) -> Any:
    """Write the HTN's HDDL to ``folder`` and parse it back."""
    domain, problem = write_hddl(htn, folder)
    assert (domain.name, problem.name) == ("domain.hddl", "problem.hddl")
    return read_hddl(domain, problem)


def assert_valid_plan(htn: HTN, plan: list[str] | None) -> None:
    assert plan is not None
    assert sorted(to_leaves(plan)) == sorted(htn.leaves)  # every leaf exactly once
    assert htn.admits(plan)


@pytest.mark.parametrize("name", examples.names())
def test_learned_example_and_its_alternatives_round_trip_and_solve(name: str, tmp_path: Path) -> None:
    strict = name == "two-glasses"  # the thesis's readings, the strict learner's alternatives
    htn = learn(examples.load(name), mode="strict" if strict else "auto").htn_
    main_plan = solve_hddl(round_trip(htn, tmp_path), htn)
    assert_valid_plan(htn, main_plan)
    if strict:
        assert len(htn.alternatives) == 2
    for i, alternative in enumerate(htn.alternatives):
        assert alternative.complete
        plan = solve_hddl(round_trip(alternative, tmp_path / f"alternative{i}"), alternative)
        assert_valid_plan(alternative, plan)
        if strict:  # a strict alternative admits only known executions
            assert plan is not None and htn.admits(plan)
        else:  # a general one admits every execution the hierarchy admits
            assert main_plan is not None and alternative.admits(main_plan)


# --- a clique of two chains: no interleaving ----------------------------------------------------------------

CLIQUE = HTN("two chains", (clique(chain("a", "b"), chain("c", "d")),))


def test_clique_htn_admits_only_blocks() -> None:
    admitted = ["".join(p) for p in itertools.permutations("abcd") if CLIQUE.admits(list(p))]
    assert admitted == ["abcd", "cdab"]


def test_clique_plan_is_one_block_order(tmp_path: Path) -> None:
    plan = solve_hddl(round_trip(CLIQUE, tmp_path), CLIQUE)
    assert plan is not None and "".join(plan) in {"abcd", "cdab"}


def test_clique_methods_run_one_whole_child_then_recurse(tmp_path: Path) -> None:
    problem = round_trip(CLIQUE, tmp_path)
    (root,) = problem.task_network.subtasks
    clique_task = root.task
    methods = [m for m in problem.methods if m.achieved_task.task == clique_task]
    chains = {m.achieved_task.task.name: m for m in problem.methods if m.achieved_task.task != clique_task}
    assert len(methods) == 3
    recursive = [m for m in methods if m.subtasks]
    (end,) = [m for m in methods if not m.subtasks]
    assert str(end.preconditions[0]) == "(done_a and done_c)"
    assert len(recursive) == 2
    for method in recursive:
        child, again = (method.get_subtask(ident) for ident in method.total_order())
        assert again.task == clique_task  # [child, Q]: totally ordered, the child runs to its end first
        assert child.task.name in chains
        first = chains[child.task.name].subtasks[0].task.name
        assert [str(p) for p in method.preconditions] == [f"(not done_{first})"]
    for method in chains.values():
        assert [method.get_subtask(i).task.name for i in method.total_order()] in (["a", "b"], ["c", "d"])


def test_clique_forbids_interleaving_even_when_forced(tmp_path: Path) -> None:
    # Make c wait for a: only "abcd" is left, and the planner finds it.
    problem = round_trip(CLIQUE, tmp_path / "one")
    problem.action("c").add_precondition(problem.fluent("done_a")())
    assert solve_hddl(problem, CLIQUE) == ["a", "b", "c", "d"]
    # Also make b wait for c: only the interleaving a c b d satisfies both, and it must not be found.
    # (Aries cannot prove a recursive hierarchy unsolvable, so it searches until the timeout.)
    problem = round_trip(CLIQUE, tmp_path / "two")
    problem.action("c").add_precondition(problem.fluent("done_a")())
    problem.action("b").add_precondition(problem.fluent("done_c")())
    assert solve_hddl(problem, CLIQUE, timeout=2) is None


# --- repeated actions, names, top levels ------------------------------------------------------------


def test_repeated_action_round_trips(tmp_path: Path) -> None:
    htn = HTN("coffee", (ChainNode((ActionNode("stir"), ActionNode("pour"), ActionNode("stir", 2))),))
    domain, _ = hddl_strings(htn)
    assert "(:action stir\n" in domain and "(:action stir_2\n" in domain
    problem = round_trip(htn, tmp_path)
    assert sorted(a.name for a in problem.actions) == ["pour", "stir", "stir_2"]
    assert solve_hddl(problem, htn) == ["stir", "pour", "stir"]


def test_repeated_action_occurrences_keep_their_order() -> None:
    # Either chain may go first, but the first "stir" performed is always occurrence 1.
    htn = HTN("coffee", (clique(chain(ActionNode("stir"), "pour"), chain(ActionNode("stir", 2), "mix")),))
    plan = solve_hddl(htn_to_problem(htn))
    assert_valid_plan(htn, plan)


def test_problem_built_here_maps_back_without_the_htn() -> None:
    htn = HTN("coffee", (chain("Stir Coffee", "pour", ActionNode("Stir Coffee", 2)),))
    assert solve_hddl(htn_to_problem(htn)) == ["Stir Coffee", "pour", "Stir Coffee"]


def test_identifiers_are_sanitised_and_parse_back(tmp_path: Path) -> None:
    ids = ["Stir Coffee", "stir coffee", "3 legs", "and", "Pour-Milk", "Émile", "task", "done_x", "x"]
    htn = HTN("My Task #1", (clique(chain(*ids[:4]), chain(*ids[4:])),))
    domain, problem_text = hddl_strings(htn)
    problem = round_trip(htn, tmp_path)
    names = [a.name for a in problem.actions] + [f.name for f in problem.fluents]
    names += [t.name for t in problem.tasks] + [m.name for m in problem.methods]
    assert all(NAME.match(n) for n in names), names
    assert len(set(names)) == len(names)
    assert sorted(a.name for a in problem.actions) == sorted(
        ["stir_coffee", "stir_coffee_2", "x_3_legs", "and_2", "pour-milk", "mile", "task_2", "done_x", "x"]
    )
    assert "Stir" not in domain + problem_text
    plan = solve_hddl(problem, htn)
    assert_valid_plan(htn, plan)
    assert plan is not None and set(plan) == set(ids)


def test_partial_htn_with_several_initial_states(tmp_path: Path) -> None:
    top = TopLevel(initial=(0, 1), terminal=(3,), edges=((0, 0, 2), (2, 1, 3), (1, 1, 4), (4, 0, 3)))
    htn = HTN("two", (chain("a", "b"), ActionNode("c")), top)
    assert htn.count_orderings() == 2
    assert_valid_plan(htn, solve_hddl(round_trip(htn, tmp_path), htn))


def test_unsolvable_top_level_gives_none() -> None:
    top = TopLevel(initial=(0,), terminal=(), edges=((0, 0, 1),))  # no terminal state: nothing admitted
    htn = HTN("stuck", (ActionNode("a"),), top)
    assert solve_hddl(htn_to_problem(htn), htn, timeout=10) is None


def test_export_is_deterministic() -> None:
    htn = learn(examples.load("ikea-chair")).htn_
    assert hddl_strings(htn) == hddl_strings(htn)


def test_write_creates_the_directory(tmp_path: Path) -> None:
    domain, problem = write_hddl(CLIQUE, tmp_path / "deep" / "er")
    assert domain.read_text().startswith("(define (domain")
    assert problem.read_text().startswith("(define (problem")


# --- errors ----------------------------------------------------------------------------------------


def test_several_roots_without_top_level_is_an_error(tmp_path: Path) -> None:
    htn = HTN("loose", (ActionNode("a"), ActionNode("b")))
    with pytest.raises(ExportError, match="no top level"):
        write_hddl(htn, tmp_path / "out")
    assert not (tmp_path / "out").exists()  # nothing written when the export fails


def test_duplicate_leaf_is_an_error() -> None:
    with pytest.raises(ExportError, match="twice"):
        htn_to_problem(HTN("dup", (chain("a", "a"),)))


def test_unreadable_hddl_is_an_error(tmp_path: Path) -> None:
    (tmp_path / "d.hddl").write_text("(define (domain")
    (tmp_path / "p.hddl").write_text("")
    with pytest.raises(ExportError, match="cannot read HDDL"):
        read_hddl(tmp_path / "d.hddl", tmp_path / "p.hddl")


def test_missing_planning_extra_is_reported(monkeypatch: pytest.MonkeyPatch) -> None:
    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "unified_planning" else real(name, *a)
    )
    with pytest.raises(ExportError, match=r"supportive\[planning\]"):
        htn_to_problem(CLIQUE)


def _goal(problem: str) -> set[str]:
    found = re.search(r"\(:goal \(and(.*?)\)\s*\)\s*\)\s*$", problem, re.S)
    return set(re.findall(r"\((done_[a-z0-9_]+)\)", found.group(1))) if found else set()


def test_the_goal_is_every_leaf_no_execution_skips() -> None:
    """Issue 26: `--format hddl` wrote an empty `(:goal (and ))`. The goal is what every plan achieves."""
    problem = hddl_strings(CLIQUE)[1]
    assert _goal(problem) == {"done_a", "done_b", "done_c", "done_d"}
    optional = HTN("opt", (chain("a", ChainNode((ActionNode("b"),), optional=True), "c"),))
    assert _goal(hddl_strings(optional)[1]) == {"done_a", "done_c"}
    # a top level where root 1 (c) may be left out: only the leaves of the root every path takes
    top = TopLevel(initial=(0,), terminal=(1, 2), edges=((0, 0, 1), (1, 1, 2)))
    assert _goal(hddl_strings(HTN("skip", (chain("a", "b"), ActionNode("c")), top))[1]) == {"done_a", "done_b"}
    nothing = HTN("all optional", (ChainNode((ActionNode("a"),), optional=True),))
    assert ":goal" not in hddl_strings(nothing)[1]


@pytest.mark.parametrize("name", ["two-glasses", "tea-mistakes", "ikea-chair"])
def test_the_goal_cuts_no_plan(name: str, tmp_path: Path) -> None:
    htn = learn(examples.load(name)).htn_
    problem = hddl_strings(htn)[1]
    assert _goal(problem), problem
    assert_valid_plan(htn, solve_hddl(round_trip(htn, tmp_path), htn))
