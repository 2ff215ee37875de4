"""The smallest DNF formula that describes a region of task states (§3.3.4.3).

To explain when it will start (or stop) a supportive behavior, a robot names the region of task states with
grounded predicates: "when the front frame is present and not attached to the left support, or …". Choosing
the words is a covering problem: pick conjunctions of literals (atoms and their negations) whose union covers
the *target* states and as few *irrelevant* states as possible, with as few words as possible. The thesis
poses it as an integer linear program (ILP); ESPRESSO, the Boolean minimiser from logic synthesis, is the
approximate alternative. States that are neither target nor irrelevant are *don't care*: covering them costs
nothing.

The ILP here keeps the thesis's trade-off (λ weighs an irrelevant state included against a relevant state
omitted) but counts each state once; see `minimal_cover`. When the words cannot cover the region the
function raises `NoCoverError`, whose ``uncoverable`` attribute holds the states the robot has no words for;
a cover's precision (irrelevant states included, relevant ones omitted) is part of the result and
`describe_precision` puts it into a sentence.

>>> table = TruthTable.from_sets(["s0", "s1", "s2", "s3"], {"p": {"s1", "s3"}, "q": {"s2", "s3"}})
>>> cover = minimal_cover(table, {"s1", "s2", "s3"})
>>> str(cover.formula), cover.exact
('p or q', True)
>>> describe_precision(minimal_cover(table, {"s1", "s2"}, lam=0.9, full_coverage=False, max_literals=1))
'misses 2 relevant states of 2 and covers no irrelevant ones'
"""

from __future__ import annotations

import itertools
import math
import typing
from collections.abc import Hashable, Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
from scipy import sparse
from scipy.optimize import Bounds, LinearConstraint, milp

from supportive.errors import LanguageError, NoCoverError
from supportive.language.dnf import DNF, Conjunction, Literal, TruthTable, simplify

__all__ = [
    "ESPRESSO_MAX_ATOMS",
    "Cover",
    "CoverMethod",
    "describe_precision",
    "exact_formula",
    "minimal_cover",
]

_SHOWN_STATES = 10  # states a message lists before "… and N more"

CoverMethod = typing.Literal["ilp", "espresso", "brute-force"]
"""How `minimal_cover` chooses the formula."""

ESPRESSO_MAX_ATOMS = 16
"""ESPRESSO works on the full truth table (2^n rows), so it is refused beyond this many atoms."""

_BRUTE_FORCE_MAX_CANDIDATES = 20
_MAX_CANDIDATES = 2_000_000  # conjunctions enumerated before pruning; beyond this, lower max_literals
_DOMINANCE_BLOCK = 512  # candidates compared at once when pruning dominated ones
@dataclass(frozen=True)
class Cover:
    """A DNF formula chosen to describe a region of states, and how well it does.

    Attributes:
        formula: The chosen formula.
        target: The states to describe (the relevant ones).
        covered: Every state the formula denotes (don't-care states included).
        irrelevant_included: The irrelevant states it denotes (covered − target, restricted to irrelevant).
        relevant_omitted: The target states it does not denote.
        precision: Of the covered states that count (target or irrelevant), the share that is target; 1.0
            when it covers none of them.
        recall: The share of the target it covers; 1.0 for an empty target.
        method: ``"ilp"``, ``"espresso"`` or ``"brute-force"``.
        objective: λ·|irrelevant included| − (1−λ)·|relevant covered|, the state part of the ILP's objective
            (the formula-size tie-break left out); lower is better, and it is the thesis's measure of how
            expressive the predicates are. None for ESPRESSO, which does not optimise it.
        exact: No irrelevant state included and no relevant state omitted.
        optimal: The objective is proven optimal over the candidate terms: False for ESPRESSO (a heuristic
            minimiser with its own objective) and for an ILP stopped by ``time_limit``.
    """

    formula: DNF
    target: frozenset[Hashable]
    covered: frozenset[Hashable]
    irrelevant_included: frozenset[Hashable]
    relevant_omitted: frozenset[Hashable]
    precision: float
    recall: float
    method: CoverMethod
    objective: float | None
    exact: bool
    optimal: bool = True


