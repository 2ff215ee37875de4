"""The estimator contract (docs/architecture.md, supportive.estimator), checked over every estimator:
settings in ``__init__`` only, stored under their own names and left unchanged by ``fit``; learned attributes
end in ``_`` and exist only after ``fit``; ``fit`` returns ``self``; an unfitted estimator raises
NotFittedError; a refit is independent of earlier fits; everything random takes a seed."""

from __future__ import annotations

import ast
import importlib
import inspect
import pkgutil
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import supportive
from supportive.errors import LearningError, NotFittedError
from supportive.estimator import Estimator
from supportive.evaluation.baselines import Bigram, MaskedBigram, MostFrequentNotDone
from supportive.examples import load
from supportive.inference import FlatHMM, HierarchicalHMM, ObservationModel, ProgressHMM, StepPredictor
from supportive.inference.bigram import OpenBigram, TransitionCounts
from supportive.inference.synthetic import synthetic_stream
from supportive.language.demonstrated import BehaviorRecorder
from supportive.language.states import TaskStates
from supportive.learning import HTNLearner
from supportive.learning.learner import Mode
from supportive.planning import SupportPlanner, SupportProblem
from supportive.tasks.behaviors import SupportiveBehavior
from supportive.tasks.htn import HTN, ActionNode, ChainNode, CliqueNode

A_DEMOS = [["knife", "carrots", "celery"], ["knife", "celery", "carrots"]] * 2
B_DEMOS = [["a", "b", "c", "d"], ["b", "a", "c", "d"], ["a", "b", "d", "c"], ["b", "a", "d", "c"]]
A_HTN = HTN("a", (ChainNode((ActionNode("x"), CliqueNode((ActionNode("y"), ActionNode("z"))))),))
B_HTN = HTN("b", (ChainNode((ActionNode("y"), ActionNode("x"), ActionNode("z"))),))
EVENTS = ObservationModel({a: {f"see-{a}": 0.9} for a in "xyz"}, noise=0.05)


def _labelled(htn: HTN, seed: int) -> tuple[list[list[frozenset[str]]], list[list[str]]]:
    """Contact-event streams of ``htn`` and the action at each moment."""
    rng = np.random.default_rng(seed)
    sequences, labels = [], []
    for _ in range(6):
        stream = synthetic_stream(htn.roots[0], EVENTS, seed=rng)
        sequences.append(list(stream.observations))
        labels.append([a for a, _ in stream.truth])
    return sequences, labels


@cache
def _chair() -> tuple[TaskStates, SupportiveBehavior, list[str]]:
    chair = TaskStates.of(load("ikea-chair"))
    screws = next(b for b in chair.spec.behaviors if b.name == "give-screws")
    done = list(chair.spec.demonstrations[0].actions[:22])
    return chair, screws, done


@cache
def _table() -> tuple[Any, tuple[Any, ...]]:
    from supportive.envs.circuits.scenario import thesis_scenario

    scenario = thesis_scenario(1, environments=5)
    return scenario.world, tuple(scenario.plans())


@dataclass(frozen=True)
class Case:
    """One estimator: how to make it, fit it on two data sets, use it, and read what it learned."""

    name: str
    make: Callable[[], Any]
    fit_a: Callable[[Any], Any]
    fit_b: Callable[[Any], Any]
    use: Callable[[Any], Any]
    learned: Callable[[Any], Any]


def _htn_learner(mode: Mode) -> Case:
    return Case(
        f"HTNLearner-{mode}",
        lambda: HTNLearner(mode=mode),
        lambda e: e.fit(A_DEMOS, "a"),
        lambda e: e.fit(load("blocks-v")),
        lambda e: e.htn_,
        lambda e: (e.htn_, e.names_, e.task_, e.labelled_, e.deviations_),
    )


def _hmm(kind: type[FlatHMM] | type[HierarchicalHMM] | type[ProgressHMM]) -> Case:
    def use(e: Any) -> Any:
        return e.filter().update({"see-x"}).subgoals

    def learned(e: Any) -> Any:
        running = e.filter()
        return (e.mean_duration_, e.observations_.table.tolist(), [running.update({"see-y"}).subgoals.tolist() for _ in range(3)])

    return Case(
        kind.__name__,
        lambda: kind(A_HTN if kind is not ProgressHMM else B_HTN, EVENTS),
        lambda e: e.fit(*_labelled(A_HTN, 1)),
        lambda e: e.fit(*_labelled(A_HTN, 2)),
        use,
        learned,
    )


