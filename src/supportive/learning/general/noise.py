"""Slips as noise: what people do wrong, estimated from the demonstrations by comparing explanations.

A learned hierarchy is a distribution over executions (:class:`~supportive.learning.distribution.ProgressModel`).
People add noise to the execution they meant: with some rate per step, a step is done **out of order**
(taken from its place and done at a random other one), **repeated** (done again at a random place), forgotten
(**missing**), or a step the others never do is done (**unknown**). A demonstration is then explained either
as it is, by a hierarchy loose enough to admit it, or as a valid execution of a tighter hierarchy plus noise.
The learner keeps the explanation of all the demonstrations that is more probable (hard EM over which steps
are noise):

* the score of a set of slips is the log-likelihood of the demonstrations with those slips undone (a step
  set aside is put back at the first place the hierarchy learned without it admits it, together with the
  demonstration's other steps put back; a missing step likewise) under the hierarchy learned from them, read
  jointly with people's habits integrated out (each order choice the hierarchy leaves open has its own
  distribution over the orders admitted there, under a Dirichlet prior of concentration ``concentration``:
  :meth:`~supportive.learning.order_likelihood.OrderLikelihood.log_probability_of_all`; so loosening a
  hierarchy for an order several people take costs little, while an order one person took alone costs about
  ``log(n K / α)``), plus the log-likelihood of the slips themselves: which steps are slips of each kind, the
  kind's rate integrated out under a beta prior of mean ``rate`` worth ``weight`` steps (beta-binomial: on
  clean data the rates go to zero), and where each landed (a uniform choice among the demonstration's
  positions);
* the search starts from no slip and adds, best first, the candidate whose score gain is largest, while that
  gain exceeds ``margin`` nats a slip; then takes back the slips not worth ``margin`` nats each; then replaces
  the slips of one demonstration by a single candidate of its own where that is more probable (the earlier of
  two performances taken for the repeat and the later then out of place, where the later is the repeat: a
  move that needs one slip out and another in at once); and repeats the three until a pass changes nothing
  (slips that only pay together can be missed by a pass that took a few that pay alone). It also runs from a
  second start, the most telling step out of place in every demonstration that has one (when that beats no
  slip), and keeps the more probable of the two ends: a greedy search from the large start can stall where
  taking back the variants of a step would mean keeping its real slips (issue #23: four real slips of a step
  kept with eighteen valid variants, 70 nats less probable than the four alone). Candidates are the steps that reverse an order the others agree on (an order that so few
  demonstrations reverse that the hierarchy learned without them, which predicts how often the pair comes
  either way, makes it unlikely: a binomial test), alone and, for an order several demonstrations reverse,
  together; steps found inside a subtask the others keep together, in fewer demonstrations than establish an
  order; the steps whose move makes an odd demonstration an execution of the hierarchy of the others; every
  performance of a step the others do not do, and every demonstration that skips a step the others do; those
  the others would have to agree on are shown by at least ``support`` demonstrations (no slip can be told from
  a variant with fewer);
* a step out of order stands only when the demonstrations show it as no sample of valid executions readily
  would (:meth:`_Search._by_chance`): the likelihood comparison rewards a tighter hierarchy for any
  arrangement a sample happens to avoid, and a task has many arrangements (some come up far less often than
  due in a clean sample: a step alone between two chain steps once in 52 executions where 5.8 are due). The
  hierarchy learned with the step kept, every order it admits equally likely, gives each demonstration's
  chance of falling outside the tighter hierarchy; the slips of the step stand when as few falling outside as
  did is below ``evidence`` over the number of pairs of steps (the arrangements a tighter hierarchy may
  forbid; Bonferroni).

So on clean data nothing is set aside: a tighter hierarchy gains less than the noise costs, whatever the
pair frequencies a partial order implies (a free pair in a partial order is not a coin: the hierarchy's own
distribution says how often each order comes). The estimated rates (:class:`NoiseEstimate`) go to zero.
"""

from __future__ import annotations

import heapq
import itertools
import math
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Literal, cast

import numpy as np

from supportive.learning.general.evidence import IntMatrix, padded, position_pair_counts, positions_of
from supportive.learning.general.loosening import loosened_for
from supportive.learning.general.structure import FittedStructure, StructureSettings, fit_structure
from supportive.learning.order_likelihood import OrderLikelihood
from supportive.learning.pair_orders import order_probabilities
from supportive.tasks.htn import Leaf

__all__ = ["KINDS", "Deviation", "NoiseEstimate", "NoiseSettings", "SlipResult", "SlipSearchCache", "find_slips"]

Kind = Literal["out of order", "repeated", "missing", "unknown"]
KINDS: tuple[Kind, ...] = ("out of order", "repeated", "missing", "unknown")
"""The kinds of slip, in the order reports list them."""

_Closure = tuple[frozenset[int], list[tuple[int, int]]]
"""A robust closure's members and the ``(demonstration, step)`` found inside it by few (:func:`_robust_closure`)."""

_TAKEN_OUT = frozenset({"out of order", "repeated", "unknown"})
_PUT_BACK = frozenset({"out of order", "missing"})
_BEYOND = np.iinfo(np.int64).max
"""Where a step a demonstration does not do starts (after any other)."""


