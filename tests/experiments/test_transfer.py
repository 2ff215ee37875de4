from __future__ import annotations

import json
import random

from supportive.examples.food import transfer_names
from supportive.experiments import get, names, run_experiment
from supportive.experiments.plotting import PNG_SIGNATURE
from supportive.experiments.transfer import CLAIM, TaskModel, execute, explore, run_condition, run_trial
from supportive.experiments.transfer.explore import FAIL, NOVELTY, START, STEP
from supportive.experiments.transfer.measure import CONDITIONS, make_trials
from supportive.experiments.transfer.sources import aggregate, dictionary, macros_for, source_q, task_model
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, count_orderings

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


def m_structure(name: str):  # type: ignore[no-untyped-def]
    from supportive.examples.food import load_transfer

    return load_transfer(name).structure


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
    options = tuple((x,) for x in "abcdxyz")
    result = explore(model, options, random.Random(0), max_episodes=200, step_cap=50)
    assert result.episodes is not None and result.paths_known == 2 == result.paths_found
    # with the macro (a, b) the agent still has to find a → c → b → d with primitives
    result = explore(model, (*options, ("a", "b")), random.Random(0), max_episodes=200, step_cap=50)
    assert result.episodes is not None and result.paths_known == 2
    # a cap too small to ever finish: censored
    result = explore(model, options, random.Random(0), max_episodes=5, step_cap=2)
    assert result.episodes is None and result.episodes_run == 5 and result.completed == 0


def test_transfer_sources() -> None:
    target = "rice-pilaf"
    macros = macros_for(target)
    available = set(task_model(target).actions)
    assert all(m.applicable(available) for m in macros)
    options = tuple((a,) for a in dictionary())
    q = source_q("garlic-bread", options)
    model = task_model("garlic-bread")
    for state, allowed in model.allowed.items():
        if state == model.full:
            continue
        for i, (action,) in enumerate(options):
            assert (q[state][i] > -0.5) == (action in allowed)
    prior = aggregate(["garlic-bread", "risotto"], options)
    assert START in prior and all(v <= 0 for row in prior.values() for v in row)


def test_tiny_run_is_deterministic(tmp_path) -> None:  # type: ignore[no-untyped-def]
    trials = make_trials(2, 5)
    small = [
        type(t)(t.index, t.seed, {**t.params, "max_episodes": 300, "step_cap": 200}) for t in trials
    ]  # fmt: skip
    first = [run_trial(t) for t in small]
    assert first == [run_trial(t) for t in small]
    assert set(first[0]["conditions"]) == set(CONDITIONS)
    assert run_condition("rice-pilaf", "cchtn", 3, max_episodes=300) == run_condition(
        "rice-pilaf", "cchtn", 3, max_episodes=300
    )
    a = run_experiment("transfer", trials=2, seed=1, output=tmp_path / "a", progress=False)
    b = run_experiment("transfer", trials=2, seed=1, output=None, progress=False)
    assert a.metrics == b.metrics
    metrics = json.loads((tmp_path / "a" / "metrics.json").read_text())
    assert metrics["conditions"]["none"]["episodes"]["n"] == 2
    assert "timing" not in json.dumps(metrics)
    for png in ("iterations.png", "tasks.png"):
        assert (tmp_path / "a" / png).read_bytes().startswith(PNG_SIGNATURE)
    report = (tmp_path / "a" / "report.md").read_text()
    assert CLAIM in report and "(c) Q-function + CC-HTN macros" in report