def _baseline(kind: type[TransitionCounts]) -> Case:
    return Case(
        kind.__name__,
        kind,
        lambda e: e.fit(A_DEMOS),
        lambda e: e.fit(B_DEMOS),
        lambda e: e.next_step([]),
        lambda e: (e.next_step([]), e.next_step(["a"]), dict(e.transitions_), e.ends_),
    )


def _recorder() -> Case:
    def make() -> BehaviorRecorder:
        chair, screws, _ = _chair()
        return BehaviorRecorder(chair, screws)

    def fit_a(e: BehaviorRecorder) -> BehaviorRecorder:
        done = _chair()[2]
        return e.fit([done], stops=[[*done, "screw_seat_left"]])

    def fit_b(e: BehaviorRecorder) -> BehaviorRecorder:
        return e.fit([_chair()[2][:12]])

    return Case(
        "BehaviorRecorder",
        make,
        fit_a,
        fit_b,
        lambda e: e.behavior_,
        lambda e: (e.behavior_, e.starts_, e.stops_, e.termination_),
    )


def _planner() -> Case:
    def fit(plans: slice) -> Callable[[Any], Any]:
        def go(e: SupportPlanner[Any, Any, Any]) -> Any:
            world, known = _table()
            return e.fit(SupportProblem.of(world, known[plans]))

        return go

    def use(plans: slice) -> Callable[[Any], Any]:
        def go(e: SupportPlanner[Any, Any, Any]) -> Any:
            world, known = _table()
            return e.decide(SupportProblem.of(world, known[plans]), 0)

        return go

    return Case(
        "SupportPlanner",
        lambda: SupportPlanner(environments=5),
        fit(slice(0, 3)),
        fit(slice(3, 6)),
        use(slice(0, 3)),
        lambda e: (e.baseline_, e.weights_, e.penalty_, use(slice(3, 6))(e).chosen),
    )


CASES = [
    _htn_learner("general"),
    _htn_learner("strict"),
    _hmm(FlatHMM),
    _hmm(HierarchicalHMM),
    _hmm(ProgressHMM),
    Case(
        "StepPredictor",
        lambda: StepPredictor(slip=0.05),
        lambda e: e.fit(A_DEMOS),
        lambda e: e.fit(B_DEMOS),
        lambda e: e.next_step([]),
        lambda e: (e.next_step([]), e.next_step(["a", "b"]), e.learner_.htn_),
    ),
    _baseline(Bigram),
    _baseline(MaskedBigram),
    _baseline(MostFrequentNotDone),
    _baseline(OpenBigram),
    Case(
        "TransitionCounts",
        TransitionCounts,
        lambda e: e.fit(A_DEMOS),
        lambda e: e.fit(B_DEMOS),
        lambda e: e.transitions_["<start>"],
        lambda e: (dict(e.transitions_), e.actions_, e.most_, e.ends_),
    ),
    _recorder(),
    _planner(),
]
IDS = [c.name for c in CASES]


def _settings(estimator: Any) -> dict[str, Any]:
    return {k: v for k, v in vars(estimator).items() if not k.startswith("_") and not k.endswith("_")}


def _same(a: Any, b: Any) -> bool:
    if a is b:
        return True
    try:
        return bool(a == b)
    except ValueError:  # numpy arrays
        return bool(np.array_equal(a, b))


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_init_stores_its_settings_and_learns_nothing(case: Case) -> None:
    estimator = case.make()
    assert isinstance(estimator, Estimator)
    assert not estimator.fitted
    assert [name for name in vars(estimator) if name.endswith("_")] == []
    for name, parameter in inspect.signature(type(estimator).__init__).parameters.items():
        if name != "self" and parameter.kind not in (inspect.Parameter.VAR_KEYWORD, inspect.Parameter.VAR_POSITIONAL):
            assert hasattr(estimator, name), f"setting {name} is not stored under its name"


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_using_an_unfitted_estimator_raises_not_fitted(case: Case) -> None:
    with pytest.raises(NotFittedError, match="not fitted"):
        case.use(case.make())


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_fit_returns_self_learns_only_underscored_attributes_and_keeps_the_settings(case: Case) -> None:
    estimator = case.make()
    before = _settings(estimator)
    assert case.fit_a(estimator) is estimator
    assert estimator.fitted
    after = _settings(estimator)
    assert after.keys() == before.keys(), "fit added a public attribute that does not end in _"
    assert all(_same(before[k], after[k]) for k in before), "fit changed a setting"
    case.use(estimator)


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_a_refit_is_independent_of_earlier_fits(case: Case) -> None:
    refitted = case.fit_b(case.fit_a(case.make()))
    fresh = case.fit_b(case.make())
    assert _same(case.learned(refitted), case.learned(fresh))
    assert {k for k in vars(refitted) if k.endswith("_")} == {k for k in vars(fresh) if k.endswith("_")}