@dataclass(frozen=True)
class Deviation:
    """One slip: in demonstration ``demonstration`` (an index), the step at ``position`` (-1 for a missing
    step) labelled ``leaf``, of kind ``kind``."""

    demonstration: int
    position: int
    leaf: Leaf
    kind: Kind

    def as_dict(self, demo_ids: Sequence[str] = ()) -> dict[str, object]:
        """Plain-data form; ``demo_ids`` names the demonstrations by their ids."""
        action, instance = self.leaf
        name = (
            demo_ids[self.demonstration]
            if self.demonstration < len(demo_ids)
            else str(self.demonstration + 1)
        )
        data: dict[str, object] = {"demonstration": name, "kind": self.kind, "action": action}
        if instance != 1:
            data["occurrence"] = instance
        if self.position >= 0:
            data["step"] = self.position + 1
        return data


@dataclass(frozen=True)
class NoiseSettings:
    """The slip search's settings (see :class:`~supportive.learning.learner.HTNLearner`, which holds their
    defaults and says how they were chosen)."""

    margin: float
    rate: float
    weight: float
    max_candidates: int
    concentration: float


@dataclass(frozen=True)
class NoiseEstimate:
    """The noise model fitted with the slips: per kind, how many slips and their rate per observed step.

    Attributes:
        steps: Observed steps over all demonstrations.
        counts: Slips per kind.
        gain: How much more probable (natural log) the demonstrations are with these slips than with none.
        evaluations: Explanations scored by the search.
    """

    steps: int
    counts: dict[str, int] = field(default_factory=dict)
    gain: float = 0.0
    evaluations: int = 0

    @property
    def rates(self) -> dict[str, float]:
        """Slips per observed step, by kind (every kind listed; 0 where none was found)."""
        return {kind: (self.counts.get(kind, 0) / self.steps if self.steps else 0.0) for kind in KINDS}

    def as_dict(self) -> dict[str, object]:
        """Plain-data form (``"noise"`` in the HTN JSON)."""
        return {
            "steps": self.steps,
            "slips": {kind: self.counts.get(kind, 0) for kind in KINDS},
            "rates": {kind: round(rate, 6) for kind, rate in self.rates.items()},
            "log_likelihood_gain": round(self.gain, 4),
        }


@dataclass(frozen=True)
class SlipResult:
    """The demonstrations with their slips taken out (``cleaned``) and undone (``restored``: a step out of order
    or missing put back at the first place the hierarchy admits it, as the search scored them; the cleaned
    ones when the slips cannot be undone), the slips, the noise model and the hierarchy learned from the
    cleaned demonstrations."""

    cleaned: list[tuple[Leaf, ...]]
    restored: list[tuple[Leaf, ...]]
    deviations: tuple[Deviation, ...]
    noise: NoiseEstimate
    structure: FittedStructure


@dataclass
class _Work:
    """What the search learns of one set of demonstrations that no noise setting changes, by set of slips:
    the hierarchy learned with them taken out, the candidates scored next, the demonstrations with them taken
    out and undone; the counted orders of top levels; and the hierarchy's part of the score
    (:meth:`_Search._structure`), by ``order_concentration`` too."""

    fits: dict[frozenset[Deviation], FittedStructure] = field(default_factory=dict)
    found: dict[frozenset[Deviation], list[frozenset[Deviation]]] = field(default_factory=dict)
    cleaned_by: dict[frozenset[Deviation], list[tuple[Leaf, ...]]] = field(default_factory=dict)
    restorations: dict[frozenset[Deviation], list[tuple[Leaf, ...]]] = field(default_factory=dict)
    orders: dict[object, int] = field(default_factory=dict)
    scores: dict[float, dict[frozenset[Deviation], float]] = field(default_factory=dict)


class SlipSearchCache:
    """The slip search's work, shared between fits of the same demonstrations under different slip settings.

    A sweep of ``slip_margin``, ``slip_rate``, ``slip_rate_weight`` or ``order_concentration`` (as
    ``supportive reproduce learner-settings`` runs) explains the same demonstrations many times: the
    hierarchies learned with each set of slips taken out, the candidates and the scores of the hierarchies
    (for each concentration) are the same in every fit. Given to
    :class:`~supportive.learning.learner.HTNLearner` as ``slip_cache``, they are learned once; the results are
    exactly those of fits without it. The work is kept apart for each set of demonstrations, way of learning
    hierarchies and candidate bound, and held until the cache is dropped: use one for the fits of one sweep.

    >>> from supportive.learning import HTNLearner
    >>> from supportive.learning.general import SlipSearchCache
    >>> demos = [list("abcd")] * 8 + [list("abdc"), list("bacd")]
    >>> cache = SlipSearchCache()
    >>> fits = [HTNLearner(mode="general", slip_margin=m, slip_cache=cache).fit(demos) for m in (0.0, 1.0)]
    >>> len(cache)  # one set of demonstrations, searched twice
    1
    """

    def __init__(self) -> None:
        self._work: dict[tuple[object, ...], _Work] = {}

    def __len__(self) -> int:
        """How many sets of demonstrations (with a way of learning and a candidate bound) the cache holds."""
        return len(self._work)

    def _of(self, labelled: tuple[tuple[Leaf, ...], ...], structure: StructureSettings, modules: bool, bound: int) -> _Work:
        """The work kept for these demonstrations, learned this way, with this candidate bound (new if none)."""
        return self._work.setdefault((labelled, structure, modules, bound), _Work())


def find_slips(
    labelled: Sequence[Sequence[Leaf]],
    structure: StructureSettings,
    settings: NoiseSettings,
    *,
    modules: bool = True,
    cache: SlipSearchCache | None = None,
) -> SlipResult:
    """The most probable explanation of ``labelled`` as valid executions plus slips (see the module
    docstring).

    Args:
        labelled: The demonstrations as leaves (:func:`~supportive.learning.general.labelling.label_performances`).
        structure: How hierarchies are learned (:func:`~supportive.learning.general.structure.fit_structure`).
        settings: The search's margin, the slip rates' prior and how many candidates a round scores.
        modules: False learns partial orders of steps only (see :func:`fit_structure`).
        cache: Work shared with other searches of the same demonstrations (:class:`SlipSearchCache`); None:
            none shared.
    """
    return _Search(labelled, structure, settings, modules, cache).run()


