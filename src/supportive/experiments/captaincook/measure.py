"""Trials and summary of the CaptainCook4D experiment: learning curves, passive vs active, on real recordings.

One trial = one seed over the recipes (all 24 by default). For each recipe, with K = its error-free recordings:

* **passive**: the recordings, in a trial-seeded random order, are added one at a time to an
  :class:`~supportive.learning.learner.HTNLearner`;
* **active** (``random``, ``distance``, ``connectivity``): a :class:`~supportive.learning.active.TeachingSession`
  is taught K demonstrations by a :class:`~supportive.learning.instructors.SimulatedInstructor` that follows the
  recipe's published graph (a :class:`~supportive.learning.instructors.PartialOrder`); her preferred path is
  one of the recipe's recordings (trial-seeded; the same for every strategy), made valid for the published
  order where it breaks it (:meth:`~supportive.learning.instructors.PartialOrder.linearize`); she heeds queries
  within 3 steps; the learner asks after steps 1, 3 and 5 of every demonstration but the first.

After each demonstration k = 1..K the learned hierarchy's implied "must come before" pairs are scored
against the published ones (precision, recall, F1).
"""

from __future__ import annotations

import functools
import math
import zlib
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from supportive.errors import ExperimentError
from supportive.experiments.active_learning.common import STRATEGIES
from supportive.experiments.captaincook.recipes import compare_recipe
from supportive.experiments.statistics import mean_ci
from supportive.experiments.trials import Trial, spawn_trials
from supportive.io.captaincook import Recipe, load_captaincook
from supportive.learning.active import QuerySchedule, TeachingSession, run_session
from supportive.learning.instructors import PartialOrder, SimulatedInstructor
from supportive.learning.learner import HTNLearner
from supportive.learning.precedence import implied_precedences, precedence_scores
from supportive.tasks.htn import Leaf, to_leaves

__all__ = [
    "CONDITIONS",
    "DEFAULT_TRIALS",
    "HORIZON",
    "METRICS",
    "SCHEDULE",
    "make_trials",
    "partial_order",
    "recipe_rng",
    "run_recipe",
    "run_trial",
    "summarize",
]

CONDITIONS = ("passive", *STRATEGIES)
"""Passive learning, then the three query strategies of §2.2.6."""

METRICS = ("precision", "recall", "f1")

DEFAULT_TRIALS = 10

HORIZON = 3
"""Most steps ahead a query is heeded (§2.2.10.1)."""

SCHEDULE = QuerySchedule(after_steps=(1, 3, 5), max_per_demonstration=3, skip_first_demonstrations=1)
"""The pilot study's schedule for tasks 1 and 2 (§2.2.7): after steps 1, 3, 5; none in the first demonstration."""


def make_trials(trials: int, seed: int, *, recipes: Sequence[str] | None = None) -> tuple[Trial, ...]:
    """``trials`` trials over every recipe, or over ``recipes`` (slugs) only, each with its own seed."""
    chosen = None if recipes is None else tuple(recipes)
    return spawn_trials(seed, [{"recipes": chosen} for _ in range(trials)])


@functools.lru_cache(maxsize=2)
def _recipes(root: str | None) -> tuple[Recipe, ...]:
    return tuple(load_captaincook(None if root is None else Path(root)))


def recipe_rng(trial: Trial, recipe: str) -> np.random.Generator:
    """A recipe's generator within a trial: it depends on the trial's seed and the recipe's name only, not on
    which other recipes the trial runs."""
    seed = trial.seed
    key = (*seed.spawn_key, zlib.crc32(recipe.encode()))
    return np.random.default_rng(np.random.SeedSequence(seed.entropy, spawn_key=key))


def partial_order(recipe: Recipe) -> PartialOrder:
    """The recipe's published graph as a partial order over the leaves of its recordings."""
    leaves: dict[Leaf, None] = {}
    for demo in recipe.spec.demonstrations:
        leaves.update(dict.fromkeys(to_leaves(demo.actions)))
    return PartialOrder(leaves, recipe.published)


def _score(learner: HTNLearner, recipe: Recipe) -> tuple[float, float, float]:
    score = precedence_scores(implied_precedences(learner.htn_), recipe.published)
    return score.precision, score.recall, score.f1


def _curve(points: Sequence[tuple[float, float, float]]) -> dict[str, list[float]]:
    return {m: [p[i] for p in points] for i, m in enumerate(METRICS)}


def run_recipe(recipe: Recipe, rng: np.random.Generator) -> dict[str, Any]:
    """Every condition's learning curve on one recipe (see the module's docstring)."""
    demos = recipe.spec.demonstrations
    k = len(demos)
    order = [int(i) for i in rng.permutation(k)]
    base = int(rng.integers(k))
    session_seeds = [int(s) for s in rng.integers(0, 2**32, size=len(STRATEGIES))]

    passive = HTNLearner(mode="strict")
    points = []
    for i in order:
        passive.partial_fit(demos[i])
        points.append(_score(passive, recipe))
    curves = {"passive": _curve(points)}

    task = partial_order(recipe)
    base_path = task.linearize(demos[base].actions)
    actions = [a.id for a in recipe.spec.actions]
    queries: dict[str, dict[str, int]] = {}
    valid = True
    for strategy, session_seed in zip(STRATEGIES, session_seeds, strict=True):
        instructor = SimulatedInstructor(task, base_path, perturbation=0.0, horizon=HORIZON)
        session = TeachingSession(actions, strategy, SCHEDULE, seed=session_seed, learner=HTNLearner(mode="strict"))
        points = []
        for _ in range(k):
            run_session(session, instructor, 1)
            points.append(_score(session.learner, recipe))
        curves[strategy] = _curve(points)
        valid &= all(task.admits(to_leaves(d.actions)) for d in session.demonstrations)
        queries[strategy] = {
            "asked": len(session.queries),
            "honoured": sum(bool(q.honoured) for q in session.queries),
            "distinct_demonstrations": len({d.actions for d in session.demonstrations}),
        }
    return {
        "recipe": recipe.name,
        "demonstrations": k,
        "order": order,
        "base": base,
        "base_valid": tuple(demos[base].actions) == base_path,
        "active_demonstrations_valid": valid,
        "curves": curves,
        "queries": queries,
    }