class _Broken:
    """An argument a fit cannot read: any use of it raises."""

    def __getattr__(self, name: str) -> Any:
        raise _Planted(name)

    def __iter__(self) -> Any:
        raise _Planted("__iter__")

    def __len__(self) -> int:
        raise _Planted("__len__")


class _Planted(Exception):
    pass


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_a_failed_fit_leaves_the_estimator_unfitted(case: Case) -> None:
    estimator = case.fit_a(case.make())
    with pytest.raises(Exception):  # noqa: B017 - whatever each fit raises on an unreadable argument
        estimator.fit(_Broken())
    assert not estimator.fitted
    assert [name for name in vars(estimator) if name.endswith("_")] == []
    with pytest.raises(NotFittedError):
        case.use(estimator)
    assert _same(case.learned(case.fit_b(estimator)), case.learned(case.fit_b(case.make())))


def test_after_a_failed_fit_partial_fit_starts_afresh() -> None:
    learner = HTNLearner()
    with pytest.raises(LearningError, match="no demonstrations"):
        learner.fit([], "t")
    assert not learner.fitted
    learner.partial_fit(["a", "b"])
    assert learner.task_graph_.demonstrations and learner.htn_.admits(["a", "b"])


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_get_params_gives_every_setting_and_makes_an_unfitted_copy(case: Case) -> None:
    estimator = case.fit_a(case.make())
    params = estimator.get_params()
    init = type(estimator).__init__
    names = [n for n in inspect.signature(init).parameters if n != "self"] if init is not object.__init__ else []
    assert list(params)[: len(names)] == names
    copy = type(estimator)(**params)
    assert not copy.fitted
    assert all(_same(copy.get_params()[name], params[name]) for name in names)
    assert _same(case.learned(case.fit_b(copy)), case.learned(case.fit_b(estimator)))


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_set_params_changes_settings_and_refuses_unknown_names(case: Case) -> None:
    estimator = case.make()
    params = estimator.get_params(deep=False)
    assert estimator.set_params(**params) is estimator
    assert all(_same(estimator.get_params()[name], value) for name, value in params.items())
    with pytest.raises(LearningError, match="no setting 'colour'"):
        estimator.set_params(colour="red")


def test_set_params_checks_values_as_init_does() -> None:
    predictor = StepPredictor()
    assert predictor.set_params(backoff=0.3, slip=0.05).get_params()["backoff"] == 0.3
    assert predictor.slip == 0.05
    for bad in ({"backoff": 1.0}, {"slip": 2.0}, {"slip_rate": 0.9}, {"mode": "sideways"}):
        with pytest.raises(LearningError):
            StepPredictor(**bad)
        with pytest.raises(LearningError):
            predictor.set_params(**bad)
    assert predictor.get_params()["backoff"] == 0.3 and predictor.slip == 0.05, "a refused value changed nothing"


def test_settings_are_named_parameters() -> None:
    with pytest.raises(TypeError, match="named parameters"):

        class _Loose(Estimator):  # private: the contract test lists public estimators only
            def __init__(self, **settings: Any) -> None:
                self.settings = settings


@pytest.mark.parametrize("kind", [FlatHMM, HierarchicalHMM, ProgressHMM])
@pytest.mark.parametrize("mean_duration", [float("nan"), float("inf"), 0.5])
def test_a_mean_duration_that_is_no_number_of_steps_is_refused_at_once(
    kind: type[FlatHMM] | type[HierarchicalHMM] | type[ProgressHMM], mean_duration: float
) -> None:
    with pytest.raises(LearningError, match=f"mean_duration .* got {mean_duration}"):
        kind(A_HTN, EVENTS, mean_duration=mean_duration)