@dataclass(frozen=True)
class _Steps:
    """Demonstrations (their leaves) encoded once for the candidate searches: ``leaves`` sorted,
    ``index`` of each, ``matrix[d, k]`` the id of demonstration ``d``'s k-th step (-1 after its end) and
    ``at[d, i]`` where ``d`` does leaf ``i`` (-1: not at all; a leaf is done once in a demonstration)."""

    leaves: list[Leaf]
    index: dict[Leaf, int]
    matrix: IntMatrix
    at: IntMatrix

    @classmethod
    def of(cls, demos: Sequence[Sequence[Leaf]]) -> _Steps:
        """The encoding of ``demos``."""
        flat = list(itertools.chain.from_iterable(demos))
        leaves = sorted(set(flat))
        index = {leaf: i for i, leaf in enumerate(leaves)}
        matrix = padded(np.fromiter(map(index.__getitem__, flat), dtype=np.int64, count=len(flat)), list(map(len, demos)))
        return cls(leaves, index, matrix, positions_of(matrix, len(leaves)))

    @cached_property
    def by_step(self) -> IntMatrix:
        """``at`` laid out by step: ``by_step[i, d]`` is where demonstration ``d`` does leaf ``i`` (a step's row
        is contiguous, so sums over the demonstrations run along rows)."""
        by_step: IntMatrix = np.ascontiguousarray(self.at.T)
        return by_step

    @cached_property
    def doers(self) -> IntMatrix:
        """How many demonstrations do each leaf."""
        doers: IntMatrix = (self.at >= 0).sum(axis=0)
        return doers


@dataclass(frozen=True)
class _Kept:
    """The demonstrations with the steps that slips take out removed (leaves not numbered again):
    ``demos[d]`` the leaves kept, ``where[d]`` the place each had in the demonstration as given (only for the
    demonstrations a slip touched: elsewhere the k-th step kept is the k-th). Indexed by a demonstration, it
    lists the ``(place, leaf)`` of that demonstration's steps kept."""

    demos: list[tuple[Leaf, ...]]
    where: dict[int, list[int]]

    def __len__(self) -> int:
        return len(self.demos)

    def __getitem__(self, d: int) -> list[tuple[int, Leaf]]:
        where = self.where.get(d)
        return list(enumerate(self.demos[d]) if where is None else zip(where, self.demos[d], strict=True))

    def position(self, d: int, k: int) -> int:
        """The place in the demonstration as given of demonstration ``d``'s k-th step kept."""
        where = self.where.get(d)
        return k if where is None else where[k]


