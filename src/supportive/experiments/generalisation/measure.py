"""Generalisation trials: one generated task, or one CaptainCook4D recipe, measured with both learners; or one
generated task of a size the slip settings were not chosen on, with mistakes put in (the slip check)."""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from supportive.experiments.captaincook.recipes import FEW_SHOT
from supportive.experiments.learner_settings import measure as slip_settings
from supportive.experiments.learner_settings.spread import f1_scores
from supportive.experiments.statistics import mean_ci, ratio_ci
from supportive.experiments.trials import Trial, spawn_trials
from supportive.generate import random_structure
from supportive.generate.habits import PEOPLE
from supportive.generate.mistakes import KINDS, PROFILES
from supportive.io.captaincook import load_captaincook
from supportive.learning import HTNLearner
from supportive.learning.graph_edges import edge_scores
from supportive.learning.precedence import implied_precedences, precedence_scores
from supportive.learning.selection import held_out_log_likelihoods
from supportive.tasks.htn import HTN, count_orderings, iter_orderings, sample_ordering, to_leaves

__all__ = [
    "DEFAULT_TRIALS",
    "LEARNERS",
    "SLIP_CASES",
    "SLIP_SIZES",
    "SLIP_TASKS",
    "SYNTHETIC",
    "make_trials",
    "run_trial",
    "summarize",
]

SYNTHETIC = 300
"""Generated tasks of a full run (half of each profile)."""
SLIP_SIZES: tuple[tuple[int, int], ...] = ((3, 5), (13, 20), (21, 30))
"""Steps per task of the slip check (inclusive ranges): sizes on either side of the 6–12 the slip settings were
chosen on (``learner-settings``), where settings that fitted their sizes would show it."""
SLIP_CASES = (*KINDS, "none")
"""What the slip check puts into a tenth of a task's demonstrations: each kind of mistake, or nothing."""
SLIP_TASKS = 12
"""Generated tasks per size, number of demonstrations and case of the slip check (a full run): a sample size,
not a setting (two of each profile by each kind of people)."""
SLIP_TRIALS = len(SLIP_SIZES) * len(slip_settings.DEMONSTRATIONS) * len(SLIP_CASES) * SLIP_TASKS
DEFAULT_TRIALS = SYNTHETIC + 24 + SLIP_TRIALS
"""Trials of a full run: the generated tasks, the 24 recipes, then the slip check's tasks."""
TRIAL_KINDS = ("generated task", "recipe", "task of another size")
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
    """Trials 0..: generated tasks (profiles alternating), then the 24 recipes, then the slip check's tasks
    (cycling through size × number of demonstrations × case, the profiles and then the kinds of people
    alternating from one cycle to the next); fewer trials keep the same proportion."""
    recipes = min(24, max(1, round(trials * 24 / DEFAULT_TRIALS)))
    checks = max(1, min(trials - recipes - 1, round(trials * SLIP_TRIALS / DEFAULT_TRIALS)))
    synthetic = trials - recipes - checks
    params: list[dict[str, Any]] = [
        {"kind": "synthetic", "profile": ("uniform", "ikea")[i % 2]} for i in range(synthetic)
    ]
    params += [{"kind": "recipe", "recipe": i} for i in range(recipes)]
    cells = list(itertools.product(SLIP_SIZES, slip_settings.DEMONSTRATIONS, SLIP_CASES))
    for i in range(checks):
        sizes, n, case = cells[i % len(cells)]
        turn = i // len(cells)
        profile, people = PROFILES[turn % len(PROFILES)], PEOPLE[turn // len(PROFILES) % len(PEOPLE)]
        params.append(
            {"kind": "slip check", "sizes": list(sizes), "demonstrations": n, "case": case, "profile": profile, "people": people}
        )
    return spawn_trials(seed, params)


def run_trial(trial: Trial) -> dict[str, Any]:
    """Measure one generated task or one recipe with both learners, or one task of the slip check with the
    default learner."""
    kind = trial.params["kind"]
    if kind == "synthetic":
        return {"index": trial.index, "kind": kind, **_synthetic(trial)}
    if kind == "slip check":
        return {"index": trial.index, "kind": kind, **_slip_check(trial)}
    return {"index": trial.index, "kind": "recipe", **_recipe(int(trial.params["recipe"]))}


def _slip_check(trial: Trial) -> dict[str, Any]:
    """A generated task of the trial's size, its demonstrations drawn and given mistakes as ``learner-settings``
    draws them, learned by the default learner: its slips scored as that experiment scores them (under
    ``settings``, ``"default"``)."""
    demos, truth, valid = slip_settings.trial_demonstrations(trial)
    params = trial.params
    slips = HTNLearner().fit(demos).deviations_
    return {
        "sizes": list(params["sizes"]), "demonstrations": len(demos), "case": params["case"],
        "profile": params["profile"], "people": params["people"], "steps": sum(len(d) for d in demos),
        "mistakes": len(truth), "settings": {"default": slip_settings.slip_counts(slips, params["case"], demos, truth, valid)},
    }


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
    checks = [r for r in results if r["kind"] == "slip check"]
    out: dict[str, Any] = {"synthetic": {}, "slips": {}, "captaincook": {}, "tasks": [dict(r) for r in results]}
    if checks:
        out["slip_sizes"] = [
            {
                "steps": [low, high],
                "people": {
                    people: _slip_sizes([r for r in checks if tuple(r["sizes"]) == (low, high) and r["people"] == people])
                    for people in PEOPLE
                    if any(tuple(r["sizes"]) == (low, high) and r["people"] == people for r in checks)
                },
            }
            for low, high in sorted({tuple(r["sizes"]) for r in checks})
        ]
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


def _slip_sizes(tasks: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """The slip check's tasks of one size by one kind of people: precision, recall and mistakes put in per kind
    (pooling the numbers of demonstrations; ``cells``: apart for each number, as ``learner-settings`` has
    them), and on the clean tasks the share of their steps reported and how many had any report."""
    kinds = {}
    for kind in KINDS:
        cell = [t for t in tasks if t["case"] == kind]
        counts = {k: sum(t["settings"]["default"][k] for t in cell) for k in ("reported", "right", "found")}
        mistakes = sum(t["mistakes"] for t in cell)
        precision, recall, _ = f1_scores(counts["reported"], counts["right"], counts["found"], mistakes)
        kinds[kind] = {"precision": round(precision, 4), "recall": round(recall, 4), "mistakes": mistakes, "tasks": len(cell)}
    clean = [t for t in tasks if t["case"] == "none"]
    steps = sum(t["steps"] for t in clean)
    reported = sum(t["settings"]["default"]["reported"] for t in clean)
    return {
        "kinds": kinds,
        "cells": slip_settings.slip_cells(tasks, "default"),
        "clean_tasks": len(clean),
        "clean_steps": steps,
        "clean_flagged": round(reported / steps, 6) if steps else 0.0,
        "clean_tasks_flagged": sum(t["settings"]["default"]["wrong_tasks"] for t in clean),
    }


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