def exact_formula(
    table: TruthTable, region: Iterable[Hashable], within: Iterable[Hashable] | None = None, *, max_literals: int = 3
) -> DNF:
    """A formula that denotes exactly ``region`` among ``within`` (default: every state): the minimal cover
    when one of at most ``max_literals`` literals per term exists, else one clause per valuation of the atoms in
    the region, shortened with :func:`~supportive.language.dnf.simplify`.

    Raises:
        LanguageError: when a state of ``within`` outside the region has the same atoms as one inside: no formula
            over the table's atoms tells them apart.

    >>> table = TruthTable.from_sets(["s0", "s1", "s2", "s3"], {"p": {"s1", "s3"}, "q": {"s2", "s3"}})
    >>> str(exact_formula(table, ["s3"])), str(exact_formula(table, ["s3"], within=["s2", "s3"]))
    ('p and q', 'p')
    """
    inside = table.mask(DNF.true()) if within is None else table.mask_of(within)
    target = table.mask_of(region) & inside
    try:
        return minimal_cover(
            table, _states(table, target), irrelevant=_states(table, inside & ~target), max_literals=max_literals
        ).formula
    except NoCoverError:
        pass
    rows = {tuple(row) for row in table.values[target]}
    if any(tuple(row) in rows for row in table.values[inside & ~target]):
        raise LanguageError("the predicates cannot tell some states outside the region from states in it")
    clauses = tuple(
        Conjunction(frozenset(Literal(atom, bool(value)) for atom, value in zip(table.atoms, row, strict=True)))
        for row in sorted(rows)
    )
    return simplify(DNF(clauses), table, _states(table, inside))


def describe_precision(cover: Cover) -> str:
    """How precise a cover is, as a phrase to follow "this description …".

    >>> cover = Cover(DNF.of(["p"]), frozenset(range(12)), frozenset(range(14)), frozenset({12, 13}),
    ...               frozenset(), 12 / 14, 1.0, "ilp", None, False)
    >>> describe_precision(cover)
    'covers all 12 relevant states and 2 irrelevant ones'
    """
    relevant = len(cover.target)
    omitted = len(cover.relevant_omitted)
    included = len(cover.irrelevant_included)
    irrelevant = (
        "no irrelevant ones" if included == 0 else f"{included} irrelevant {_plural(included, 'one')}"
    )
    if relevant == 0:
        return f"has no relevant states to cover and covers {irrelevant}"
    if omitted == 0:
        states = "the one relevant state" if relevant == 1 else f"all {relevant} relevant states"
        return f"covers {states} and {irrelevant}"
    return f"misses {omitted} relevant {_plural(omitted, 'state')} of {relevant} and covers {irrelevant}"


