"""What the task-graph protocol would give if CaptainCook4D's people drew their orders uniformly from each
recipe's published graph (``supportive captaincook --uniform N``): how much of a learner's shortfall is its own,
and how much the recordings' habits.

A learner sees only orders. An order every recording keeps is evidence for a precondition whether the recipe
needs it or the people who recorded it have a habit, and no learner of orders can tell the two apart. Here each
recipe's recordings are replaced by as many executions drawn **uniformly** among the orders its published graph
admits (:meth:`~supportive.generate.partial_orders.PartialOrderTask.counting_sampler`), learned as
:func:`~supportive.experiments.captaincook.recipes.compare_recipe` learns the real ones (every drawn recording,
then the first few, :func:`~supportive.experiments.captaincook.recipes.few_shot_spec`), and scored against the
same graph the same way. The gap between these figures and the real recordings' is what the people's habits
cost; the gap between these and 1 is the learner's own, given that many recordings.

:func:`kept_free_pairs` asks the recordings themselves: of the pairs of steps the published graph leaves
unordered, how many every recording doing both keeps in one order, against how many uniform draws would keep
so on average (a pair that ``q`` of the graph's orders put one way is kept by ``m`` draws with chance
``q^m + (1 - q)^m``).
"""

from __future__ import annotations

import itertools
import statistics
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from supportive.errors import DatasetError, InvalidValueError
from supportive.experiments.captaincook.recipes import few_shot_spec
from supportive.experiments.statistics import mean_ci
from supportive.generate.partial_orders import PartialOrderTask
from supportive.io.captaincook import Recipe
from supportive.learning.graph_edges import compare_edges
from supportive.learning.learner import learn
from supportive.learning.linear_extensions import count_linear_extensions
from supportive.learning.precedence import implied_precedences
from supportive.tasks.htn import HTN, Leaf, to_leaves
from supportive.tasks.spec import Demonstration

__all__ = ["KeptPairs", "UniformDraws", "kept_free_pairs", "published_order", "uniform_draws"]


@dataclass(frozen=True)
class UniformDraws:
    """Task-graph F1 of a learner on recordings drawn uniformly from the published graphs.

    Attributes:
        draws: Sets of recordings drawn per recipe (each as many as the recipe has).
        seed: The seed every draw derives from.
        full: Mean F1 over the recipes (each recipe's mean over its draws) with its 95 % interval
            (:func:`~supportive.experiments.statistics.mean_ci`), learned from every drawn recording.
        few_shot: The same, learned from the first :data:`~supportive.experiments.captaincook.recipes.FEW_SHOT`.
    """

    draws: int
    seed: int
    full: dict[str, Any]
    few_shot: dict[str, Any]

    def as_dict(self) -> dict[str, object]:
        """Plain-data form."""
        return {"draws": self.draws, "seed": self.seed, "full": self.full, "5-shot": self.few_shot}


@dataclass(frozen=True)
class KeptPairs:
    """Pairs of steps a published graph leaves unordered, done by two or more recordings (``free``); those every
    such recording does in one order (``kept``); and how many uniform draws from the graph's orders would keep
    on average (``expected``), summed over recipes."""

    free: int
    kept: int
    expected: float

    def as_dict(self) -> dict[str, object]:
        """Plain-data form."""
        return {"free": self.free, "kept": self.kept, "expected": round(self.expected, 3)}


def kept_free_pairs(recipes: Sequence[Recipe]) -> KeptPairs:
    """:class:`KeptPairs` of the recipes' error-free recordings (see the module docstring).

    Raises:
        DatasetError: when a published graph's orders are too many to count exactly.
    """
    free = kept = 0
    expected = 0.0
    for recipe in recipes:
        steps = sorted(recipe.steps)
        index = {leaf: i for i, leaf in enumerate(steps)}
        pairs = [(index[a], index[b]) for a, b in recipe.published if a in index and b in index]
        total = count_linear_extensions(len(steps), pairs)
        if not total:
            raise DatasetError(f"{recipe.name}: its published graph's orders could not be counted")
        positions = [{leaf: k for k, leaf in enumerate(to_leaves(d.actions))} for d in recipe.spec.demonstrations]
        ordered = set(pairs)
        for i, j in itertools.combinations(range(len(steps)), 2):
            if (i, j) in ordered or (j, i) in ordered:
                continue
            both = [p for p in positions if steps[i] in p and steps[j] in p]
            if len(both) < 2:
                continue
            first = sum(p[steps[i]] < p[steps[j]] for p in both)
            keeping = count_linear_extensions(len(steps), [*pairs, (i, j)])
            if keeping is None:
                raise DatasetError(f"{recipe.name}: its published graph's orders could not be counted")
            share = keeping / total
            free += 1
            kept += first in (0, len(both))
            expected += share ** len(both) + (1 - share) ** len(both)
    return KeptPairs(free, kept, expected)


def published_order(recipe: Recipe) -> tuple[PartialOrderTask, dict[str, Leaf]]:
    """The recipe's published graph as a partial-order task of one-step chains (its steps named
    ``action#occurrence``), and each name's leaf."""
    leaves = {f"{action}#{occurrence}": (action, occurrence) for action, occurrence in sorted(recipe.steps)}
    name = {leaf: text for text, leaf in leaves.items()}
    cross = tuple(sorted((name[a], name[b]) for a, b in recipe.published if a in name and b in name))
    return PartialOrderTask(tuple((text,) for text in leaves), cross), leaves


def uniform_draws(
    recipes: Sequence[Recipe], draws: int, seed: int = 0, learner_options: Mapping[str, Any] | None = None
) -> UniformDraws:
    """The task-graph F1 of the learner ``learner_options`` configures (the default learner when None) on
    ``draws`` sets of uniformly drawn recordings of each recipe (see the module docstring). Draw ``d`` of
    recipe ``i`` uses the generator ``default_rng([seed, i, d])``: the same seed gives the same numbers.

    Raises:
        DatasetError: when there is no recipe.
        InvalidValueError: when ``draws`` is below 1.
    """
    if not recipes:
        raise DatasetError("no CaptainCook4D recipe to draw recordings for")
    if draws < 1:
        raise InvalidValueError(f"draws must be 1 or more, got {draws}")
    options = dict(learner_options or {})
    full: list[float] = []
    few: list[float] = []
    for i, recipe in enumerate(recipes):
        order, leaves = published_order(recipe)
        sample = order.counting_sampler()
        scores: list[tuple[float, float]] = []
        for d in range(draws):
            rng = np.random.default_rng([seed, i, d])
            recordings = tuple(
                Demonstration.of([leaves[step][0] for step in sample(rng)], id=f"uniform-{k + 1}")
                for k in range(len(recipe.spec.demonstrations))
            )
            spec = recipe.spec.with_demonstrations(recordings)
            scores.append((_edge_f1(recipe, learn(spec, **options).htn_), _edge_f1(recipe, learn(few_shot_spec(spec), **options).htn_)))
        full.append(statistics.fmean(s[0] for s in scores))
        few.append(statistics.fmean(s[1] for s in scores))
    return UniformDraws(draws, seed, mean_ci(full, bounds=(0.0, 1.0)), mean_ci(few, bounds=(0.0, 1.0)))


def _edge_f1(recipe: Recipe, htn: HTN) -> float:
    """The task-graph F1 of ``htn``'s implied precedences against the recipe's published graph."""
    return compare_edges(implied_precedences(htn), recipe.steps, recipe.graph_edges).score.f1