def run_trial(trial: Trial) -> dict[str, Any]:
    """One trial: every chosen recipe's learning curves, in recipe-name order."""
    recipes = _recipes(trial.params.get("root"))
    chosen = trial.params.get("recipes")
    if chosen is not None:
        known = {r.name for r in recipes}
        unknown = sorted(set(chosen) - known)
        if unknown:
            raise ExperimentError(f"captaincook: unknown recipes {', '.join(unknown)}")
        recipes = tuple(r for r in recipes if r.name in set(chosen))
    return {
        "trial": trial.index,
        "recipes": [run_recipe(r, recipe_rng(trial, r.name)) for r in recipes],
    }


# ---------------------------------------------------------------------------------------------- summary


def _mean(values: Sequence[float]) -> float:
    return math.fsum(values) / len(values)


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Curves averaged over recipes (at each k, the recipes with at least k recordings), 95% CI over trials."""
    if not results:
        raise ExperimentError("captaincook: no trial to summarize")
    names = [r["recipe"] for r in results[0]["recipes"]]
    sizes = {r["recipe"]: r["demonstrations"] for r in results[0]["recipes"]}
    k_max = max(sizes.values())
    by_recipe = [{r["recipe"]: r for r in result["recipes"]} for result in results]

    def recipe_means(cond: str, metric: str, k: int, only: Sequence[str]) -> list[float]:
        """Per trial: the mean over ``only`` of the value after ``k`` demonstrations (k: 1-based, 0 = own K)."""
        return [_mean([t[n]["curves"][cond][metric][(k or sizes[n]) - 1] for n in only]) for t in by_recipe]

    curves: dict[str, Any] = {}
    deltas: dict[str, Any] = {}
    for k in range(1, k_max + 1):
        only = [n for n in names if sizes[n] >= k]
        row: dict[str, Any] = {"k": k, "recipes": len(only)}
        for cond in CONDITIONS:
            row[cond] = {m: mean_ci(recipe_means(cond, m, k, only)) for m in METRICS}
        curves[str(k)] = row
        passive = recipe_means("passive", "f1", k, only)
        deltas[str(k)] = {
            s: mean_ci([a - p for a, p in zip(recipe_means(s, "f1", k, only), passive, strict=True)])
            for s in STRATEGIES
        }
    last = {cond: {m: mean_ci(recipe_means(cond, m, 0, names)) for m in METRICS} for cond in CONDITIONS}
    passive_last = recipe_means("passive", "f1", 0, names)
    last_delta = {
        s: mean_ci([a - p for a, p in zip(recipe_means(s, "f1", 0, names), passive_last, strict=True)])
        for s in STRATEGIES
    }

    recipes: dict[str, Any] = {}
    recipes_by_name = {r.name: r for r in _recipes(None)} if names else {}
    for n in names:
        entry: dict[str, Any] = {"demonstrations": sizes[n]}
        for cond in CONDITIONS:
            entry[cond] = {
                m: [round(_mean([t[n]["curves"][cond][m][i] for t in by_recipe]), 4) for i in range(sizes[n])]
                for m in METRICS
            }
        full = compare_recipe(recipes_by_name[n]).score
        entry["all_recordings"] = {
            "precision": round(full.precision, 4),
            "recall": round(full.recall, 4),
            "f1": round(full.f1, 4),
        }
        entry["base_breaks_published_order"] = sum(not t[n]["base_valid"] for t in by_recipe)
        recipes[n] = entry

    queries = {
        s: {
            key: sum(t[n]["queries"][s][key] for t in by_recipe for n in names)
            for key in ("asked", "honoured", "distinct_demonstrations")
        }
        for s in STRATEGIES
    }
    return {
        "conditions": list(CONDITIONS),
        "recipes_run": len(names),
        "demonstrations": {"min": min(sizes.values()), "max": k_max, "total": sum(sizes.values())},
        "horizon": HORIZON,
        "schedule": {
            "after_steps": list(SCHEDULE.after_steps),
            "per_demonstration": SCHEDULE.max_per_demonstration,
            "skip_first": SCHEDULE.skip_first_demonstrations,
        },
        "curves": curves,
        "delta_f1": deltas,
        "at_own_k": last,
        "delta_f1_at_own_k": last_delta,
        "active_demonstrations_valid": all(
            t[n]["active_demonstrations_valid"] for t in by_recipe for n in names
        ),
        "queries": queries,
        "recipes": recipes,
    }