def minimal_cover(
    table: TruthTable,
    target: Iterable[Hashable],
    *,
    irrelevant: Iterable[Hashable] | None = None,
    lam: float = 0.5,
    full_coverage: bool = True,
    max_literals: int = 3,
    method: CoverMethod = "ilp",
    allow_irrelevant: bool | None = None,
    time_limit: float | None = None,
) -> Cover:
    """The smallest DNF formula over the table's atoms that best covers ``target``.

    Candidate terms are the consistent conjunctions of at most ``max_literals`` literals that hold in at
    least one target state; the empty one (``true``) is among them, so a region that is everything that
    counts is said as ``true`` rather than ``p or not p``. With ``method="ilp"`` the choice is an integer
    program over binary ``x_p`` (term ``p`` is said), ``y_s`` (target state ``s`` is covered) and ``z_s``
    (irrelevant state ``s`` is included)::

        min  λ·Σ_s z_s − (1−λ)·Σ_s y_s + μ·Σ_p x_p·(1 + |p|)
        s.t. y_s ≤ Σ_{p ∋ s} x_p          for every target state s
             z_s ≥ x_p                   for every irrelevant state s and term p ∋ s
             y_s = 1                     for every target state s, when full_coverage
             z_s = 0                     for every irrelevant state s, unless allow_irrelevant

    The thesis writes the objective per term, Σ_p x_p·(λ|R(p) ∖ S_target| − (1−λ)|R(p) ∖ S_¬target|); a
    state covered by two chosen terms then counts twice (a reward for saying the same thing twice, a double
    penalty for an overlap), so here each state counts once, through ``y`` and ``z``. The last term breaks
    ties towards fewer terms and literals; μ is set below the smallest change the state terms can make
    (λ·a − (1−λ)·b for whole numbers a, b), so it never trades a state for a shorter formula (for a λ whose
    smallest change is below the solver's tolerance, about 1e-6, the tie-break may be lost; a chosen term
    that covers no target state the others miss is dropped afterwards in any case). A large λ prefers
    leaving relevant states out to taking irrelevant ones in (the thesis calls small λ conservative; in its
    own formula it is the other way round, and this follows the formula).

    Whether irrelevant states may be covered at all is ``allow_irrelevant``, by default ``not
    full_coverage``: a full cover is then exact or impossible, and `NoCoverError` names the target states
    that no conjunction of at most ``max_literals`` literals separates from the irrelevant ones (what the
    robot has no words for), while a partial cover trades states with λ. ``full_coverage=True,
    allow_irrelevant=True`` is the thesis's constraint as written: every target state covered, irrelevant
    ones included at λ each; it always succeeds (``true`` covers everything).

    How it is solved: states with the same predicate values are covered by the same terms, so the ILP is
    over *valuations* (``y`` and ``z`` per valuation, weighted by its target and irrelevant states; a
    valuation holding both kinds counts its net weight once). Terms are pruned first (those covering no
    needed valuation, that is a target one under full coverage and one worth covering otherwise; all but
    the shortest of terms covering the same valuations; terms dominated by one no longer that covers at
    least the same needed and at most the same costly valuations), and under full coverage implied
    coverage rows and irrelevant valuations every answer must include are dropped; none of this changes the
    optimum. ``z_s ≥ x_p`` is written as one row per valuation, ``|{p ∋ s}|·z_s ≥ Σ_{p ∋ s}
    x_p`` with ``z`` binary: the same integer points, and HiGHS solves it far faster (0.1 s against 9 s and
    more on noisy 1,000-state targets, measured). HiGHS runs with a zero relative gap.

    Args:
        table: The states and which atoms hold in each.
        target: The states to describe.
        irrelevant: The states the description should leave out; by default every state not in ``target``.
            States in neither are don't care: covering them is free.
        lam: λ in [0, 1], the cost of including an irrelevant state; 1−λ is the gain of covering a target one.
        full_coverage: Every target state must be covered (the thesis's Σ_{p ∋ s} x_p ≥ 1).
        max_literals: The longest conjunction considered (ILP and brute force; ESPRESSO ignores it).
        method: ``"ilp"`` (scipy's HiGHS MILP); ``"espresso"`` (pyeda's ESPRESSO on the truth table over
            the atoms, up to `ESPRESSO_MAX_ATOMS` atoms: each state's valuation is a minterm, target ones
            1, irrelevant ones 0, the rest don't care; it ignores ``lam`` and ``max_literals``); or
            ``"brute-force"`` (every set of candidate terms, smallest first, for at most 20 candidates after
            pruning; for tests).
        allow_irrelevant: Whether terms may include irrelevant states (``z_s`` free); None (the default)
            means ``not full_coverage``. For ESPRESSO, which never includes an irrelevant state it can
            avoid, it decides a valuation that is both target and irrelevant under ``full_coverage``: True
            covers it, False raises `NoCoverError`; without ``full_coverage`` such a valuation is 0.
        time_limit: Seconds the ILP may search (the other methods ignore it); when they run out the best
            cover found so far is returned with ``optimal=False``. None: no limit. Full coverage with
            irrelevant states allowed and a target that no short formula fits (a red-blue set cover) can
            take HiGHS many seconds.

    Returns:
        The cover, with its precision.

    Raises:
        NoCoverError: under ``full_coverage`` without ``allow_irrelevant``, when some target state cannot
            be separated from the irrelevant ones (its ``uncoverable`` holds them).
        LanguageError: for λ outside [0, 1], ``max_literals`` below 1, a state both target and irrelevant, an
            unknown method, ESPRESSO on more than `ESPRESSO_MAX_ATOMS` atoms, brute force with more than 20
            candidates, or more candidate conjunctions than can be enumerated.
        KeyError: for a state the table does not know.
    """
    if not 0.0 <= lam <= 1.0:
        raise LanguageError(f"lam must be in [0, 1], got {lam}")
    if max_literals < 1:
        raise LanguageError(f"max_literals must be at least 1, got {max_literals}")
    if method not in ("ilp", "espresso", "brute-force"):
        raise LanguageError(f"unknown method {method!r}: expected 'ilp', 'espresso' or 'brute-force'")
    allow = not full_coverage if allow_irrelevant is None else allow_irrelevant
    target_mask = table.mask_of(target)
    if irrelevant is None:
        irrelevant_mask = ~target_mask
    else:
        irrelevant_mask = table.mask_of(irrelevant)
        both = target_mask & irrelevant_mask
        if both.any():
            raise LanguageError(f"states both target and irrelevant: {_listing(table, both)}")
    if method == "espresso":
        formula = _espresso(table, target_mask, irrelevant_mask, full_coverage, allow)
        return _make_cover(table, formula, target_mask, irrelevant_mask, method, None, False)
    problem = _Problem.build(table, target_mask, irrelevant_mask, lam, full_coverage)
    candidates = _candidates(problem, max_literals, allow)
    if full_coverage:
        covered = candidates.cover.any(axis=0)
        lost = problem.need & ~covered
        if lost.any():
            states = np.flatnonzero(target_mask & np.isin(problem.valuation_of, np.flatnonzero(lost)))
            raise NoCoverError(
                frozenset(table.states[i] for i in states),
                f"no conjunction of at most {max_literals} literals covers these target states without "
                "also covering an irrelevant one",
                table.states,
            )
    candidates, need, costly = _reduce(problem, candidates)
    if method == "ilp":
        chosen, optimal = _solve_ilp(problem, need, costly, candidates, lam, time_limit)
    else:
        chosen, optimal = _brute_force(problem, candidates, lam), True
    chosen = _drop_redundant(problem, candidates, chosen)
    formula = DNF(tuple(sorted((candidates.conjunction(p) for p in chosen), key=lambda c: (len(c), str(c)))))
    return _make_cover(table, formula, target_mask, irrelevant_mask, method, lam, optimal)


