from __future__ import annotations

import importlib
import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import pytest
from tests.experiments.test_docs_numbers import check_quoted

from supportive.examples.food import transfer_names
from supportive.experiments import get, names, run_experiment
from supportive.experiments.plotting import PNG_SIGNATURE
from supportive.experiments.transfer.explore import (
    FAIL,
    NOVELTY,
    START,
    STEP,
    Option,
    TaskModel,
    execute,
    explore,
)
from supportive.experiments.transfer.measure import (
    CONDITIONS,
    MACRO_CONDITIONS,
    READINGS,
    make_trials,
    run_condition,
    run_trial,
)
from supportive.experiments.transfer.report import CLAIM, column
from supportive.experiments.transfer.sources import (
    PRIOR_SCALE,
    _sequence_value,
    aggregate,
    dictionary,
    macro_option,
    macros_for,
    source_q,
    task_model,
    transfer_initial,
)
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, Node, admits, count_orderings, to_leaves

# a → {b, c} → d: 2 orderings.
TINY = ChainNode(
    (ActionNode("a"), CliqueNode((ActionNode("b"), ActionNode("c"))), ActionNode("d"))
)  # fmt: skip


def test_registered() -> None:
    assert "transfer" in names()
    experiment = get("transfer")
    assert experiment.reference == "§2.1.7.4, Figure 2.6"
    assert experiment.default_trials == 25 * 4
    assert len(transfer_names()) == 25
    assert len(dictionary()) == 39


def test_task_model_states() -> None:
    model = TaskModel.from_structure("tiny", TINY)
    assert model.orderings == 2
    assert set(model.allowed[0]) == {"a"}
    assert set(model.allowed[1]) == {"b", "c"}
    assert model.allowed[model.full] == {}
    for name in transfer_names()[:5]:
        m = task_model(name)
        assert m.orderings == count_orderings(m_structure(name))


def m_structure(name: str) -> Node:
    from supportive.examples.food import load_transfer

    structure = load_transfer(name).structure
    assert structure is not None
    return structure


def test_macro_expands_and_stops_at_first_disallowed_action() -> None:
    model = TaskModel.from_structure("tiny", TINY)
    seen: set[tuple[int, str]] = set()
    path: list[str] = []
    step = execute(model, 0, ("a", "c", "b", "d"), seen, START, path, set())
    assert step.performed == ("a", "c", "b", "d") and step.state == model.full and step.tried == 4
    assert path == ["a", "c", "b", "d"] and len(seen) == 4
    # "a" runs, then "d" is not allowed: it fails and "c" is never tried
    path2: list[str] = []
    step = execute(model, 0, ("a", "d", "c"), seen, START, path2, set())
    assert step.performed == ("a",) and step.tried == 2 and step.state == 1 and step.last == "a"
    # "a" is known now (no novelty): STEP, then the failure discounted once
    assert step.reward == round(STEP + 0.9 * FAIL, 12)
    # a failing first action leaves the state unchanged
    step = execute(model, 1, ("d", "b"), seen, "a", [], set())
    assert step.performed == () and step.state == 1 and step.reward == FAIL and step.last == "a"
    # novelty pays once
    step = execute(model, 1, ("b",), set(), "a", [], set())
    assert step.reward == STEP + NOVELTY


def test_explorer_comprehends_a_tiny_task() -> None:
    model = TaskModel.from_structure("tiny", TINY)
    options = tuple(((x,),) for x in "abcdxyz")
    result = explore(model, options, 0, max_episodes=200, step_cap=50)
    assert result.episodes is not None and result.paths_known == 2 == result.paths_found
    # with the macro (a, b) the agent still has to find a → c → b → d with primitives
    result = explore(model, (*options, (("a", "b"),)), 0, max_episodes=200, step_cap=50)
    assert result.episodes is not None and result.paths_known == 2
    # a cap too small to ever finish: censored
    result = explore(model, options, 0, max_episodes=5, step_cap=2)
    assert result.episodes is None and result.episodes_run == 5 and result.completed == 0


def test_transfer_sources() -> None:
    target = "rice-pilaf"
    macros = macros_for(target)
    available = set(task_model(target).actions)
    assert all(m.applicable(available) for m in macros)
    options = tuple(((a,),) for a in dictionary())
    q = source_q("garlic-bread", options)
    model = task_model("garlic-bread")
    for state, allowed in model.allowed.items():
        if state == model.full:
            continue
        for i, ((action,),) in enumerate(options):
            assert (q[state][i] > -0.5) == (action in allowed)
    prior = aggregate(["garlic-bread", "risotto"], options)
    assert START in prior and all(v <= 0 for row in prior.values() for v in row)


