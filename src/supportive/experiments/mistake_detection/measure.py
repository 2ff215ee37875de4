"""Mistake-detection trials: a generated task (the threshold is chosen on these), or one CaptainCook4D recipe
scored leaving one recording out (reported afterwards, at the chosen threshold and along the curve)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from supportive.errors import TaskFileError
from supportive.evaluation.mistakes import (
    DETECTOR,
    METHODS,
    REFERENCE,
    MethodScores,
    MistakeEvaluation,
    detection_model,
    evaluate_mistakes,
)
from supportive.experiments.trials import Trial, spawn_trials
from supportive.generate.mistakes import PROFILES, MistakeKind, inject, random_known_task
from supportive.inference.mistakes import MistakeDetector
from supportive.io.captaincook import load_captaincook

__all__ = [
    "DEFAULT_TRIALS",
    "GENERATED",
    "KINDS",
    "POSITIVES",
    "RECIPES",
    "SIZES",
    "TEST",
    "THRESHOLDS",
    "TRAIN",
    "choose",
    "make_trials",
    "run_trial",
    "summarize",
]

GENERATED = 30
"""Generated tasks of a full run (the profiles in turn)."""
RECIPES = 24
DEFAULT_TRIALS = GENERATED + RECIPES
"""Trials of a full run: the generated tasks, then every recipe."""
TRIAL_KINDS = ("generated task", "recipe")
"""What a run needs a trial of each of (its summary compares them)."""
SIZES = (6, 12)
"""Steps per generated task (inclusive range)."""
TRAIN = 20
"""Clean demonstrations each generated task is learned from."""
TEST = 10
"""Held-out executions per generated task: this many clean, and this many with each kind of mistake."""
KINDS: tuple[MistakeKind, ...] = ("early", "dropped", "repeated")
"""The mistakes put into generated executions: a step moved early, a step skipped, a step repeated."""
THRESHOLDS = (0.1, 0.3, 0.5, 0.7, 0.9, 0.99)
"""The thresholds tried; the default is chosen among them (:func:`choose`)."""
POSITIVES = ("order", "missing")
"""The CaptainCook4D labels counted as mistakes to find (the rest are reported apart)."""


def make_trials(trials: int, seed: int) -> tuple[Trial, ...]:
    """Generated tasks first (the profiles in turn), then the recipes; fewer trials keep the proportion."""
    recipes = max(1, min(RECIPES, round(trials * RECIPES / (GENERATED + RECIPES))))
    params: list[dict[str, Any]] = [
        {"kind": "generated", "profile": PROFILES[i % len(PROFILES)]} for i in range(trials - recipes)
    ]
    params += [{"kind": "recipe", "recipe": i} for i in range(recipes)]
    return spawn_trials(seed, params)


def run_trial(trial: Trial) -> dict[str, Any]:
    """One generated task at every threshold, or one recipe left one recording out: each fold learned from all
    the other recordings (``sums``), and from the correct ones among them (``sums_correct``; None when the
    recipe has fewer than two); the recipe's published graph scored beside them (:data:`REFERENCE`)."""
    if trial.params["kind"] == "generated":
        return {"index": trial.index, "kind": "generated", **_generated(trial)}
    recipe = load_captaincook(errors=True)[int(trial.params["recipe"])]
    evaluation = evaluate_mistakes(recipe.spec, thresholds=THRESHOLDS, positives=POSITIVES, truth=recipe.published)
    try:
        correct: dict[str, Any] | None = _sums(
            evaluate_mistakes(
                recipe.spec, thresholds=THRESHOLDS, positives=POSITIVES, learn_from="correct", truth=recipe.published
            )
        )
    except TaskFileError:  # the only refusal left once the run above passed: fewer than two correct recordings
        correct = None
    return {
        "index": trial.index,
        "kind": "recipe",
        "recipe": recipe.name,
        "held_out": evaluation.held_out,
        "sums": _sums(evaluation),
        "sums_correct": correct,
    }


def _sums(evaluation: MistakeEvaluation) -> dict[str, Any]:
    """The counts of the detector at each threshold and of each baseline (and the reference), as plain data."""
    sums = {str(t): vars(scores) for t, scores in evaluation.detector.items()}
    return sums | {name: vars(scores) for name, scores in evaluation.methods.items()}