def test_every_estimator_is_checked() -> None:
    for package in ("learning", "inference", "language", "evaluation", "planning", "safety", "social"):
        module = importlib.import_module(f"supportive.{package}")
        for info in pkgutil.walk_packages(module.__path__, f"{module.__name__}."):
            if not info.name.endswith(".embeddings"):  # needs torch; defines no estimator
                importlib.import_module(info.name)

    def public(cls: type) -> set[str]:
        found: set[str] = set()
        sub: type
        for sub in cls.__subclasses__():
            found |= public(sub) | ({sub.__name__} if not sub.__name__.startswith("_") else set())
        return found

    checked = {c.name.split("-")[0] for c in CASES}
    assert public(Estimator) == checked


def test_the_observation_model_is_a_model_not_an_estimator() -> None:
    assert not hasattr(ObservationModel, "fit") and not issubclass(ObservationModel, Estimator)
    sequences, labels = _labelled(A_HTN, 3)
    model = ObservationModel.from_labelled(sequences, labels)
    assert set(model.actions) == {"x", "y", "z"}


# ------------------------------------------------------------------ seeds

SRC = Path(supportive.__file__).resolve().parent
LEGACY = {"rand", "randn", "randint", "random", "choice", "shuffle", "permutation", "seed", "normal", "uniform"}


def test_nothing_random_bypasses_the_seed_convention() -> None:
    """No module but seeding.py uses the standard library's ``random`` or numpy's global generator, and no
    generator is made without a seed."""
    found = []
    for path in sorted(SRC.rglob("*.py")):
        if path.name == "seeding.py" or "examples" in path.parts:
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            where = f"{path.relative_to(SRC)}:{getattr(node, 'lineno', 0)}"
            if isinstance(node, ast.Import) and any(a.name == "random" for a in node.names):
                found.append(f"{where}: import random")
            if isinstance(node, ast.ImportFrom) and node.module == "random":
                found.append(f"{where}: from random import")
            if isinstance(node, ast.Attribute) and node.attr in LEGACY:
                value = node.value
                if isinstance(value, ast.Attribute) and value.attr == "random" and isinstance(value.value, ast.Name):
                    found.append(f"{where}: {value.value.id}.random.{node.attr}")
            if (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Attribute)
                and node.func.attr == "default_rng"
                and not node.args
                and not node.keywords
            ):
                found.append(f"{where}: default_rng() without a seed")
    assert found == []


def _draws(seed: Callable[[], Any]) -> list[Any]:
    """What each random entry point gives for a fresh ``seed()`` (each takes the project's Seed)."""
    from supportive.envs.circuits.advice import advise
    from supportive.envs.circuits.scenario import thesis_scenario
    from supportive.evaluation.replay import watch
    from supportive.experiments.transfer.explore import explore
    from supportive.experiments.transfer.sources import dictionary, task_model
    from supportive.generate import generate_task, sample_orderings
    from supportive.safety.contrast import caregiver_contrast
    from supportive.safety.episode import run_episode
    from supportive.tasks.htn import sample_ordering
    from supportive.worlds.household import load_map

    scenario = thesis_scenario(1, environments=5)
    options = tuple(((a,),) for a in dictionary())
    return [
        generate_task(12, seed()).demonstrations,
        sample_orderings(A_HTN.roots[0], 3, seed()),
        sample_ordering(A_HTN.roots[0], seed()),
        run_episode(load_map("playroom"), 0.5, caregiver=True, steps=10, seed=seed()).damage,
        caregiver_contrast(steps=10, seed=seed()).moment,
        [s.subgoal for s in watch(load("ikea-chair"), seed=seed())],
        advise(scenario, scenario.plans()[:3], seed=seed())[0].actions,
        explore(task_model("omelette"), options, seed(), max_episodes=3, step_cap=20).steps,
    ]


def test_the_same_seed_gives_the_same_numbers_and_a_generator_is_taken() -> None:
    assert _draws(lambda: 5) == _draws(lambda: 5)
    assert _draws(lambda: np.random.default_rng(5)) == _draws(lambda: np.random.default_rng(5))