@dataclass(frozen=True)
class _Problem:
    """The states that count, merged into valuations (states with equal predicate values), and their roles.

    A valuation's states are covered together, so what covering it is worth is its net weight
    λ·(irrelevant states) − (1−λ)·(target states). Under full coverage the valuations holding a target state
    are *needed* (covered in every feasible answer, so their weight is a constant); otherwise the needed ones
    are those whose covering gains (net weight below 0). The *costly* ones are the rest with a positive net
    weight: covering them is what z pays for.
    """

    atoms: tuple[str, ...]
    rows: np.ndarray  # (valuations, atoms) bool
    target_weight: np.ndarray  # (valuations,) int: target states per valuation
    irrelevant_weight: np.ndarray  # (valuations,) int
    valuation_of: np.ndarray  # (states,) int: each state's valuation, −1 for a don't-care state
    full_coverage: bool
    net: np.ndarray  # (valuations,) float
    need: np.ndarray  # (valuations,) bool
    costly: np.ndarray  # (valuations,) bool

    @classmethod
    def build(
        cls, table: TruthTable, target_mask: np.ndarray, irrelevant_mask: np.ndarray, lam: float, full: bool
    ) -> _Problem:
        counted = target_mask | irrelevant_mask
        valuation_of = np.full(len(table.states), -1, dtype=np.int64)
        if counted.any():
            rows, inverse = np.unique(table.values[counted], axis=0, return_inverse=True)
            valuation_of[counted] = inverse.reshape(-1)
        else:
            rows = np.zeros((0, len(table.atoms)), dtype=bool)
        target_weight = np.bincount(valuation_of[target_mask], minlength=len(rows))
        irrelevant_weight = np.bincount(valuation_of[irrelevant_mask], minlength=len(rows))
        net = lam * irrelevant_weight - (1.0 - lam) * target_weight
        net[np.abs(net) < 1e-9] = 0.0  # λ = 0.6: 0.6·2 − 0.4·3 is a tie, not −2e-16
        need = target_weight > 0 if full else net < 0
        costly = (net > 0) & ~need
        return cls(table.atoms, rows, target_weight, irrelevant_weight, valuation_of, full, net, need, costly)


@dataclass(frozen=True)
class _Candidates:
    """Candidate terms: their literals and which valuations they cover."""

    atoms: tuple[str, ...]
    columns: list[tuple[int, ...]]  # atom indices of each term
    signs: list[int]  # bit j set: the literal on columns[p][j] is positive
    lengths: np.ndarray  # (terms,) int
    cover: np.ndarray  # (terms, valuations) bool

    def conjunction(self, p: int) -> Conjunction:
        return Conjunction(
            frozenset(
                Literal(self.atoms[a], bool(self.signs[p] >> j & 1)) for j, a in enumerate(self.columns[p])
            )
        )

    def subset(self, keep: np.ndarray) -> _Candidates:
        index = np.flatnonzero(keep)
        return _Candidates(
            self.atoms,
            [self.columns[i] for i in index],
            [self.signs[i] for i in index],
            self.lengths[index],
            self.cover[index],
        )