def test_tiny_run_is_deterministic(tmp_path: Path) -> None:
    trials = make_trials(2, 5)
    small = [
        type(t)(t.index, t.seed, {**t.params, "max_episodes": 300, "step_cap": 200}) for t in trials
    ]  # fmt: skip
    first = [run_trial(t) for t in small]
    assert first == [run_trial(t) for t in small]
    assert set(first[0]["conditions"]) == set(CONDITIONS) - set(MACRO_CONDITIONS)
    assert list(first[0]["readings"]) == [r.name for r in READINGS]
    assert all(set(runs) == set(MACRO_CONDITIONS) for runs in first[0]["readings"].values())
    assert run_condition("rice-pilaf", "cchtn", 3, max_episodes=300) == run_condition(
        "rice-pilaf", "cchtn", 3, max_episodes=300
    )
    a = run_experiment("transfer", trials=2, seed=1, output=tmp_path / "a", progress=False)
    b = run_experiment("transfer", trials=2, seed=1, output=None, progress=False)
    assert a.metrics == b.metrics
    assert check_quoted("supportive reproduce transfer -n 2 --seed 1", tmp_path / "a") >= 1  # docs/experiments.md
    metrics = json.loads((tmp_path / "a" / "metrics.json").read_text())
    assert metrics["conditions"]["none"]["episodes"]["n"] == 2
    assert metrics["readings"] == ["any-order", "fixed-order"]
    for p in metrics["pairs"]:
        assert p["wins"] + p["ties"] + p["losses"] == p["trials"] == 2
    assert {(p["first"], p["second"]) for p in metrics["pairs"]} >= {
        (column("cchtn", r), "q") for r in metrics["readings"]
    } | {("cchtn:any-order", "cchtn:fixed-order")}
    assert "timing" not in json.dumps(metrics)
    for png in ("iterations.png", "tasks.png"):
        assert (tmp_path / "a" / png).read_bytes().startswith(PNG_SIGNATURE)
    report = (tmp_path / "a" / "report.md").read_text()
    assert CLAIM in report and "(c) Q-function + CC-HTN macros" in report


def test_any_order_macros_perform_every_admissible_order(monkeypatch: pytest.MonkeyPatch) -> None:
    target = next(t for t in transfer_names() if any(m.count_sequences() > 2 for m in macros_for(t)))
    macro = next(m for m in macros_for(target) if m.count_sequences() > 2)
    fixed, anything = macro_option(macro, "fixed"), macro_option(macro, "any")
    assert fixed == (macro.actions,)
    assert len(anything) == macro.count_sequences() == len(set(anything)) and macro.actions in anything
    assert all(admits(macro.node, to_leaves(seq)) for seq in anything)
    # the explorer draws among them (seeded): over a few runs on the task, more than one order is performed
    model = task_model(target)
    performed: set[tuple[str, ...]] = set()
    real = execute

    def spy(model_: TaskModel, state: int, sequence: tuple[str, ...], *rest: Any) -> Any:
        if len(sequence) > 1:
            performed.add(sequence)
        return real(model_, state, sequence, *rest)

    module = importlib.import_module("supportive.experiments.transfer.explore")
    monkeypatch.setattr(module, "execute", spy)
    options = (*tuple(((a,),) for a in dictionary()), anything)
    explore(model, options, 1, max_episodes=60, step_cap=100, epsilon=0.5)
    assert len(performed) > 1 and performed <= set(anything)


def _value_iteration(name: str, options: Sequence[Option]) -> dict[int, float]:
    """The oracle: plain value iteration (sweeps until nothing moves) over the task's states, each option
    worth the mean over its sequences."""
    model = task_model(name)
    value = {s: 0.0 for s in model.allowed}
    for _ in range(500):
        change = 0.0
        for state in model.allowed:
            if state == model.full:
                continue
            q = []
            for option in options:
                worths = []
                for sequence in option:
                    w = _sequence_value(model, state, sequence, value)
                    worths.append(FAIL + 0.9 * value[state] if w is None else w)
                q.append(sum(worths) / len(worths))
            best = max(q)
            change = max(change, abs(best - value[state]))
            value[state] = best
        if change < 1e-12:
            break
    return value


def test_source_q_with_any_order_macros_is_the_value_iteration_fixed_point() -> None:
    # aglio-e-olio's dictionary (the other tasks' macros, any order) on a source task, bruschetta, where some
    # macros' orders start with an allowed action and some with a failing one
    name = "bruschetta"
    options = transfer_initial("aglio-e-olio", True, "max", PRIOR_SCALE, "any")[0]
    q = source_q(name, options)
    oracle = _value_iteration(name, options)
    model = task_model(name)
    mixed = 0
    for state, row in q.items():
        assert max(row) == pytest.approx(oracle[state], abs=1e-9)
        for option, value in zip(options, row, strict=True):
            worths = [_sequence_value(model, state, seq, oracle) for seq in option]
            mixed += None in worths and any(w is not None for w in worths)
            expected = [FAIL + 0.9 * oracle[state] if w is None else w for w in worths]
            assert value == pytest.approx(sum(expected) / len(expected), abs=1e-9)
    assert mixed > 0  # some macros' orders start with an allowed action, some with a failing one


def test_fixed_order_reading_keeps_one_sequence_per_macro_and_the_old_numbers() -> None:
    trial = make_trials(1, 2, readings=["fixed-order"])[0]
    small = type(trial)(trial.index, trial.seed, {**trial.params, "max_episodes": 300, "step_cap": 200})
    both = type(trial)(trial.index, trial.seed, {**small.params, "readings": ["any-order", "fixed-order"]})
    alone, together = run_trial(small), run_trial(both)
    assert list(alone["readings"]) == ["fixed-order"]
    assert alone["readings"]["fixed-order"] == together["readings"]["fixed-order"]  # readings do not interact
    assert alone["conditions"] == together["conditions"]
