"""Generalisation trials: one generated task, or one CaptainCook4D recipe, measured with both learners."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from supportive.experiments.captaincook.recipes import FEW_SHOT
from supportive.experiments.statistics import mean_ci, ratio_ci
from supportive.experiments.trials import Trial, spawn_trials
from supportive.generate import random_structure
from supportive.io.captaincook import load_captaincook
from supportive.learning import HTNLearner
from supportive.learning.graph_edges import edge_scores
from supportive.learning.precedence import implied_precedences, precedence_scores
from supportive.learning.selection import held_out_log_likelihoods
from supportive.tasks.htn import HTN, count_orderings, iter_orderings, sample_ordering, to_leaves

__all__ = ["DEFAULT_TRIALS", "LEARNERS", "SYNTHETIC", "make_trials", "run_trial", "summarize"]

SYNTHETIC = 300
"""Generated tasks of a full run (half of each profile)."""
DEFAULT_TRIALS = SYNTHETIC + 24
"""Trials of a full run: the generated tasks, then the 24 recipes."""
TRIAL_KINDS = ("generated task", "recipe")
"""What a run needs a trial of each of (its summary compares them)."""
LEARNERS = ("auto", "general", "strict")
"""The default learner (``auto``: the reading chosen by held-out likelihood), the ``general`` reading alone, and
the thesis's ``strict`` one."""
SIZES = (4, 12)
DEMONSTRATIONS = 4
ORDERINGS_LIMIT = 5000
SLIP_CLEAN, SLIPPED = 16, 4
"""Slips on generated tasks: this many sampled demonstrations, and this many more with one step moved."""


def make_trials(trials: int, seed: int) -> tuple[Trial, ...]:
    """Trials 0..: generated tasks (profiles alternating), then the 24 recipes; fewer trials keep the same
    proportion."""
    recipes = max(1, round(trials * 24 / (SYNTHETIC + 24)))
    synthetic = trials - recipes
    params: list[dict[str, Any]] = [
        {"kind": "synthetic", "profile": ("uniform", "ikea")[i % 2]} for i in range(synthetic)
    ]
    params += [{"kind": "recipe", "recipe": i} for i in range(min(recipes, 24))]
    return spawn_trials(seed, params)


def run_trial(trial: Trial) -> dict[str, Any]:
    """Measure one generated task or one recipe with both learners."""
    if trial.params["kind"] == "synthetic":
        return {"index": trial.index, "kind": "synthetic", **_synthetic(trial)}
    return {"index": trial.index, "kind": "recipe", **_recipe(int(trial.params["recipe"]))}


def _synthetic(trial: Trial) -> dict[str, Any]:
    rng = trial.rng()
    while True:  # redraw until the valid orderings can be listed
        structure = random_structure(int(rng.integers(SIZES[0], SIZES[1] + 1)), rng, profile=trial.params["profile"])
        if count_orderings(structure) <= ORDERINGS_LIMIT:
            break
    valid = [[a for a, _ in o] for o in iter_orderings(structure)]
    demos = [[a for a, _ in sample_ordering(structure, rng)] for _ in range(DEMONSTRATIONS)]
    out: dict[str, Any] = {"profile": trial.params["profile"], "actions": len(structure.leaves), "orderings": len(valid)}
    for mode in LEARNERS:
        htn = HTNLearner(mode=mode).fit(demos).htn_  # type: ignore[arg-type]
        out[mode] = {**_orderings_scores(htn, valid), "complete": htn.complete}
    clean = [[a for a, _ in sample_ordering(structure, rng)] for _ in range(SLIP_CLEAN)]
    slipped = [_moved_step([a for a, _ in sample_ordering(structure, rng)], rng) for _ in range(SLIPPED)]
    out["slips"] = {
        "clean": _orderings_scores(HTNLearner().fit(clean).htn_, valid),
        "with_slips": _orderings_scores(HTNLearner().fit(clean + slipped).htn_, valid),
        "with_slips_none_set_aside": _orderings_scores(HTNLearner(slips=False).fit(clean + slipped).htn_, valid),
    }
    return out


def _orderings_scores(htn: HTN, valid: Sequence[Sequence[str]]) -> dict[str, float]:
    """Recall of the valid orderings and precision of the admitted ones."""
    admitted = htn.count_orderings()
    hits = sum(htn.admits(o) for o in valid)
    return {"recall": hits / len(valid), "precision": min(1.0, hits / admitted) if admitted else 1.0}


def _moved_step(demo: list[str], rng: np.random.Generator) -> list[str]:
    """``demo`` with one step taken out and put back at a random place (a slip)."""
    step = demo.pop(int(rng.integers(len(demo))))
    demo.insert(int(rng.integers(len(demo) + 1)), step)
    return demo