def _candidates(problem: _Problem, max_literals: int, allow_irrelevant: bool) -> _Candidates:
    """Every consistent conjunction of 0..max_literals literals that covers a needed valuation.

    With ``allow_irrelevant`` False, terms covering an irrelevant state are left out too.
    """
    n_atoms = len(problem.atoms)
    longest = min(max_literals, n_atoms)
    total = sum(math.comb(n_atoms, k) * 2**k for k in range(longest + 1))
    if total > _MAX_CANDIDATES:
        raise LanguageError(
            f"{total} conjunctions of up to {longest} literals over {n_atoms} atoms is too many to "
            "enumerate: lower max_literals"
        )
    rows = problem.rows.astype(np.int64)
    dirty = problem.irrelevant_weight > 0
    columns: list[tuple[int, ...]] = []
    signs: list[int] = []
    lengths: list[np.ndarray] = []
    masks: list[np.ndarray] = []
    for k in range(longest + 1):
        combos = np.array(list(itertools.combinations(range(n_atoms), k)), dtype=np.int64)
        combos = combos.reshape(len(combos), k)
        codes = (rows[:, combos] << np.arange(k)).sum(axis=2)  # (valuations, combos)
        cover = codes.T[:, None, :] == np.arange(2**k)[None, :, None]  # (combos, sign patterns, valuations)
        cover = cover.reshape(len(combos) * 2**k, len(rows))
        keep = cover[:, problem.need].any(axis=1)
        if not allow_irrelevant:
            keep &= ~cover[:, dirty].any(axis=1)
        for flat in np.flatnonzero(keep):
            combo, pattern = divmod(int(flat), 2**k)
            columns.append(tuple(int(a) for a in combos[combo]))
            signs.append(pattern)
        lengths.append(np.full(int(keep.sum()), k, dtype=np.int64))
        masks.append(cover[keep])
    return _Candidates(problem.atoms, columns, signs, np.concatenate(lengths), np.concatenate(masks))


def _reduce(problem: _Problem, candidates: _Candidates) -> tuple[_Candidates, np.ndarray, np.ndarray]:
    """Shrink the problem without changing its optimum; returns the terms and the needed and costly valuations
    the ILP has to look at.

    Repeated until nothing changes:

    * terms: of those covering the same needed and costly valuations only the shortest stays, and a term is
      dropped when one no longer covers at least its needed valuations and at most its costly ones;
    * under full coverage, a needed valuation whose every term also covers another needed valuation is
      covered whenever that one is, so its constraint goes;
    * under full coverage, a costly valuation that every term covering some needed valuation also covers is
      paid for by every answer, so it cannot tell answers apart and goes.
    """
    need = problem.need.copy()
    costly = problem.costly.copy()
    while True:
        size = (len(candidates.lengths), int(need.sum()), int(costly.sum()))
        if problem.full_coverage and len(candidates.lengths):
            covers_need = candidates.cover[:, problem.need].astype(np.float32)
            if costly.any():
                covers_cost = candidates.cover[:, costly].astype(np.float32)
                forced = ((covers_need.T @ covers_cost) == covers_need.sum(axis=0)[:, None]).any(axis=0)
                costly[np.flatnonzero(costly)[forced]] = False
            rows = candidates.cover[:, need].astype(np.float32)
            degree = rows.sum(axis=0)
            inside = (rows.T @ rows) == degree[:, None]  # [i, j]: every term covering i covers j
            order = np.arange(len(degree))
            before = (degree[:, None] < degree[None, :]) | (
                (degree[:, None] == degree[None, :]) & (order[:, None] < order[None, :])
            )
            implied = (inside & before).any(axis=0)
            need[np.flatnonzero(need)[implied]] = False
        candidates = _prune(need, costly, candidates)
        if (len(candidates.lengths), int(need.sum()), int(costly.sum())) == size:
            return candidates, need, costly


def _prune(need: np.ndarray, costly: np.ndarray, candidates: _Candidates) -> _Candidates:
    """Drop duplicate and dominated terms, judged on the ``need`` and ``costly`` valuations."""
    if len(candidates.lengths) == 0:
        return candidates
    covers_need = candidates.cover[:, need]
    covers_cost = candidates.cover[:, costly]
    # Same coverage: keep the first, which is the shortest (terms are enumerated by length).
    roles = np.packbits(np.concatenate([covers_need, covers_cost], axis=1), axis=1)
    _, first = np.unique(roles, axis=0, return_index=True)
    keep = np.zeros(len(candidates.lengths), dtype=bool)
    keep[first] = True
    undominated = _undominated(covers_need[keep], covers_cost[keep], candidates.lengths[keep])
    return candidates.subset(keep).subset(undominated)


