"""The mistake-detection experiment: trials, the procedure that picks the threshold, the summary, the plot."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from tests.evaluation.test_mistake_scores import TEA_RULES, _tea

from supportive.evaluation.mistakes import DETECTOR, METHODS, REFERENCE, evaluate_mistakes
from supportive.experiments import get
from supportive.experiments.mistake_detection.measure import (
    GENERATED,
    KINDS,
    RECIPES,
    THRESHOLDS,
    choose,
    make_trials,
    run_trial,
    summarize,
)
from supportive.experiments.mistake_detection.report import _alike, findings, plots, report
from supportive.inference.mistakes import DEFAULT_THRESHOLD


def test_a_full_run_has_the_generated_tasks_then_every_recipe() -> None:
    trials = make_trials(get("mistake-detection").default_trials, 0)
    assert [t.params["kind"] for t in trials] == ["generated"] * GENERATED + ["recipe"] * RECIPES
    assert [t.params["recipe"] for t in trials[GENERATED:]] == list(range(RECIPES))


def _row(recall: float, alarms: float) -> dict[str, Any]:
    return {"false_alarms": alarms, "worst_recall": recall}


def test_choose_is_the_best_worst_recall_among_quiet_thresholds_nearest_a_half() -> None:
    table = {"0.1": _row(1.0, 0.02), "0.3": _row(0.95, 0.0), "0.5": _row(0.95, 0.0), "0.9": _row(0.9, 0.0)}
    assert choose(table) == 0.5
    assert choose({"0.1": _row(1.0, 0.02)}) is None


def test_the_default_threshold_is_among_those_tried() -> None:
    assert DEFAULT_THRESHOLD in THRESHOLDS


def test_a_generated_trial_and_a_recipe_summarise_and_plot(tmp_path: Path) -> None:
    generated = run_trial(make_trials(get("mistake-detection").default_trials, 0)[0])
    assert set(generated["thresholds"]) == {str(t) for t in THRESHOLDS}
    for row in generated["thresholds"].values():
        assert set(row["kinds"]) == set(KINDS) and row["clean"][1] > 0
    sums = {}
    for learn_from in ("all", "correct"):
        tea = evaluate_mistakes(
            _tea(), thresholds=THRESHOLDS, positives=("order", "missing"), learn_from=learn_from, truth=TEA_RULES
        )
        sums[learn_from] = {str(t): vars(s) for t, s in tea.detector.items()} | {n: vars(s) for n, s in tea.methods.items()}
    recipe = {"index": 1, "kind": "recipe", "recipe": "tea", "held_out": tea.held_out, "sums": sums["all"], "sums_correct": sums["correct"]}
    fewer = {**recipe, "index": 2, "recipe": "few correct", "sums_correct": None}  # fewer than two correct recordings
    metrics = summarize([generated, recipe, fewer])
    assert metrics["chosen"] in THRESHOLDS
    cc = metrics["captaincook"]
    assert cc["held_out"] == 24 and list(cc["methods"]) == [*METHODS, REFERENCE]  # the published graph last
    assert set(cc["curve"]) == {str(t) for t in THRESHOLDS}
    assert cc["methods"][DETECTOR]["positives"] == 4  # twice: the early pour and the skipped steep
    correct = cc["learned_from_correct"]
    assert correct["recipes"] == 1 and list(correct["methods"]) == [*METHODS, REFERENCE]
    assert correct["methods"][DETECTOR]["positives"] == 2 and set(correct["curve"]) == {str(t) for t in THRESHOLDS}
    text = report(metrics)
    assert "Chosen: **" in text and "precondition" in text and "Learned from the correct recordings only (1 recipes)" in text
    assert len(findings(metrics)) == 3  # generated; CaptainCook4D learned from all, from correct
    assert "published graph" in text
    (picture,) = plots(metrics, tmp_path)
    assert picture.name == "precision-recall.png" and picture.stat().st_size > 0


def test_the_published_graph_is_shown_but_is_no_baseline_to_beat() -> None:
    """Summed only when every recipe has it; the detector is judged against the best *learned* baseline even
    when the published graph scores higher (no robot knows it)."""
    tea = evaluate_mistakes(_tea(), thresholds=THRESHOLDS, positives=("order", "missing"), truth=TEA_RULES)
    sums = {str(t): vars(s) for t, s in tea.detector.items()} | {n: vars(s) for n, s in tea.methods.items()}
    recipe = {"kind": "recipe", "recipe": "tea", "held_out": tea.held_out, "sums": sums, "sums_correct": None}
    without = {**recipe, "sums": {k: v for k, v in sums.items() if k != REFERENCE}}
    assert REFERENCE in summarize([recipe])["captaincook"]["methods"]
    assert REFERENCE not in summarize([recipe, without])["captaincook"]["methods"]
    metrics = summarize([recipe])
    methods = metrics["captaincook"]["methods"]
    methods[REFERENCE]["f1"] = 1.0
    (finding,) = findings(metrics)
    best = max(methods[name]["f1"] for name in METHODS[1:])
    assert f"/ {best:.3f} (" in finding.values[0][1]


def test_thresholds_giving_one_point_are_labelled_once_as_a_run() -> None:
    points = [(0.2, 0.5), (0.2, 0.5), (0.3, 0.4), (0.2, 0.5)]
    assert _alike(points, ["0.1", "0.3", "0.5", "0.7"]) == [((0.2, 0.5), "0.1–0.3"), ((0.3, 0.4), "0.5"), ((0.2, 0.5), "0.7")]