def _recipe(index: int) -> dict[str, Any]:
    clean = load_captaincook()[index]
    every = load_captaincook(errors=True)[index]
    demos = [d.actions for d in clean.spec.demonstrations]
    # The graph judges orders among its own steps; recordings with errors add performances it lacks (a second
    # blitz, an off-graph step), whose orders it can neither confirm nor refute ("all_precision" counts them).
    graph_steps = {leaf for demo in clean.spec.demonstrations for leaf in to_leaves(demo.actions)}
    half = len(demos) // 2
    out: dict[str, Any] = {"recipe": clean.name, "held_out": len(demos) - half}
    for mode in LEARNERS:
        learner = HTNLearner(mode=mode).fit(demos[:half])  # type: ignore[arg-type]
        # each held-out recording's log-likelihood as the readings are compared (every execution the hierarchy
        # admits equally likely, a refused one explained as noise), and whether it is admitted
        held_out = held_out_log_likelihoods(learner.htn_, demos[half:], learner.slip_rate)
        scores = {}
        for name, recipe in (("error_free", clean), ("with_errors", every)):
            htn = HTNLearner(mode=mode).fit(recipe.spec).htn_  # type: ignore[arg-type]
            implied = implied_precedences(htn)
            judged = {(a, b) for a, b in implied if a in graph_steps and b in graph_steps}
            score = precedence_scores(judged, clean.published)
            everything = precedence_scores(implied, clean.published)
            scores[name] = {"precision": score.precision, "recall": score.recall, "all_precision": everything.precision}
        edges = {}
        for setting, recordings in (("full", clean.spec.demonstrations), ("5-shot", clean.spec.demonstrations[:FEW_SHOT])):
            htn = HTNLearner(mode=mode).fit(clean.spec.with_demonstrations(recordings)).htn_  # type: ignore[arg-type]
            score = edge_scores(implied_precedences(htn), clean.steps, clean.graph_edges)
            edges[setting] = {"precision": score.precision, "recall": score.recall, "f1": score.f1}
        out[mode] = {
            "admitted": sum(ok for _, ok in held_out),
            "held_out_log_likelihood": round(float(np.mean([v for v, _ in held_out])), 6),
            **scores,
            "edges": edges,
        }
    return out


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Means per profile and learner; CaptainCook admission (with its 95 % interval over the recipes), the
    mean log-likelihood of a held-out recording (mean and interval over the recipes), and precedence and
    task-graph scores per learner (the task-graph F1 with its interval, see
    :func:`_edge_summary`)."""
    synthetic = [r for r in results if r["kind"] == "synthetic"]
    recipes = [r for r in results if r["kind"] == "recipe"]
    out: dict[str, Any] = {"synthetic": {}, "slips": {}, "captaincook": {}, "tasks": [dict(r) for r in results]}
    for profile in sorted({r["profile"] for r in synthetic}):
        rows = [r for r in synthetic if r["profile"] == profile]
        out["synthetic"][profile] = {
            mode: {
                "tasks": len(rows),
                "recall": round(float(np.mean([r[mode]["recall"] for r in rows])), 4),
                "precision": round(float(np.mean([r[mode]["precision"] for r in rows])), 4),
                "complete": sum(bool(r[mode]["complete"]) for r in rows),
            }
            for mode in LEARNERS
        }
        out["slips"][profile] = {
            data: {
                metric: round(float(np.mean([r["slips"][data][metric] for r in rows])), 4)
                for metric in ("recall", "precision")
            }
            for data in ("clean", "with_slips", "with_slips_none_set_aside")
        }
    if recipes:
        held = sum(int(r["held_out"]) for r in recipes)
        for mode in LEARNERS:
            admitted = sum(int(r[mode]["admitted"]) for r in recipes)
            out["captaincook"][mode] = {
                "recipes": len(recipes),
                "held_out": held,
                "admitted": admitted,
                "admission": round(admitted / held, 4),
                "admission_interval": _bounds(
                    ratio_ci(
                        [float(r[mode]["admitted"]) for r in recipes],
                        [float(r["held_out"]) for r in recipes],
                        digits=4,
                        bounds=(0.0, 1.0),
                    )
                ),
                "held_out_log_likelihood": mean_ci([r[mode]["held_out_log_likelihood"] for r in recipes], digits=4),
                **{
                    f"{data}_{metric}": round(float(np.mean([r[mode][data][metric] for r in recipes])), 4)
                    for data in ("error_free", "with_errors")
                    for metric in ("precision", "recall", "all_precision")
                },
                "edges": {setting: _edge_summary(recipes, mode, setting) for setting in ("full", "5-shot")},
            }
    return out


def _bounds(summary: Mapping[str, Any]) -> dict[str, Any]:
    """The bounds of a :func:`~supportive.experiments.statistics.mean_ci`-like summary (its mean is reported
    beside it already)."""
    return {"low": summary["low"], "high": summary["high"]}


def _edge_summary(recipes: Sequence[Mapping[str, Any]], mode: str, setting: str) -> dict[str, Any]:
    """The task-graph protocol's means over the recipes, with how sure the F1 is: its 95 % interval over the
    recipes (``f1_interval``; a recipe is a draw of the benchmark) and, but for the strict learner, the mean
    paired difference from strict per recipe with its interval (``f1_minus_strict``)."""
    f1 = [float(r[mode]["edges"][setting]["f1"]) for r in recipes]
    summary: dict[str, Any] = {
        metric: round(float(np.mean([r[mode]["edges"][setting][metric] for r in recipes])), 4)
        for metric in ("precision", "recall", "f1")
    }
    summary["f1_interval"] = _bounds(mean_ci(f1, digits=4, bounds=(0.0, 1.0)))
    if mode != "strict":
        strict = [float(r["strict"]["edges"][setting]["f1"]) for r in recipes]
        summary["f1_minus_strict"] = mean_ci([a - b for a, b in zip(f1, strict, strict=True)], digits=4)
    return summary