def _undominated(need: np.ndarray, cost: np.ndarray, lengths: np.ndarray) -> np.ndarray:
    """Terms no other term beats: none as short covers ⊇ their needed valuations and ⊆ their costly ones.

    Coverages are distinct (duplicates are gone), so domination is a strict partial order and every dropped
    term has an undominated one that can replace it in any answer without making the answer worse.
    """
    need_f = need.astype(np.float32)
    cost_f = cost.astype(np.float32)
    need_size = need_f.sum(axis=1)
    cost_size = cost_f.sum(axis=1)
    count = len(lengths)
    keep = np.ones(count, dtype=bool)
    for start in range(0, count, _DOMINANCE_BLOCK):
        block = slice(start, min(start + _DOMINANCE_BLOCK, count))
        # Rows: the possible dominator a; columns: the term b in this block.
        superset = (need_f @ need_f[block].T) == need_size[block][None, :]
        subset = (cost_f @ cost_f[block].T) == cost_size[:, None]
        dominated = superset & subset & (lengths[:, None] <= lengths[block][None, :])
        dominated[np.arange(start, block.stop), np.arange(block.stop - start)] = False
        keep[block] = ~dominated.any(axis=0)
    return keep


def _size_cost(lengths: np.ndarray) -> np.ndarray:
    """What a term costs to say: one for the term, one per literal."""
    return (1 + lengths).astype(np.float64)


def _state_gap(lam: float, most_irrelevant: int, most_relevant: int, full_coverage: bool) -> float:
    """The smallest positive change of λ·a − (1−λ)·b over whole a ≤ most_irrelevant, b ≤ most_relevant."""
    if full_coverage or lam in (0.0, 1.0):
        return lam if full_coverage and lam > 0 else 1.0
    a = np.arange(most_irrelevant + 1, dtype=np.float64)
    nearest = lam * a / (1.0 - lam)
    gaps = [
        np.abs(lam * a - (1.0 - lam) * np.clip(b, -most_relevant, most_relevant))
        for b in (np.floor(nearest) - 1, np.floor(nearest), np.ceil(nearest), np.ceil(nearest) + 1)
    ]
    values = np.concatenate(gaps)
    positive = values[values > 1e-12]
    return float(positive.min()) if len(positive) else 1.0


def _solve_ilp(
    problem: _Problem,
    needed: np.ndarray,
    costly: np.ndarray,
    candidates: _Candidates,
    lam: float,
    time_limit: float | None,
) -> tuple[list[int], bool]:
    """The ILP of `minimal_cover` over valuations, solved by HiGHS; returns the chosen terms and whether
    they are proven optimal (False when ``time_limit`` stopped the search).

    y is kept for the needed valuations when coverage is partial (under full coverage they are constraints),
    z for the costly valuations some term covers (forced ones cost the same in every answer and are left out).
    """
    n_terms = len(candidates.lengths)
    if n_terms == 0:
        return [], True
    full = problem.full_coverage
    need = np.flatnonzero(needed)
    touched = np.flatnonzero(costly & candidates.cover.any(axis=0))
    n_need = len(need)
    n_y = 0 if full else n_need
    n_z = len(touched)
    gap = _state_gap(lam, int(problem.irrelevant_weight.sum()), int(problem.target_weight.sum()), full)
    mu = gap / (2.0 * (min(n_terms, n_need) * (1 + int(candidates.lengths.max())) + 1))
    cost = np.concatenate(
        [mu * _size_cost(candidates.lengths), problem.net[need][:n_y], problem.net[touched]]
    )
    n_vars = n_terms + n_y + n_z
    # Coverage: Σ_{p ∋ v} x_p − y_v ≥ 0, or Σ_{p ∋ v} x_p ≥ 1 under full coverage.
    terms, valuations = np.nonzero(candidates.cover[:, need])
    rows = [valuations]
    cols = [terms]
    data = [np.ones(len(terms))]
    if n_y:
        rows.append(np.arange(n_need))
        cols.append(n_terms + np.arange(n_need))
        data.append(-np.ones(n_need))
    coverage = sparse.csr_array(
        (np.concatenate(data), (np.concatenate(rows), np.concatenate(cols))), shape=(n_need, n_vars)
    )
    constraints = [LinearConstraint(coverage, np.ones(n_need) if full else np.zeros(n_need), np.inf)]
    if n_z:
        # Inclusion: |{p ∋ v}|·z_v − Σ_{p ∋ v} x_p ≥ 0 for every costly valuation v, z_v binary: the same
        # integer points as z_v ≥ x_p for each p ∋ v, in one row per valuation instead of one per pair.
        touching = candidates.cover[:, touched]
        terms, index = np.nonzero(touching)
        degree = touching.sum(axis=0).astype(np.float64)
        inclusion = sparse.csr_array(
            (
                np.concatenate([-np.ones(len(terms)), degree]),
                (
                    np.concatenate([index, np.arange(n_z)]),
                    np.concatenate([terms, n_terms + n_y + np.arange(n_z)]),
                ),
            ),
            shape=(n_z, n_vars),
        )
        constraints.append(LinearConstraint(inclusion, 0.0, np.inf))
    # y need not be integral: with x binary the optimum sets y_v = min(1, Σ_{p ∋ v} x_p).
    integrality = np.concatenate([np.ones(n_terms), np.zeros(n_y), np.ones(n_z)])
    options: dict[str, float] = {"mip_rel_gap": 0.0}
    if time_limit is not None:
        options["time_limit"] = time_limit
    result = milp(
        cost, integrality=integrality, bounds=Bounds(0.0, 1.0), constraints=constraints, options=options
    )
    if result.x is None:  # pragma: no cover - feasibility is checked before solving
        raise LanguageError(f"the cover ILP found no answer: {result.message}")
    return [int(p) for p in np.flatnonzero(result.x[:n_terms] > 0.5)], result.status == 0