def _generated(trial: Trial) -> dict[str, Any]:
    rng = trial.rng()
    profile = trial.params["profile"]
    task = random_known_task(profile, int(rng.integers(SIZES[0], SIZES[1] + 1)), rng)
    model = detection_model([task.sample(rng) for _ in range(TRAIN)])
    clean = [task.sample(rng) for _ in range(TEST)]
    mistaken = {kind: inject([task.sample(rng) for _ in range(TEST)], kind, 1.0, task.admits, rng) for kind in KINDS}
    out: dict[str, Any] = {"profile": profile, "thresholds": {}}
    for threshold in THRESHOLDS:
        detector = MistakeDetector(model, threshold=threshold)
        flagged = steps = 0
        for demo in clean:
            detector.reset()
            flagged += sum(detector.observe(a).mistake for a in demo)
            steps += len(demo)
        kinds: dict[str, list[int]] = {}
        delays: list[int] = []
        for kind, (demos, injected) in mistaken.items():
            found = 0
            for mistake in injected:
                delay = _found(detector, demos[mistake.demonstration], kind, mistake.action, mistake.position)
                if delay is not None:
                    found += 1
                    delays += [delay] if kind == "dropped" else []
            kinds[kind] = [found, len(injected)]
        out["thresholds"][str(threshold)] = {"clean": [flagged, steps], "kinds": kinds, "delays": delays}
    return out


def _found(detector: MistakeDetector, demo: Sequence[str], kind: str, action: str, position: int) -> int | None:
    """Steps from the mistake to the verdict that catches it (None: missed). A step moved early or repeated is
    caught when it is flagged; a skipped step when a verdict names it (the task's end included)."""
    detector.reset()
    for step, done in enumerate(demo):
        verdict = detector.observe(done)
        if kind != "dropped" and step == position:
            return 0 if verdict.mistake else None
        if kind == "dropped" and verdict.mistake and action in verdict.skipped + verdict.prerequisites:
            return step - position
    if kind == "dropped" and action in detector.finish().skipped:
        return len(demo) - position
    return None


def choose(generated: Mapping[str, Mapping[str, Any]]) -> float | None:
    """The procedure that picks the default threshold on generated tasks: among the thresholds that flag at
    most 1 % of the steps of clean executions, the one with the best worst recall over the kinds of mistake;
    ties go to the threshold nearest 0.5 (a miss and a false alarm weighed alike). None when none qualifies."""
    qualified = [float(t) for t, row in generated.items() if row["false_alarms"] <= 0.01]
    if not qualified:
        return None
    best = max(generated[str(t)]["worst_recall"] for t in qualified)
    return min((t for t in qualified if generated[str(t)]["worst_recall"] == best), key=lambda t: (abs(t - 0.5), t))


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Generated: per threshold, false alarms and recall per kind; the chosen threshold. CaptainCook4D: every
    method's scores summed over recipes, the detector at the chosen threshold and along the curve."""
    generated = [r for r in results if r["kind"] == "generated"]
    table: dict[str, Any] = {}
    for threshold in THRESHOLDS:
        key = str(threshold)
        flagged = sum(r["thresholds"][key]["clean"][0] for r in generated)
        steps = sum(r["thresholds"][key]["clean"][1] for r in generated)
        recall = {
            kind: _share(sum(r["thresholds"][key]["kinds"][kind][0] for r in generated),
                         sum(r["thresholds"][key]["kinds"][kind][1] for r in generated))
            for kind in KINDS
        }
        delays = [d for r in generated for d in r["thresholds"][key]["delays"]]
        table[key] = {
            "false_alarms": _share(flagged, steps),
            "recall": recall,
            "worst_recall": min(recall.values()) if recall else 0.0,
            "skip_delay": round(sum(delays) / len(delays), 4) if delays else None,
        }
    chosen = choose(table) if generated else None
    recipes = [r for r in results if r["kind"] == "recipe"]
    captaincook: dict[str, Any] = {}
    if recipes:
        at = str(chosen if chosen is not None else 0.5)
        captaincook = {
            "recipes": len(recipes),
            "held_out": sum(int(r["held_out"]) for r in recipes),
            "threshold": float(at),
            **_methods([r["sums"] for r in recipes], at),
        }
        correct = [r["sums_correct"] for r in recipes if r.get("sums_correct") is not None]
        if correct:
            captaincook["learned_from_correct"] = {"recipes": len(correct), **_methods(correct, at)}
    return {"generated": table, "chosen": chosen, "captaincook": captaincook}


def _methods(sums: Sequence[Mapping[str, Any]], at: str) -> dict[str, Any]:
    """The recipes' counts summed: every method's scores (the detector at threshold ``at``; the reference
    last, when the recipes have it) and the detector's curve over the thresholds."""
    others = [*METHODS[1:], *([REFERENCE] if all(REFERENCE in row for row in sums) else [])]
    summed = {name: _summed([row[name] for row in sums]) for name in (*(str(t) for t in THRESHOLDS), *others)}
    return {
        "methods": {DETECTOR: summed[at].as_dict(), **{n: summed[n].as_dict() for n in others}},
        "curve": {str(t): summed[str(t)].as_dict() for t in THRESHOLDS},
    }


def _share(part: int, whole: int) -> float:
    return round(part / whole, 6) if whole else 0.0


def _summed(rows: Sequence[Mapping[str, Any]]) -> MethodScores:
    total = MethodScores()
    for row in rows:
        total.merge(MethodScores(**row))
    return total
