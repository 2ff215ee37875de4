"""Online mistake detection (inference/mistakes.py): each kind named with its steps, only the past used, said
once, the task's end, contact events; and the help each kind calls for (language/help.py)."""

from __future__ import annotations

import numpy as np
import pytest

from supportive.errors import LearningError
from supportive.evaluation.mistakes import detection_model
from supportive.generate.mistakes import inject, random_known_task
from supportive.inference.mistakes import MistakeDetector
from supportive.language.help import help_for, mistake_record, warning_for
from supportive.tasks.behaviors import BehaviorCategory

TEA = [["boil", "cup", "teabag", "pour", "steep", "serve"], ["cup", "boil", "teabag", "pour", "steep", "serve"]] * 4
TEXTS = {"boil": "boil the water", "cup": "take a cup", "teabag": "put a teabag in", "pour": "pour the water",
         "steep": "let it steep", "serve": "serve the tea"}


@pytest.fixture(scope="module")
def detector() -> MistakeDetector:
    return MistakeDetector(detection_model(TEA))


def _judge(detector: MistakeDetector, steps: list[str]) -> list[tuple[str, bool, str | None, tuple[str, ...]]]:
    detector.reset()
    out: list[tuple[str, bool, str | None, tuple[str, ...]]] = []
    for step in steps:
        verdict = detector.observe(step)
        out.append((step, verdict.mistake, verdict.kind, verdict.prerequisites + verdict.skipped))
    return out


def test_a_correct_execution_is_never_flagged(detector: MistakeDetector) -> None:
    for demo in TEA[:2]:
        assert not any(mistake for _, mistake, _, _ in _judge(detector, demo))
    assert not detector.finish().mistake


def test_each_kind_is_named_with_its_steps(detector: MistakeDetector) -> None:
    skipped = _judge(detector, ["boil", "cup", "teabag", "steep"])  # pour was due and skipped
    assert skipped[-1] == ("steep", True, "missing", ("pour",))
    early = _judge(detector, ["boil", "pour"])  # the cup and the teabag were not yet due
    assert early[-1] == ("pour", True, "out-of-order", ("cup", "teabag"))
    again = _judge(detector, ["boil", "cup", "teabag", "pour", "pour"])
    assert again[-1][1:3] == (True, "repeated")
    unknown = _judge(detector, ["boil", "sugar"])
    assert unknown[-1][1:3] == (True, "unknown-step")


def test_a_step_named_once_is_not_flagged_again_when_done_late(detector: MistakeDetector) -> None:
    verdicts = _judge(detector, ["boil", "cup", "teabag", "steep", "pour", "serve"])
    assert [mistake for _, mistake, _, _ in verdicts] == [False, False, False, True, False, False]


def test_decisions_use_only_the_past(detector: MistakeDetector) -> None:
    steps = ["boil", "cup", "teabag", "steep", "pour", "serve"]
    whole = _judge(detector, steps)
    for cut in range(1, len(steps) + 1):
        assert _judge(detector, steps[:cut]) == whole[:cut]


def test_the_end_names_the_steps_never_done_and_not_named_before(detector: MistakeDetector) -> None:
    _judge(detector, ["boil", "cup", "teabag", "pour", "steep"])
    end = detector.finish()
    assert (end.mistake, end.kind, end.skipped, end.step) == (True, "missing", ("serve",), 6)
    said = _judge(detector, ["boil", "cup", "teabag", "pour", "serve"])
    assert said[-1] == ("serve", True, "missing", ("steep",))
    assert not detector.finish().mistake, "steep was named when serve was done: not again at the end"


def test_the_threshold_is_checked_and_decides(detector: MistakeDetector) -> None:
    with pytest.raises(LearningError):
        MistakeDetector(detector.hmm, threshold=0.0)
    lax = MistakeDetector(detector.hmm, threshold=1.0)
    lax.observe("boil")
    verdict = lax.observe("pour")
    assert verdict.probability < 1.0 or verdict.mistake


def test_contact_events_judge_each_new_subgoal() -> None:
    from supportive.inference import ObservationModel, ProgressHMM
    from supportive.learning import HTNLearner

    events = ObservationModel({a: {f"touch_{a}": 0.9} for a in TEXTS})
    hmm = ProgressHMM(HTNLearner(mode="general").fit(TEA).htn_, events, mean_duration=2.0).fit()
    running = MistakeDetector(hmm)
    judged = [running.update({f"touch_{a}"}) for a in ["boil", "boil", "cup", "cup", "teabag", "teabag", "steep", "steep"]]
    steps = [v for v in judged if v is not None]
    assert [v.action for v in steps] == ["boil", "cup", "teabag", "steep"]
    assert (steps[-1].mistake, steps[-1].kind, steps[-1].skipped) == (True, "missing", ("pour",))


@pytest.mark.parametrize("kind", ["early", "dropped", "repeated"])
def test_generated_mistakes_are_caught_without_false_alarms(kind: str) -> None:
    caught = total = alarms = steps = 0
    for profile, seed in [("ikea", 1), ("uniform", 2), ("partial order", 3)]:
        task = random_known_task(profile, 8, seed=seed)  # type: ignore[arg-type]
        rng = np.random.default_rng(seed)
        running = MistakeDetector(detection_model([task.sample(rng) for _ in range(20)]))
        for demo in (task.sample(rng) for _ in range(5)):
            running.reset()
            alarms += sum(running.observe(a).mistake for a in demo)
            steps += len(demo)
        demos, injected = inject([task.sample(rng) for _ in range(5)], kind, 1.0, task.admits, rng)  # type: ignore[arg-type]
        for mistake in injected:
            running.reset()
            verdicts = [running.observe(a) for a in demos[mistake.demonstration]] + [running.finish()]
            total += 1
            caught += any(v.mistake and v.step - 1 >= mistake.position for v in verdicts)
    assert alarms <= 0.01 * steps and caught >= 0.9 * total, (alarms, steps, caught, total)


def test_help_speaks_of_each_kind_in_the_robots_words(detector: MistakeDetector) -> None:
    said = {}
    for steps in (["boil", "cup", "teabag", "steep"], ["boil", "pour"], ["boil", "boil"], ["boil", "sugar"]):
        detector.reset()
        verdict = [detector.observe(s) for s in steps][-1]
        offered = help_for(verdict, TEXTS)
        assert offered is not None and verdict.kind is not None
        said[verdict.kind] = offered
    assert said["missing"].category is BehaviorCategory.ENHANCING_AWARENESS
    assert said["missing"].say == "You skipped pouring the water: it comes before letting it steep. I will remind you."
    assert said["out-of-order"].category is BehaviorCategory.MATERIALS_RETRIEVAL
    assert "taking a cup and putting a teabag in" in said["out-of-order"].say
    assert said["repeated"].say == "You have already finished boiling the water; once is enough."
    assert "'sugar'" in said["unknown-step"].behavior
    record = mistake_record(verdict, TEXTS)
    assert record["kind"] == "unknown-step" and record["help"]["category"] == "enhancing awareness"  # type: ignore[index]


def test_a_warning_comes_before_a_step_that_cannot_be_undone() -> None:
    warned = warning_for(["pour"], ["serve", "steep"], {"serve"}, TEXTS)
    assert warned is not None and warned.category is BehaviorCategory.TASK_PROGRESSION_GUIDANCE
    assert warned.say == "Before serving the tea: pouring the water is not done yet, and serving the tea cannot be undone."
    assert warning_for([], ["serve"], {"serve"}, TEXTS) is None
    assert warning_for(["pour"], ["steep"], {"serve"}, TEXTS) is None