def _brute_force(problem: _Problem, candidates: _Candidates, lam: float) -> list[int]:
    """The optimum of the ILP's objective by trying every set of terms, smallest first, in exact arithmetic
    (λ read as a fraction of denominator at most 10^6, so that ties are ties).

    It scores each set on every state (forced ones included), independently of the ILP's bookkeeping.
    """
    n_terms = len(candidates.lengths)
    if n_terms > _BRUTE_FORCE_MAX_CANDIDATES:
        raise LanguageError(
            f"brute force is for at most {_BRUTE_FORCE_MAX_CANDIDATES} candidate terms, this cover has "
            f"{n_terms} after pruning: use method='ilp'"
        )
    bits = [sum(1 << int(v) for v in np.flatnonzero(row)) for row in candidates.cover]
    exact_lam = _exact(lam)
    net = [
        exact_lam * int(i) - (1 - exact_lam) * int(t)
        for i, t in zip(problem.irrelevant_weight, problem.target_weight, strict=True)
    ]
    needed = sum(1 << int(v) for v in np.flatnonzero(problem.need))
    size = [int(c) for c in _size_cost(candidates.lengths)]
    best: tuple[Fraction, int] | None = None
    chosen: list[int] = []
    # An optimal set has at most one term per needed valuation: a term covering nothing new could go.
    for k in range(min(n_terms, int(problem.need.sum())) + 1):
        for combo in itertools.combinations(range(n_terms), k):
            covered = 0
            for p in combo:
                covered |= bits[p]
            if problem.full_coverage and covered & needed != needed:
                continue
            states = sum((net[v] for v in range(len(net)) if covered >> v & 1), Fraction(0))
            key = (states, sum(size[p] for p in combo))
            if best is None or key < best:
                best, chosen = key, list(combo)
    return chosen


def _exact(lam: float) -> Fraction:
    """λ as the fraction it was meant to be (0.6 is 3/5, not the float nearest to it)."""
    return Fraction(lam).limit_denominator(1_000_000)


def _drop_redundant(problem: _Problem, candidates: _Candidates, chosen: list[int]) -> list[int]:
    """Drop chosen terms that cover no needed valuation the others miss (a safety net for the tie-break)."""
    need = candidates.cover[:, problem.need]
    kept = sorted(chosen, key=lambda p: -int(candidates.lengths[p]))
    for p in list(kept):
        others = [q for q in kept if q != p]
        rest = need[others].any(axis=0) if others else np.zeros(need.shape[1], dtype=bool)
        if not (need[p] & ~rest).any():
            kept = others
    return sorted(kept)


