"""One CaptainCook4D recipe learned from its error-free recordings and scored against its published task graph
(``supportive captaincook``): the precedences the learned hierarchy implies
(:func:`~supportive.learning.precedence.implied_precedences`) against the published ones (their transitive
closure), and the task graph they make against the published graph edge by edge, with the protocol of
*Differentiable Task Graph Learning* (:mod:`supportive.learning.graph_edges`), learned from every error-free
recording (``full``) and from the first :data:`FEW_SHOT` (``5-shot``).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from supportive.errors import DatasetError
from supportive.experiments.statistics import mean_ci
from supportive.io.captaincook import Recipe
from supportive.learning.graph_edges import EDGE_ERRORS, compare_edges
from supportive.learning.learner import learn
from supportive.learning.precedence import PrecedenceScore, implied_precedences, precedence_scores
from supportive.tasks.spec import TaskSpec

__all__ = ["FEW_SHOT", "RecipeMeans", "RecipeReport", "captaincook_report", "compare_recipe", "few_shot_spec", "recipe_means"]

FEW_SHOT = 5
"""Recordings of the few-shot setting of the task-graph protocol (each recipe's first five)."""


@dataclass(frozen=True)
class RecipeReport:
    """What learning one recipe gave, and how its implied orderings compare with the published graph.

    Attributes:
        recipe: The recipe's name (slug).
        demonstrations: Error-free recordings learned from.
        actions: Distinct actions of the recipe.
        known_paths: Distinct executions in the learned task graph (orders seen in the demonstrations).
        complete: True when the learned hierarchy has a single root.
        roots: Number of roots of the learned hierarchy.
        score: Implied precedences of the learned hierarchy against the published ones.
        edges: The task graph of those precedences against the published graph, edge by edge
            (:func:`~supportive.learning.graph_edges.edge_scores`).
        few_shot_edges: The same, learned from the first :data:`FEW_SHOT` recordings.
        edge_errors: The wrong edges of ``edges`` by kind (:func:`~supportive.learning.graph_edges.edge_errors`).
        few_shot_edge_errors: The same for ``few_shot_edges``.
        admits_demonstrations: True when the learned hierarchy admits every demonstration it did not set
            aside as a deviation (invariant 1).
        deviations: Demonstrations with a step set aside as a slip.
    """

    recipe: str
    demonstrations: int
    actions: int
    known_paths: int
    complete: bool
    roots: int
    score: PrecedenceScore
    edges: PrecedenceScore
    few_shot_edges: PrecedenceScore
    admits_demonstrations: bool
    deviations: int = 0
    edge_errors: dict[str, int] = field(default_factory=dict)
    few_shot_edge_errors: dict[str, int] = field(default_factory=dict)

    def as_dict(self) -> dict[str, object]:
        """Plain-data form (one row of ``supportive captaincook --json``)."""
        return {
            "recipe": self.recipe,
            "demonstrations": self.demonstrations,
            "actions": self.actions,
            "known_paths": self.known_paths,
            "complete": self.complete,
            "roots": self.roots,
            "admits_demonstrations": self.admits_demonstrations,
            "deviations": self.deviations,
            "precision": self.score.precision,
            "recall": self.score.recall,
            "f1": self.score.f1,
            "edges": _as_dict(self.edges),
            "edges_5_shot": _as_dict(self.few_shot_edges),
            "edge_errors": dict(self.edge_errors),
            "edge_errors_5_shot": dict(self.few_shot_edge_errors),
        }


def _as_dict(score: PrecedenceScore) -> dict[str, float]:
    return {"precision": score.precision, "recall": score.recall, "f1": score.f1}


def few_shot_spec(spec: TaskSpec) -> TaskSpec:
    """``spec`` with its first :data:`FEW_SHOT` demonstrations only (the protocol's 5-shot setting)."""
    return spec.with_demonstrations(spec.demonstrations[:FEW_SHOT])


def compare_recipe(recipe: Recipe, learner_options: Mapping[str, Any] | None = None) -> RecipeReport:
    """Learn ``recipe``'s hierarchy from its demonstrations and score its implied precedences.

    Args:
        recipe: A loaded CaptainCook4D recipe.
        learner_options: Keyword arguments for :class:`~supportive.learning.learner.HTNLearner`.

    Raises:
        LearningError: when the recipe has no demonstration.
    """
    options = dict(learner_options or {})
    learner = learn(recipe.spec, **options)
    htn = learner.htn_
    few = learn(few_shot_spec(recipe.spec), **options).htn_
    deviating = {d.demonstration for d in learner.deviations_}
    demos = [demo for i, demo in enumerate(recipe.spec.demonstrations) if i not in deviating]
    implied = implied_precedences(htn)
    full = compare_edges(implied, recipe.steps, recipe.graph_edges)
    few_shot = compare_edges(implied_precedences(few), recipe.steps, recipe.graph_edges)
    return RecipeReport(
        recipe=recipe.name,
        demonstrations=len(recipe.spec.demonstrations),
        actions=len(recipe.spec.actions),
        known_paths=learner.task_graph_.path_count(),
        complete=htn.complete,
        roots=len(htn.roots),
        score=precedence_scores(implied, recipe.published),
        edges=full.score,
        few_shot_edges=few_shot.score,
        admits_demonstrations=all(htn.admits(demo.actions) for demo in demos),
        deviations=len(deviating),
        edge_errors=full.errors,
        few_shot_edge_errors=few_shot.errors,
    )


def captaincook_report(
    recipes: Iterable[Recipe], learner_options: Mapping[str, Any] | None = None
) -> list[RecipeReport]:
    """:func:`compare_recipe` for each recipe, in order."""
    return [compare_recipe(recipe, learner_options) for recipe in recipes]


@dataclass(frozen=True)
class RecipeMeans:
    """Means over recipes of their scores, and whether every learned model admits all its recordings;
    ``edges`` and ``few_shot_edges`` are the means of the task-graph protocol's precision, recall and F1,
    ``edge_f1`` their F1 with its 95 % interval over the recipes (:func:`~supportive.experiments.statistics.mean_ci`,
    by setting: ``full``, ``5-shot``), ``edge_errors`` and ``few_shot_edge_errors`` the wrong edges summed over
    the recipes, by kind."""

    recipes: int
    precision: float
    recall: float
    f1: float
    all_admitted: bool
    edges: dict[str, float]
    few_shot_edges: dict[str, float]
    edge_f1: dict[str, dict[str, Any]] = field(default_factory=dict)
    edge_errors: dict[str, int] = field(default_factory=dict)
    few_shot_edge_errors: dict[str, int] = field(default_factory=dict)


def recipe_means(reports: Sequence[RecipeReport]) -> RecipeMeans:
    """The mean precision, recall and F1 of ``reports``.

    Raises:
        DatasetError: when there is no report (no recipe was loaded).
    """
    if not reports:
        raise DatasetError("no CaptainCook4D recipe to average over")
    n = len(reports)
    return RecipeMeans(
        recipes=n,
        precision=sum(r.score.precision for r in reports) / n,
        recall=sum(r.score.recall for r in reports) / n,
        f1=sum(r.score.f1 for r in reports) / n,
        all_admitted=all(r.admits_demonstrations for r in reports),
        edges=_means([r.edges for r in reports]),
        few_shot_edges=_means([r.few_shot_edges for r in reports]),
        edge_f1={
            "full": mean_ci([r.edges.f1 for r in reports], bounds=(0.0, 1.0)),
            "5-shot": mean_ci([r.few_shot_edges.f1 for r in reports], bounds=(0.0, 1.0)),
        },
        edge_errors=_summed([r.edge_errors for r in reports]),
        few_shot_edge_errors=_summed([r.few_shot_edge_errors for r in reports]),
    )


def _summed(counts: Sequence[Mapping[str, int]]) -> dict[str, int]:
    total: Counter[str] = Counter()
    for row in counts:
        total.update(row)
    return {kind: total[kind] for kind in EDGE_ERRORS}


def _means(scores: Sequence[PrecedenceScore]) -> dict[str, float]:
    n = len(scores)
    return {
        "precision": sum(s.precision for s in scores) / n,
        "recall": sum(s.recall for s in scores) / n,
        "f1": sum(s.f1 for s in scores) / n,
    }
