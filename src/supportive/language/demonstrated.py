"""Initiation and termination conditions learned from demonstration (§3.3.4.2).

A person shows the robot when a behavior should start (or stop) by triggering it in a few states. To cover
more than the states shown, the marked states are generalised with kernel density estimation over a state
feature map — here each state's row of the task's truth table (which atoms hold), so states that agree on
more predicates are nearer. The kernel is an isotropic Gaussian whose bandwidth is chosen by leave-one-out
cross-validation of the log-likelihood of the marked states (over a grid of candidate bandwidths), and a
state joins the region when its density reaches ``level`` times the lowest density of any marked state.

The thesis warns that for behaviors with dangerous failure modes such generalisation is "highly
undesirable". So states marked *hazardous* are never included, and neither is any state nearer (in feature
space) to a hazardous state than to every marked one: generalisation never crosses a hazard.

:class:`BehaviorRecorder` is the recording half: it collects the states where a person started a behavior
and where they stopped it, learns the initiation region from the first (never in or across a hazard) and the
termination region from the second (plus every hazardous state: the behavior must stop there), and writes
them as the behavior's formulas.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable, Sequence
from dataclasses import dataclass, replace
from typing import Self

import numpy as np
from scipy.spatial.distance import cdist
from scipy.special import logsumexp

from supportive.errors import LanguageError, LearningError
from supportive.estimator import Estimator
from supportive.language.cover import exact_formula
from supportive.language.dnf import TruthTable
from supportive.language.explain import scope
from supportive.language.states import State, TaskStates
from supportive.tasks.behaviors import SupportiveBehavior

__all__ = ["BANDWIDTHS", "BehaviorRecorder", "DemonstratedRegion", "learn_region"]

BANDWIDTHS: tuple[float, ...] = (0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0)
"""Candidate bandwidths (in feature-space distance: √(atoms that differ)) tried by cross-validation."""


@dataclass(frozen=True)
class DemonstratedRegion:
    """A region learned from marked states.

    Attributes:
        states: The states in the region (marked ones included, hazardous ones never).
        bandwidth: The kernel bandwidth cross-validation chose.
        threshold: Log-density a state needs to join.
        marked: The states the person marked.
        excluded: States kept out because of a hazard (hazardous, or nearer a hazard than any marked state).
    """

    states: frozenset[Hashable]
    bandwidth: float
    threshold: float
    marked: frozenset[Hashable]
    excluded: frozenset[Hashable]


def _log_density(points: np.ndarray, samples: np.ndarray, bandwidth: float) -> np.ndarray:
    squared = cdist(points, samples, "sqeuclidean")
    dims = samples.shape[1]
    norm = -0.5 * dims * np.log(2 * np.pi * bandwidth**2) - np.log(len(samples))
    return np.asarray(logsumexp(-squared / (2 * bandwidth**2), axis=1) + norm)


def _cross_validated(samples: np.ndarray, candidates: Sequence[float]) -> float:
    """The bandwidth maximising the leave-one-out log-likelihood (ties: the smaller one); with one sample
    nothing can be cross-validated and the median candidate is used."""
    if len(samples) < 2:
        return float(np.median(candidates))
    squared = cdist(samples, samples, "sqeuclidean")
    np.fill_diagonal(squared, np.inf)
    dims = samples.shape[1]
    best, best_score = min(candidates), -np.inf
    for h in sorted(candidates):
        norm = -0.5 * dims * np.log(2 * np.pi * h**2) - np.log(len(samples) - 1)
        score = float(np.sum(logsumexp(-squared / (2 * h**2), axis=1) + norm))
        if score > best_score + 1e-12:
            best, best_score = h, score
    return best


def learn_region(
    table: TruthTable,
    marked: Iterable[Hashable],
    *,
    hazardous: Iterable[Hashable] = (),
    bandwidths: Sequence[float] = BANDWIDTHS,
    level: float = 1.0,
) -> DemonstratedRegion:
    """Generalise the marked states to a region.

    Args:
        table: The task's truth table (its rows are the state features).
        marked: States where the person started (or stopped) the behavior.
        hazardous: States where it must never run.
        bandwidths: Candidate bandwidths for cross-validation (all > 0).
        level: Scale of the inclusion threshold: a state joins when its density is at least ``level`` times
            the least dense marked state's (1: as dense as that; smaller generalises further).

    Raises:
        LanguageError: with no marked state, a marked state that is also hazardous, an unknown state or a
            non-positive bandwidth or level.

    >>> table = TruthTable.from_sets(["a", "b", "c", "d"], {"p": {"a", "b"}, "q": {"a", "c"}, "r": {"d"}})
    >>> sorted(learn_region(table, ["a"], bandwidths=[0.5]).states)
    ['a']
    >>> sorted(learn_region(table, ["a", "c"], level=0.1).states)
    ['a', 'b', 'c']
    >>> sorted(learn_region(table, ["a", "c"], level=0.1, hazardous=["b"]).states)
    ['a', 'c']
    """
    chosen = frozenset(marked)
    danger = frozenset(hazardous)
    if not chosen:
        raise LanguageError("mark at least one state")
    if chosen & danger:
        raise LanguageError(f"a state cannot be both marked and hazardous: {sorted(map(str, chosen & danger))}")
    if any(h <= 0 for h in bandwidths) or not bandwidths or level <= 0:
        raise LanguageError("bandwidths and level must be > 0")
    features = table.values.astype(float)
    rows = [table.state_index[s] for s in chosen]
    samples = features[rows]
    bandwidth = _cross_validated(samples, bandwidths)
    density = _log_density(features, samples, bandwidth)
    threshold = float(density[rows].min()) + float(np.log(level))
    inside = density >= threshold - 1e-9
    inside[rows] = True  # what the person showed is always in
    excluded = np.zeros(len(table.states), dtype=bool)
    if danger:
        hazard_rows = [table.state_index[s] for s in danger]
        to_hazard = cdist(features, features[hazard_rows]).min(axis=1)
        to_marked = cdist(features, samples).min(axis=1)
        excluded = to_hazard < to_marked
        excluded[hazard_rows] = True
        excluded[rows] = False
    keep = inside & ~excluded
    states = frozenset(s for s, k in zip(table.states, keep, strict=True) if k)
    kept_out = frozenset(s for s, k in zip(table.states, inside & excluded, strict=True) if k) | danger
    return DemonstratedRegion(states, bandwidth, threshold, chosen, kept_out)


class BehaviorRecorder(Estimator):
    """Learns a behavior's regions from where a person started and stopped it (§3.3.4.2): the caller records
    the states (or the actions done so far) whenever the person triggers or stops the behavior, then
    :meth:`fit` learns from them.

    Args:
        states: The task's states.
        behavior: The behavior being shown (its subtasks are kept; its regions are learned).
        hazardous: States where it must never run: never in the initiation region, always in the termination
            region.
        level: Of :func:`learn_region` (smaller generalises further).
        bandwidths: Of :func:`learn_region`.

    Attributes (after ``fit``):
        starts_: The states where the person started it, in order.
        stops_: The states where they stopped it.
        initiation_: The learned initiation region.
        termination_: The learned termination region (None when no stop was shown).
        behavior_: The behavior with the learned regions as formulas; without stops, its termination is kept.

    >>> from supportive.examples import load
    >>> chair = TaskStates.of(load("ikea-chair"))
    >>> screws = next(b for b in chair.spec.behaviors if b.name == "give-screws")
    >>> done = ["get_left_frame", "place_left_frame", "peg_left_front", "peg_left_rear", "get_right_frame",
    ...         "place_right_frame", "peg_right_front", "peg_right_rear", "get_front_support",
    ...         "attach_front_support", "get_back_support", "attach_back_support", "insert_bolt_fl",
    ...         "tighten_nut_fl", "insert_bolt_fr", "tighten_nut_fr", "insert_bolt_rl", "tighten_nut_rl",
    ...         "insert_bolt_rr", "tighten_nut_rr", "get_seat", "place_seat"]
    >>> learned = BehaviorRecorder(chair, screws).fit([done], stops=[[*done, "screw_seat_left"]]).behavior_
    >>> learned.initiation, learned.termination
    ('not active(Screw seat)', 'attached(seat, left_frame)')
    """

    def __init__(
        self,
        states: TaskStates,
        behavior: SupportiveBehavior,
        *,
        hazardous: Iterable[State] = (),
        level: float = 1.0,
        bandwidths: Sequence[float] = BANDWIDTHS,
    ) -> None:
        self.states = states
        self.behavior = behavior
        self.hazardous = frozenset(hazardous)
        self.level = level
        self.bandwidths = tuple(bandwidths)

    def _state(self, at: State | Sequence[str]) -> State:
        return at if isinstance(at, frozenset) else self.states.state_after(at)

    def fit(
        self, starts: Iterable[State | Sequence[str]], stops: Iterable[State | Sequence[str]] = ()
    ) -> Self:
        """Learn the regions from where the person started (``starts``) and stopped (``stops``) the behavior:
        task states, or the actions done so far.

        Raises:
            LanguageError: for actions that are no valid beginning of the task.
            LearningError: with no start, a start in a hazardous state, or a learned region the task's
                predicates cannot say exactly (a state in it looks, by its atoms, like one outside it).
        """
        self._forget()
        self.starts_ = [self._state(at) for at in starts]
        self.stops_ = [self._state(at) for at in stops]
        if not self.starts_:
            raise LearningError(f"{self.behavior.name}: record at least one state where it starts")
        if set(self.starts_) & self.hazardous:
            raise LearningError(f"{self.behavior.name}: it was started in a state marked hazardous")
        table = self.states.table
        self.initiation_ = learn_region(
            table, self.starts_, hazardous=self.hazardous, bandwidths=self.bandwidths, level=self.level
        )
        self.termination_: DemonstratedRegion | None = None
        termination = self.behavior.termination
        within = scope(self.states, self.behavior)
        if self.stops_:
            self.termination_ = learn_region(table, self.stops_, bandwidths=self.bandwidths, level=self.level)
            termination = self._said(self.termination_.states | self.hazardous, within, "stops")
        initiation = self._said(self.initiation_.states, within, "starts")
        self.behavior_ = replace(self.behavior, initiation=initiation, termination=termination)
        return self

    def _said(self, region: frozenset[Hashable], within: frozenset[Hashable], what: str) -> str:
        try:
            return str(exact_formula(self.states.table, region, within))
        except ValueError as exc:
            raise LearningError(f"{self.behavior.name}: where it {what}: {exc}") from None