def _espresso(
    table: TruthTable,
    target_mask: np.ndarray,
    irrelevant_mask: np.ndarray,
    full_coverage: bool,
    allow_irrelevant: bool,
) -> DNF:
    """ESPRESSO on the truth table over the atoms: target valuations 1, irrelevant 0, the rest don't care."""
    n_atoms = len(table.atoms)
    if n_atoms > ESPRESSO_MAX_ATOMS:
        raise LanguageError(
            f"ESPRESSO minimises over the full truth table of 2^{n_atoms} rows; it is limited to "
            f"{ESPRESSO_MAX_ATOMS} atoms: use method='ilp'"
        )
    codes = table.values.astype(np.int64) @ (np.int64(1) << np.arange(n_atoms, dtype=np.int64))
    target_codes = np.unique(codes[target_mask])
    irrelevant_codes = np.unique(codes[irrelevant_mask])
    twins = np.intersect1d(target_codes, irrelevant_codes)
    if len(twins) and full_coverage and not allow_irrelevant:
        states = np.flatnonzero(target_mask & np.isin(codes, twins))
        raise NoCoverError(
            frozenset(table.states[i] for i in states),
            "these states hold exactly the predicates of some irrelevant state, so no conjunction "
            "separates them",
            table.states,
        )
    spec = np.full(2**n_atoms, "-", dtype="<U1")
    spec[irrelevant_codes] = "0"
    spec[target_codes] = "1"
    if not full_coverage:
        spec[twins] = "0"
    if not (spec == "1").any():
        return DNF(())
    if n_atoms == 0:
        return DNF.of(Conjunction.of())
    from pyeda.inter import espresso_tts, truthtable, ttvars  # type: ignore[import-untyped]

    variables = ttvars("supportive_cover_atom", n_atoms)
    (minimised,) = espresso_tts(truthtable(variables, "".join(spec)))
    return _from_pyeda(minimised, table.atoms)


def _from_pyeda(expression: typing.Any, atoms: Sequence[str]) -> DNF:
    """A pyeda expression in DNF (constant, literal, And of literals, Or of those) as a `DNF`."""
    from pyeda.boolalg.expr import AndOp, Complement, OrOp, Variable  # type: ignore[import-untyped]

    if expression.is_zero():
        return DNF(())
    if expression.is_one():
        return DNF.of(Conjunction.of())
    clauses = expression.xs if isinstance(expression, OrOp) else (expression,)
    conjunctions = []
    for clause in clauses:
        literals = clause.xs if isinstance(clause, AndOp) else (clause,)
        converted = []
        for literal in literals:
            if isinstance(literal, Variable):
                converted.append(Literal(atoms[literal.indices[0]], True))
            elif isinstance(literal, Complement):
                converted.append(Literal(atoms[(~literal).indices[0]], False))
            else:  # pragma: no cover - ESPRESSO returns sums of products
                raise TypeError(f"unexpected term {literal!r} in ESPRESSO's result")
        conjunctions.append(Conjunction(frozenset(converted)))
    return DNF(tuple(sorted(conjunctions, key=lambda c: (len(c), str(c)))))


def _make_cover(
    table: TruthTable,
    formula: DNF,
    target_mask: np.ndarray,
    irrelevant_mask: np.ndarray,
    method: CoverMethod,
    lam: float | None,
    optimal: bool,
) -> Cover:
    covered = table.mask(formula)
    hits = int((covered & target_mask).sum())
    counted = int((covered & (target_mask | irrelevant_mask)).sum())
    included = covered & irrelevant_mask
    omitted = target_mask & ~covered
    n_target = int(target_mask.sum())
    return Cover(
        formula=formula,
        target=_states(table, target_mask),
        covered=_states(table, covered),
        irrelevant_included=_states(table, included),
        relevant_omitted=_states(table, omitted),
        precision=hits / counted if counted else 1.0,
        recall=hits / n_target if n_target else 1.0,
        method=method,
        objective=None if lam is None else lam * int(included.sum()) - (1.0 - lam) * hits,
        exact=not included.any() and not omitted.any(),
        optimal=optimal,
    )


def _states(table: TruthTable, mask: np.ndarray) -> frozenset[Hashable]:
    return frozenset(table.states[i] for i in np.flatnonzero(mask))


def _listing(table: TruthTable, mask: np.ndarray) -> str:
    states = [repr(table.states[i]) for i in np.flatnonzero(mask)]
    shown = ", ".join(states[:_SHOWN_STATES])
    return shown + (f", … and {len(states) - _SHOWN_STATES} more" if len(states) > _SHOWN_STATES else "")


def _plural(count: int, word: str) -> str:
    return word if count == 1 else word + "s"