class _Search:
    """Greedy search over sets of slips, scoring each set by refitting (see the module docstring)."""

    def __init__(
        self,
        labelled: Sequence[Sequence[Leaf]],
        structure: StructureSettings,
        settings: NoiseSettings,
        modules: bool,
        cache: SlipSearchCache | None = None,
    ) -> None:
        self.labelled = [tuple(demo) for demo in labelled]
        self.structure_settings = structure
        self.settings = settings
        self.modules = modules
        self.steps = sum(len(demo) for demo in self.labelled)
        work = _Work() if cache is None else cache._of(tuple(self.labelled), structure, modules, settings.max_candidates)
        self._scores = work.scores.setdefault(settings.concentration, {})
        self._fits = work.fits
        self._found = work.found
        self._cleaned_by = work.cleaned_by
        self._restorations = work.restorations  # slips undone
        self._orders = work.orders  # counted orders of top levels, shared by the readings scored
        self._scored: set[frozenset[Deviation]] = set()  # the explanations this search scored

    # ------------------------------------------------------------------ search
    def run(self) -> SlipResult:
        none: frozenset[Deviation] = frozenset()
        slips, gain = none, 0.0
        if self._searchable():
            joint = self._joint()
            passed: set[frozenset[Deviation]] = set()
            if joint and self._total(joint) - self._total(none) > self.settings.margin * len(joint):
                slips = self._passes(joint, passed)
            if none not in passed:  # else the search from no slip ends where this one did
                found = self._passes(none, set())
                if not passed or self._total(found) >= self._total(slips):  # ties: from no slip
                    slips = found
            slips = self._by_chance(slips)
            gain = self._total(slips) - self._total(none) if slips else 0.0
        fitted = self._fit(slips)
        deviations = tuple(sorted(slips, key=_order))
        counts = Counter(d.kind for d in deviations)
        noise = NoiseEstimate(self.steps, {k: counts[k] for k in KINDS if counts[k]}, gain, len(self._scored))
        cleaned = self._cleaned(slips)
        restored = self._restorations[slips] if slips and math.isfinite(self._structure(slips)) else cleaned
        return SlipResult(cleaned, restored, deviations, noise, fitted)

    def _passes(self, slips: frozenset[Deviation], passed: set[frozenset[Deviation]]) -> frozenset[Deviation]:
        """Forward then backward passes from ``slips``, until a pass changes nothing; every set of slips a
        pass starts from is added to ``passed``."""
        while slips not in passed:
            passed.add(slips)
            slips = self._exchange(self._backward(self._forward(slips)))
        return slips

    def _joint(self) -> frozenset[Deviation]:
        """The most telling single step out of place in each demonstration that has one (the largest
        candidate, a start the search may prune): from a hierarchy loosened by many slips, each alone may
        gain little while a variant many people do gains much."""
        candidates = self._candidates(frozenset())
        singles = [c for c in candidates if len(c) == 1 and next(iter(c)).kind == "out of order"]
        best = {next(iter(c)).demonstration: c for c in reversed(singles)}
        return frozenset().union(*best.values()) if best else frozenset()

    def _forward(self, slips: frozenset[Deviation]) -> frozenset[Deviation]:
        """Add, one at a time, the candidate whose slips make the explanation most probable per slip, while
        it gains more than ``margin`` a slip (as :meth:`_backward` and the joint start weigh slips); return
        the slips. Per slip: a group of slips (the
        same step out of order in several demonstrations) must be worth more than its best single members,
        or a variant many people do would be taken for many slips at once. Lazy: a candidate's gain in an
        earlier round bounds its gain now (adding slips rarely makes another worth more), so only the
        candidates that might be best are scored again."""
        bounds: dict[frozenset[Deviation], float] = {}
        current: float | None = None
        while True:
            candidates = self._candidates(slips)
            if not candidates:
                break
            if current is None:
                current = self._total(slips)
            heap = [(-bounds.get(c, math.inf), i, c) for i, c in enumerate(candidates)]
            heapq.heapify(heap)
            best: tuple[float, frozenset[Deviation]] | None = None
            while heap:
                _, i, candidate = heapq.heappop(heap)
                value = self._total(slips | candidate) - current
                bounds[candidate] = value / len(candidate)
                if not heap or value / len(candidate) >= -heap[0][0]:
                    best = (value, candidate)
                    break
                heapq.heappush(heap, (-value / len(candidate), i, candidate))
            if best is None or not best[0] > self.settings.margin * len(best[1]):
                break
            slips |= best[1]
            current += best[0]
        return slips

    def _backward(self, slips: frozenset[Deviation]) -> frozenset[Deviation]:
        """Take back the slips whose removal costs the explanation less than ``margin`` nats a slip, best
        first, one slip or one group at a time (a group: the same step slipped the same way in several demonstrations, which
        only together tighten the hierarchy, and only together are seen to be a variant); return the slips
        left."""
        current = self._total(slips) if slips else 0.0
        while slips:
            groups: dict[tuple[Leaf, str], set[Deviation]] = {}
            for slip in slips:
                groups.setdefault((slip.leaf, slip.kind), set()).add(slip)
            units = [frozenset({slip}) for slip in sorted(slips, key=_order)]
            units += [frozenset(g) for _, g in sorted(groups.items()) if len(g) > 1]
            units += [  # a variant several people do, taken for slips with one real slip of the same step
                frozenset(g - {kept}) for _, g in sorted(groups.items()) if len(g) > 2 for kept in sorted(g, key=_order)
            ]
            value, unit = max(
                ((self._total(slips - u) - current + self.settings.margin * len(u), u) for u in units),
                key=lambda t: t[0],
            )
            if not value > 0.0:
                break
            slips, current = slips - unit, current + value - self.settings.margin * len(unit)
        return slips

    def _exchange(self, slips: frozenset[Deviation]) -> frozenset[Deviation]:
        """Replace the slips of one demonstration by a candidate of its own, best first, while that makes the
        explanation more probable (``margin`` nats a slip counted as :meth:`_forward` and :meth:`_backward`
        count it); return the slips. The passes add or take back one candidate at a time, so they stop where
        the better explanation of a demonstration needs one slip out and another in at once: the earlier of two
        performances of a step taken for the repeat, the later then out of place, where the later is the
        repeat."""
        margin = self.settings.margin
        current = self._total(slips) if slips else 0.0
        while slips:
            best: tuple[float, frozenset[Deviation]] | None = None
            for demonstration in sorted({slip.demonstration for slip in slips}):
                own = frozenset(slip for slip in slips if slip.demonstration == demonstration)
                rest = slips - own
                for candidate in self._candidates(rest):
                    if candidate == own or {slip.demonstration for slip in candidate} != {demonstration}:
                        continue
                    value = self._total(rest | candidate) - current + margin * (len(own) - len(candidate))
                    if value > 0.0 and (best is None or value > best[0]):
                        best = (value, rest | candidate)
            if best is None:
                break
            slips = best[1]
            current = self._total(slips)
        return slips

    def _by_chance(self, slips: frozenset[Deviation]) -> frozenset[Deviation]:
        """``slips`` without the steps out of order that a sample of valid executions shows as readily: the
        step whose slips are likeliest by chance (:meth:`_chance`) is taken back while that chance is not
        below ``evidence`` over the pairs of steps (Bonferroni over the arrangements a tighter hierarchy may
        forbid). The likelihood comparison of the search gains from any arrangement a sample happens to
        avoid, and among the many a task has, some come up far less often than due in clean samples."""
        if not any(slip.kind == "out of order" for slip in slips):
            return slips
        steps = len({leaf for demo in self.labelled for leaf in demo})
        level = self.structure_settings.evidence / max(steps * (steps - 1) // 2, 1)
        while True:
            groups: dict[Leaf, frozenset[Deviation]] = {}
            for slip in slips:
                if slip.kind == "out of order":
                    groups[slip.leaf] = groups.get(slip.leaf, frozenset()) | {slip}
            if not groups:
                return slips
            tight = OrderLikelihood(self._fit(slips).htn(), shared=self._orders)  # the same for every step
            chance, leaf = max((self._chance(slips, group, tight), leaf) for leaf, group in sorted(groups.items()))
            if chance < level:
                return slips
            slips = slips - groups[leaf]

    def _chance(self, slips: frozenset[Deviation], group: frozenset[Deviation], tight: OrderLikelihood) -> float:
        """The chance that as few demonstrations as do fall outside the hierarchy learned with ``slips`` taken
        out (``tight``), were they drawn from a looser one that admits ``group`` (one step's slips), every order
        it admits equally likely (:class:`OrderLikelihood`): each demonstration falls outside with chance
        ``1 - tight / loose``, the two hierarchies' numbers of orders of the steps it performs (0 when the
        tighter has as many), and how many do is Poisson-binomial. The looser hierarchy is the tighter (fewer
        orders) of the one learned with ``group`` kept in and ``tight`` loosened only where the slips need it
        (:func:`~supportive.learning.general.loosening.loosened_for`): kept in, a slip can make the learner read
        its neighbours otherwise and admit far more than it needs. The demonstrations other slips touch are left
        out: their own slips explain them (and when that leaves none, the chance is 1)."""
        from scipy.stats import poisson_binom

        rest = slips - group
        cleaned = self._cleaned(rest)
        loose = OrderLikelihood(self._fit(rest).htn(), shared=self._orders)
        needed = loosened_for(tight.htn, [(cleaned[slip.demonstration], slip.leaf) for slip in group])
        near = OrderLikelihood(needed, shared=self._orders) if needed is not None else None
        others = {slip.demonstration for slip in rest}
        outside, chances = 0, []
        for d, demo in enumerate(cleaned):
            if d in others:
                continue
            done = frozenset(demo)
            outside += not tight.htn.admits_leaves(demo)
            reference = loose.orders(done) if near is None else min(loose.orders(done), near.orders(done))
            chances.append(1.0 - min(1.0, tight.orders(done) / max(reference, 1)))
        if not chances:  # every demonstration has other slips: nothing tells these from chance
            return 1.0
        return float(poisson_binom.cdf(outside, chances))

    def _searchable(self) -> bool:
        """With no more demonstrations than the support an agreement needs, no slip can be told from a
        variant: nothing to search (nor with an infinite margin)."""
        return (
            math.isfinite(self.settings.margin)
            and len(self.labelled) > self.structure_settings.support_needed
        )

    # ------------------------------------------------------------------ candidates
    def _candidates(self, slips: frozenset[Deviation]) -> list[frozenset[Deviation]]:
        """The slips worth scoring next, given ``slips`` (remembered: the joint start and the first
        forward round ask for the same)."""
        found = self._found.get(slips)
        if found is None:
            found = self._found[slips] = self._find_candidates(slips)
        return found

    def _find_candidates(self, slips: frozenset[Deviation]) -> list[frozenset[Deviation]]:
        cleaned = self._kept(slips)
        n = len(cleaned)
        need = self.structure_settings.support_needed
        steps = _Steps.of(cleaned.demos)
        doers = dict(zip(steps.leaves, steps.doers.tolist(), strict=True))
        rare = {leaf for leaf, k in doers.items() if n - k >= need and k < n - k}  # done by few
        skipped = {leaf for leaf, k in doers.items() if k >= need and 0 < n - k < k}  # not done by few
        performers: dict[Leaf, list[tuple[int, int]]] = {leaf: [] for leaf in rare | skipped}
        for d in range(n) if performers else ():
            for position, leaf in cleaned[d]:
                if leaf in performers:
                    performers[leaf].append((d, position))
        excused = {(d.demonstration, d.leaf) for d in slips if d.kind == "missing"}
        out: list[frozenset[Deviation]] = []
        for leaf in sorted(performers):
            kind: Kind = "repeated" if leaf[1] > 1 else "unknown"
            if leaf in rare:
                where = performers[leaf]
                out.append(frozenset(Deviation(d, p, leaf, kind) for d, p in where))
                if kind == "repeated":  # or another performance of it was the one done again
                    out.extend(
                        frozenset({Deviation(d, p, other, "repeated")})
                        for d, _ in where
                        for p, other in cleaned[d]
                        if other[0] == leaf[0] and other != leaf
                    )
            if leaf in skipped:
                doing = {d for d, _ in performers[leaf]}
                skippers = [d for d in range(n) if d not in doing and (d, leaf) not in excused]
                if skippers:
                    out.append(frozenset(Deviation(d, -1, leaf, "missing") for d in skippers))
        reversing, reversed_together = self._moved(cleaned, steps, slips)
        reversal = [0.0] * n
        for rank, candidate in enumerate(reversing):  # the most telling step of each demonstration first
            (slip,) = candidate
            reversal[slip.demonstration] = max(reversal[slip.demonstration], float(len(reversing) - rank))
        inserted = self._inserted(cleaned, steps)
        intruded = {next(iter(candidate)).demonstration for candidate in inserted}
        repairs = self._repairs(cleaned, _outliers(reversal) | _surprising(steps) | intruded)
        moved = list(dict.fromkeys(_interleave(repairs, reversing, inserted)))
        out.extend(moved[: self.settings.max_candidates])
        by_leaf: dict[Leaf, set[Deviation]] = {}  # the same step out of order in several demonstrations
        for candidate in repairs:
            (slip,) = candidate
            by_leaf.setdefault(slip.leaf, set()).add(slip)
        out.extend(frozenset(group) for _, group in sorted(by_leaf.items()) if len(group) > 1)
        out.extend(reversed_together)
        best = {next(iter(c)).demonstration: c for c in reversed(moved)}  # the most telling per demonstration
        if len(best) > 1:
            out.append(frozenset().union(*best.values()))
        return out

    def _repairs(self, cleaned: _Kept, odd: set[int]) -> list[frozenset[Deviation]]:
        """Steps whose move would make an odd demonstration (one that reverses agreed orders, whose steps
        follow one another unusually, :func:`_surprising`, or that breaks a subtask the others keep together,
        :meth:`_inserted`) an execution of the hierarchy learned from the
        others (when there are enough of those): a step moved into a subtask breaks it without reversing any
        order, and the hierarchy learned with it is loosened where the others' is not."""
        if not odd or len(cleaned) - len(odd) <= self.structure_settings.support_needed:
            return []
        core = [demo for d, demo in enumerate(cleaned.demos) if d not in odd]
        htn = fit_structure(core, (), self.structure_settings, modules=self.modules).htn()
        out: list[frozenset[Deviation]] = []
        for d in sorted(odd):
            leaves = list(cleaned.demos[d])
            if htn.admits_leaves(leaves):
                continue
            for i in htn.executions.single_moves(leaves, range(len(leaves))):
                out.append(frozenset({Deviation(d, cleaned.position(d, i), leaves[i], "out of order")}))
        return out

    def _moved(
        self, cleaned: _Kept, steps: _Steps, slips: frozenset[Deviation]
    ) -> tuple[list[frozenset[Deviation]], list[frozenset[Deviation]]]:
        """Single steps that reverse orders the other demonstrations agree on, the most telling first: each
        reversed order weighs one over the number of demonstrations keeping it (an order few demonstrations
        show, kept by all but this one, tells more); and for each agreed order that several demonstrations reverse,
        the group of their most telling steps of the two (slips that only together show the order).

        An order is *agreed* when the demonstrations reverse it far less often than the hierarchy learned so
        far, which admits the reversals, predicts (:func:`~supportive.learning.pair_orders.order_probabilities`):
        with ``r`` of ``m`` demonstrations performing both reversing it (fewer than keep it, and at least the
        support an order needs keep it) and the hierarchy predicting the reversal with chance ``q``,
        ``P[Bin(m, q) <= r]`` is below ``evidence`` over the number of orders so tested (Bonferroni: the
        chance that any free order of the task looks agreed is below ``evidence``). A free pair of a partial order is not a coin: two steps far apart in two
        interleaved chains come in the unusual order rarely, and as rarely as predicted is no evidence."""
        leaves, index = steps.leaves, steps.index
        before, together = position_pair_counts(steps.at)
        reversed_ = (before.T > 0) & (before > before.T) & (before >= self.structure_settings.support_needed)
        if not reversed_.any():
            return [], []
        model_leaves, predicted = order_probabilities(self._fit(slips).htn())
        where = np.array([index.get(leaf, -1) for leaf in model_leaves])
        known = where >= 0
        chance = np.full((len(leaves), len(leaves)), 0.5)  # [i, j]: j before i, as the hierarchy predicts
        chance[np.ix_(where[known], where[known])] = predicted[np.ix_(known, known)].T
        # scipy.stats is imported here, where the first pair is tested: it takes 0.3 s, which every command
        # that learns paid at start-up, though small tasks never come this far.
        from scipy.stats import binom

        tested = int(reversed_.sum())
        agreed = reversed_ & (
            binom.cdf(before.T, together, chance) < self.structure_settings.evidence / tested
        )
        if not agreed.any():
            return [], []
        weight = np.where(agreed.T, 1.0 / np.maximum(before.T, 1), 0.0)  # [i, j]: j before i agreed, i first here
        telling = np.zeros(steps.at.shape, dtype=np.float64)  # [d, i]: how telling demonstration d's step i is
        ranked: list[tuple[float, int, int, Leaf]] = []
        for d, demo in enumerate(cleaned.demos):
            order = steps.matrix[d, : len(demo)]
            later = np.triu(np.ones((len(order), len(order)), dtype=bool), 1)
            reversed_here = np.where(later, weight[np.ix_(order, order)], 0.0)
            scores = reversed_here.sum(axis=0) + reversed_here.sum(axis=1)
            telling[d, order] = scores
            for i in np.flatnonzero(scores).tolist():
                ranked.append((-float(scores[i]), d, cleaned.position(d, i), demo[i]))
        ranked.sort()
        singles = [frozenset({Deviation(d, p, leaf, "out of order")}) for _, d, p, leaf in ranked]
        groups: dict[frozenset[Deviation], None] = {}
        for first, then in zip(*np.nonzero(agreed & (before.T >= 2)), strict=True):  # "first before then" agreed
            reversing = np.flatnonzero((steps.at[:, then] >= 0) & (steps.at[:, then] < steps.at[:, first]))
            chosen = np.where(telling[reversing, first] >= telling[reversing, then], first, then)
            groups.setdefault(
                frozenset(
                    Deviation(int(d), cleaned.position(d, int(steps.at[d, i])), leaves[i], "out of order")
                    for d, i in zip(reversing.tolist(), chosen.tolist(), strict=True)
                )
            )
        return singles, list(groups)

    def _inserted(self, cleaned: _Kept, steps: _Steps) -> list[frozenset[Deviation]]:
        """Single steps that break a subtask the other demonstrations keep together (a step moved into a
        subtask reverses no order but breaks it), largest subtask first.

        From each pair of steps done one right after the other by at least the support an order needs, a
        would-be subtask grows as the decomposition's closures do (every step done inside its span joins it),
        except that a step found inside it in fewer demonstrations than that support does not join (so few
        cannot establish it as a variant): those demonstrations' steps are the candidates, when the subtask is
        then kept together by at least that support of the others and the step is done outside it by as many."""
        need = self.structure_settings.support_needed
        leaves, matrix, at = steps.leaves, steps.matrix, steps.at
        performed = at >= 0
        doers = steps.doers
        followed = matrix[:, 1:] >= 0
        codes, counts = np.unique(matrix[:, :-1][followed] * len(leaves) + matrix[:, 1:][followed], return_counts=True)
        found: dict[tuple[int, int], tuple[int, Leaf]] = {}
        closures: dict[frozenset[int], _Closure] = {}
        for code in codes[counts >= need].tolist():
            pair = divmod(code, len(leaves))
            members, intruders = _robust_closure(frozenset(pair), steps.by_step, need, closures)
            if not intruders:
                continue
            kept = int((performed[:, sorted(members)].sum(axis=1) >= 2).sum())
            for d, i in intruders:
                if kept - 1 >= need and doers[i] - 1 >= need:
                    position = cleaned.position(d, int(at[d, i]))
                    found[(d, position)] = max(
                        found.get((d, position), (0, leaves[i])), (len(members), leaves[i])
                    )
        ranked = sorted(found.items(), key=lambda item: (-item[1][0], item[0]))
        return [frozenset({Deviation(d, p, leaf, "out of order")}) for (d, p), (_, leaf) in ranked]

    # ------------------------------------------------------------------ scoring
    def _kept(self, slips: frozenset[Deviation]) -> _Kept:
        out_at = {(d.demonstration, d.position) for d in slips if d.kind in _TAKEN_OUT}
        demos = list(self.labelled)
        where: dict[int, list[int]] = {}
        for d in sorted({d for d, _ in out_at}):
            where[d] = [p for p in range(len(demos[d])) if (d, p) not in out_at]
            demos[d] = tuple(demos[d][p] for p in where[d])
        return _Kept(demos, where)

    def _cleaned(self, slips: frozenset[Deviation]) -> list[tuple[Leaf, ...]]:
        """The demonstrations with the slips taken out; where a repeated performance was, the performances
        left of that action are numbered again in order (the one done again may have been the first)."""
        cleaned = self._cleaned_by.get(slips)
        if cleaned is None:
            cleaned = self._cleaned_by[slips] = self._clean(slips)
        return cleaned

    def _clean(self, slips: frozenset[Deviation]) -> list[tuple[Leaf, ...]]:
        if not slips:
            return list(self.labelled)
        renumber: dict[int, set[str]] = {}
        for slip in slips:
            if slip.kind == "repeated":
                renumber.setdefault(slip.demonstration, set()).add(slip.leaf[0])
        out = []
        for d, demo in enumerate(self._kept(slips).demos):
            actions = renumber.get(d)
            if not actions:
                out.append(demo)
                continue
            seen: Counter[str] = Counter()
            labels = []
            for action, instance in demo:
                if action in actions:
                    seen[action] += 1
                    instance = seen[action]
                labels.append((action, instance))
            out.append(tuple(labels))
        return out

    def _total(self, slips: frozenset[Deviation]) -> float:
        """The score of an explanation: the hierarchy's part and the noise's."""
        return self._structure(slips) + self._noise(Counter(s.kind for s in slips))

    def _fit(self, slips: frozenset[Deviation]) -> FittedStructure:
        """The hierarchy learned with ``slips`` taken out (a step out of place or forgotten counts as
        performed where it was slipped on, for the optional flags)."""
        fitted = self._fits.get(slips)
        if fitted is None:
            excused = [(d.demonstration, d.leaf) for d in slips if d.kind in _PUT_BACK]
            fitted = fit_structure(
                self._cleaned(slips), excused, self.structure_settings, modules=self.modules
            )
            self._fits[slips] = fitted
        return fitted

    def _structure(self, slips: frozenset[Deviation]) -> float:
        """The hierarchy's part of the score of ``slips``: the log-likelihood of the demonstrations with the
        slips undone, read jointly by :class:`~supportive.learning.order_likelihood.OrderLikelihood` with the
        settings' ``concentration`` (people's habits integrated out), and of where the slips landed, less
        ``(1/2) log n`` per frequency the hierarchy learned without them fixes."""
        self._scored.add(slips)
        cached = self._scores.get(slips)
        if cached is not None:
            return cached
        cleaned = self._cleaned(slips)
        reading = OrderLikelihood(
            self._fit(slips).htn(), shared=self._orders, concentration=self.settings.concentration
        )
        by_demo: dict[int, list[Deviation]] = {}
        for slip in slips:
            by_demo.setdefault(slip.demonstration, []).append(slip)
        restored: list[tuple[Leaf, ...]] = []
        total = 0.0
        for d, demo in enumerate(cleaned):
            mine = by_demo.get(d)
            leaves, placed = (list(demo), 0.0) if mine is None else self._restored(reading, list(demo), mine)
            if leaves is None:
                total = -math.inf
                break
            restored.append(tuple(leaves))
            total += placed
        if total > -math.inf:
            total += reading.log_probability_of_all(restored)
            total -= 0.5 * math.log(max(len(cleaned), 1)) * reading.parameters()
            self._restorations[slips] = restored
        self._scores[slips] = total
        return total

    @staticmethod
    def _restored(
        reading: OrderLikelihood, leaves: list[Leaf], slips: list[Deviation]
    ) -> tuple[list[Leaf] | None, float]:
        """A demonstration with its slips undone (the steps out of order or missing put back together, each
        at the first place the hierarchy admits it with the others: :meth:`~supportive.tasks.executions.Executions.with_insertions`;
        None when there is none) and the log-probability of where its slips landed: a step out of order
        or unknown at any of the demonstration's places, a repeated one at any place after the performance
        it repeats (where that performance stands once the slips are undone: an approximation, off by the
        slips before it, of where it stood)."""
        length = len(leaves) + sum(1 for s in slips if s.kind in _TAKEN_OUT)
        put_back = [slip.leaf for slip in sorted(slips, key=_order) if slip.kind in _PUT_BACK]
        if put_back:
            restored = reading.htn.executions.with_insertions(leaves, put_back)
            if restored is None:
                return None, -math.inf
            leaves = cast(list[Leaf], restored)
        placed = 0.0
        for slip in slips:
            if slip.kind == "repeated":
                first = next((i for i, (a, _) in enumerate(leaves) if a == slip.leaf[0]), -1)
                placed -= math.log(max(length - 1 - first, 1))
            elif slip.kind != "missing":
                placed -= math.log(max(length, 1))
        return leaves, placed

    def _noise(self, counts: Counter[str]) -> float:
        """Log-probability of which steps are slips of each kind, the rate of each integrated out under its
        beta prior (beta-binomial; :meth:`_prior`)."""
        a, b = self._prior()
        n = self.steps
        return sum(
            math.lgamma(k + a)
            + math.lgamma(n - k + b)
            - math.lgamma(n + a + b)
            - (math.lgamma(a) + math.lgamma(b) - math.lgamma(a + b))
            for k in (counts[kind] for kind in KINDS)
        )

    def _prior(self) -> tuple[float, float]:
        """The beta prior of each kind's rate: mean ``rate``, worth ``weight`` observed steps."""
        return self.settings.rate * self.settings.weight, (1.0 - self.settings.rate) * self.settings.weight


def _surprising(steps: _Steps) -> set[int]:
    """The demonstrations whose steps follow one another unusually: their :func:`_transition_surprisal` is an
    outlier (:func:`_outliers`) among all demonstrations'."""
    return _outliers(_transition_surprisal(steps))


def _transition_surprisal(steps: _Steps) -> list[float]:
    """Each demonstration's mean surprisal of its transitions, the start and end included: ``-log`` of how
    often the other demonstrations go from each step to the next, add-one smoothed over what may follow a
    step (any step or the end)."""
    leaves = steps.leaves
    start, end = len(leaves), len(leaves) + 1  # the ends of every demonstration, as two more steps
    n, longest = steps.matrix.shape
    matrix = np.full((n, longest + 2), -1, dtype=np.int64)
    matrix[:, 0] = start
    matrix[:, 1:-1] = steps.matrix
    matrix[np.arange(n), (steps.matrix >= 0).sum(axis=1) + 1] = end
    before, after = matrix[:, :-1], matrix[:, 1:]
    done = after >= 0  # a transition, not padding
    width = len(leaves) + 2
    codes = np.where(done, before * width + after, 0)
    pairs = np.bincount(codes[done], minlength=width * width)
    starts = np.bincount(before[done], minlength=width)
    vocabulary = len(leaves) + 1  # what may follow a step: a step or the end, each smoothed by one
    # a step is done once in a demonstration, so each of its transitions is its own once: the others' count is
    # one less, plus one of smoothing
    surprisal = np.where(
        done,
        -np.log(np.where(done, pairs[codes], 1) / (starts[np.where(done, before, 0)] - 1 + vocabulary)),
        0.0,
    )
    means: list[float] = (surprisal.sum(axis=1) / done.sum(axis=1)).tolist()
    return means


def _outliers(scores: Sequence[float]) -> set[int]:
    """The indices of the scores beyond Tukey's outer fence (the third quartile plus three interquartile
    ranges); none among fewer than four."""
    if len(scores) < 4:
        return set()
    low, high = np.percentile(scores, [25, 75])
    fence = high + 3.0 * (high - low)
    return {d for d, score in enumerate(scores) if score > fence}


def _robust_closure(
    start: frozenset[int], by_step: IntMatrix, need: int, known: dict[frozenset[int], _Closure]
) -> _Closure:
    """The smallest set of step ids holding ``start`` whose members are contiguous in every demonstration but
    for steps found inside its span in fewer than ``need`` demonstrations; those ``(demonstration, step)`` are
    returned apart, by step. ``by_step[i, d]``: where demonstration ``d`` does step ``i`` (-1: not at all);
    ``known``: the closures of sets met before (the closure of every set met on the way is the same)."""
    members = set(start)
    met: list[frozenset[int]] = []
    member = np.zeros(len(by_step), dtype=bool)
    while True:
        key = frozenset(members)
        found = known.get(key)
        if found is not None:
            break
        met.append(key)
        member[list(members)] = True
        where = by_step[member]
        done = where >= 0
        first = np.where(done, where, _BEYOND).min(axis=0)
        last = where.max(axis=0)  # a demonstration doing one member or none spans nothing
        inside = (by_step > first) & (by_step < last) & ~member[:, None]
        joining = np.flatnonzero(inside.sum(axis=1) >= need)
        if not len(joining):
            steps, rows = np.nonzero(inside)
            found = (key, list(zip(rows.tolist(), steps.tolist(), strict=True)))
            break
        members.update(joining.tolist())
    for key in met:
        known[key] = found
    return found


def _interleave(*ranked: list[frozenset[Deviation]]) -> list[frozenset[Deviation]]:
    """The ranked lists taken in turn, best first."""
    out: list[frozenset[Deviation]] = []
    for group in itertools.zip_longest(*ranked):
        out.extend(candidate for candidate in group if candidate is not None)
    return out


def _order(deviation: Deviation) -> tuple[int, int, Leaf, str]:
    return (deviation.demonstration, deviation.position, deviation.leaf, deviation.kind)
