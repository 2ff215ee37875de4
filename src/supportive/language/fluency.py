"""Team fluency as divergence between a lead's expectations and its assistants' reality (§3.3.5.1, Eq. 3.1).

For a task lead L, supportive collaborators C and supportive behaviors A the thesis defines

    F(L, C, S, A) = Σ_{c∈C} Σ_{a∈A} (α_a+β_a+γ_a)^{-1} (α_a·D(c_π^a ‖ E^L(c_π^a))
                                                 + β_a·D(E^L(p(c_init^a)) ‖ p(c_init^a))
                                                 + γ_a·D(E^L(p(c_term^a)) ‖ p(c_term^a)))

where ``c_π^a`` is collaborator c's policy for behavior a (a distribution over the behavior's actions or
controller outcomes), ``p(c_init^a)`` and ``p(c_term^a)`` are distributions over the states in which c starts
and stops the behavior, ``E^L(·)`` is the lead's expectation of each, and α, β, γ weigh how hazardous it is
to mischaracterise the policy, the start and the end of that behavior. ``F`` is 0 when every expectation
matches reality; lower is more fluent.

``D`` is the Kullback-Leibler divergence (in nats) for partially observable or continuous settings (discretise
continuous distributions onto common bins first) and the Wasserstein / earth mover's distance for a perfectly
observable world with discrete states. ``reverse=True`` swaps the arguments of the initiation and termination
terms to ``D(p(c_init) ‖ E^L(p(c_init)))`` — the mass-covering formulation the thesis suggests for low-risk
domains; the policy term is unchanged.

Distributions are given as a mapping ``outcome -> weight`` or as a 1-D sequence / array of weights (whose
outcomes are then the indices ``0 … n-1``). Weights need not sum to one: each distribution is normalised.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar, Literal, TypeAlias

import numpy as np
import numpy.typing as npt
from scipy.optimize import linprog
from scipy.special import rel_entr
from scipy.stats import wasserstein_distance

from supportive.errors import LanguageError

__all__ = [
    "BehaviorExpectation",
    "Distribution",
    "DivergenceKind",
    "FluencyReport",
    "FluencyTerm",
    "divergence",
    "earth_movers",
    "team_fluency",
]

Distribution: TypeAlias = Mapping[Any, float] | Sequence[float] | npt.NDArray[Any]
"""A distribution: ``outcome -> weight`` or a 1-D sequence / array of weights over outcomes ``0 … n-1``."""

DivergenceKind: TypeAlias = Literal["kl", "wasserstein"]
"""``"kl"``: Kullback-Leibler divergence; ``"wasserstein"``: earth mover's distance."""

Ground: TypeAlias = Mapping[Any, float | Sequence[float] | npt.NDArray[Any]]
"""Where each state lies: a number on a line or a coordinate vector (Euclidean distance between them)."""

_KINDS: tuple[str, ...] = ("kl", "wasserstein")


# ---------------------------------------------------------------------------------------------------------
# Distributions


def _weights(dist: Distribution, name: str) -> dict[Any, float]:
    """``dist`` as an insertion-ordered ``outcome -> weight`` dict, validated (not yet normalised)."""
    if isinstance(dist, Mapping):
        items = list(dist.items())
    elif isinstance(dist, str | bytes):
        raise LanguageError(
            f"{name}: expected a mapping outcome -> weight or a 1-D sequence of weights, got a string"
        )
    else:
        try:
            array = np.asarray(dist, dtype=float)
        except (TypeError, ValueError) as exc:
            raise LanguageError(
                f"{name}: expected a mapping outcome -> weight or numeric weights ({exc})"
            ) from None
        if array.ndim != 1:
            raise LanguageError(f"{name}: an array of weights must be 1-D, got shape {array.shape}")
        items = list(enumerate(array.tolist()))
    out: dict[Any, float] = {}
    for outcome, raw in items:
        if not isinstance(raw, numbers.Real):
            raise LanguageError(f"{name}: the weight of {outcome!r} is {raw!r}, not a number")
        weight = float(raw)
        if not math.isfinite(weight):
            raise LanguageError(f"{name}: the weight of {outcome!r} is {weight}, not finite")
        if weight < 0:
            raise LanguageError(f"{name}: the weight of {outcome!r} is negative ({weight})")
        out[outcome] = weight
    if not any(w > 0 for w in out.values()):
        what = "is empty" if not out else "has only zero weights"
        raise LanguageError(f"{name} {what}: a distribution needs some positive weight")
    return out


def _normalised(weights: Mapping[Any, float]) -> dict[Any, float]:
    total = math.fsum(weights.values())
    return {k: w / total for k, w in weights.items()}


def _aligned(p: Mapping[Any, float], q: Mapping[Any, float]) -> tuple[list[Any], np.ndarray, np.ndarray]:
    """The union support (``p``'s outcomes in order, then ``q``'s new ones) and both weight vectors on it."""
    support = list(dict.fromkeys([*p, *q]))
    pv = np.array([p.get(s, 0.0) for s in support], dtype=float)
    qv = np.array([q.get(s, 0.0) for s in support], dtype=float)
    return support, pv, qv


def _check_smoothing(smoothing: float) -> float:
    value = float(smoothing)
    if not math.isfinite(value) or value < 0:
        raise LanguageError(f"smoothing must be a finite number >= 0, got {smoothing!r}")
    return value


# ---------------------------------------------------------------------------------------------------------
# Divergences


def earth_movers(p: Distribution, q: Distribution, distance: Callable[[Any, Any], float]) -> float:
    """The earth mover's (1-Wasserstein) distance between two discrete distributions, solved exactly.

    Solves the transport problem ``min Σ_ij d(x_i, y_j) T_ij`` subject to ``Σ_j T_ij = p_i``,
    ``Σ_i T_ij = q_j``, ``T >= 0`` with :func:`scipy.optimize.linprog` (HiGHS) over the outcomes with positive
    weight. Both distributions are normalised first.

    Args:
        p: The first distribution (mapping state -> weight, or 1-D weights over states ``0 … n-1``).
        q: The second distribution.
        distance: The ground metric between two states; must return finite numbers >= 0.

    Returns:
        The minimal cost of moving ``p``'s mass onto ``q``'s.

    Raises:
        LanguageError: A distribution is malformed (negative, non-finite, all-zero weights) or ``distance``
            returned a negative or non-finite value.

    Example:
        Moving half the mass two steps along the path ``a - b - c`` costs 1:

        >>> steps = {"a": 0, "b": 1, "c": 2}
        >>> path = lambda x, y: abs(steps[x] - steps[y])
        >>> round(earth_movers({"a": 0.5, "b": 0.5}, {"b": 0.5, "c": 0.5}, path), 9)
        1.0
    """
    pw = _normalised(_weights(p, "p"))
    qw = _normalised(_weights(q, "q"))
    xs = [s for s, w in pw.items() if w > 0]
    ys = [s for s, w in qw.items() if w > 0]
    cost = np.empty((len(xs), len(ys)))
    for i, x in enumerate(xs):
        for j, y in enumerate(ys):
            raw = distance(x, y)
            d = float(raw)
            if not math.isfinite(d) or d < 0:
                raise LanguageError(
                    f"distance({x!r}, {y!r}) = {raw!r}: a ground distance must be finite and >= 0"
                )
            cost[i, j] = d
    n, m = cost.shape
    if n == 1 or m == 1:  # one side is a point mass: the plan is forced
        a = np.array([pw[x] for x in xs])
        b = np.array([qw[y] for y in ys])
        return float(max(0.0, (a[:, None] * b[None, :] * cost).sum()))
    # Row sums (mass leaving x_i) and column sums (mass arriving at y_j). Both sets sum to one, so one
    # constraint is redundant: drop the last column's, or rounding in the sums can make the LP infeasible.
    a_eq = np.zeros((n + m - 1, n * m))
    for i in range(n):
        a_eq[i, i * m : (i + 1) * m] = 1.0
    for j in range(m - 1):
        a_eq[n + j, j::m] = 1.0
    b_eq = np.concatenate([[pw[x] for x in xs], [qw[y] for y in ys[:-1]]])
    result = linprog(
        cost.ravel(),
        A_eq=a_eq,
        b_eq=b_eq,
        bounds=(0, None),
        method="highs",
        # HiGHS's default 1e-7 tolerances are the size of small masses; tighten them so tiny weights count
        options={"primal_feasibility_tolerance": 1e-10, "dual_feasibility_tolerance": 1e-10},
    )
    if result.status != 0:  # pragma: no cover - the problem is always feasible and bounded
        raise RuntimeError(f"the transport problem could not be solved: {result.message}")
    return float(max(0.0, result.fun))


def _wasserstein(
    pw: dict[Any, float],
    qw: dict[Any, float],
    ground: Ground | None,
    distance: Callable[[Any, Any], float] | None,
) -> float:
    if distance is not None:
        return earth_movers(pw, qw, distance)
    support, pv, qv = _aligned(pw, qw)
    if ground is None:
        bad = [s for s in support if not isinstance(s, numbers.Real) or not math.isfinite(float(s))]
        if bad:
            raise LanguageError(
                f"kind='wasserstein' needs numeric states or a ground metric; {bad[0]!r} is not a finite number: "
                "pass ground (state -> position) or distance (state, state -> float)"
            )
        positions = np.array([float(s) for s in support])
        return float(wasserstein_distance(positions, positions, pv, qv))
    missing = [s for s in support if s not in ground]
    if missing:
        raise LanguageError(f"ground gives no position for state {missing[0]!r}")
    coords = [np.atleast_1d(np.asarray(ground[s], dtype=float)) for s in support]
    dims = {c.shape for c in coords}
    if len(dims) != 1 or next(iter(dims)) == (0,) or any(c.ndim != 1 for c in coords):
        raise LanguageError(
            f"ground positions must all be numbers or 1-D coordinates of one length, got shapes {dims}"
        )
    if not all(np.isfinite(c).all() for c in coords):
        raise LanguageError("ground positions must be finite")
    if coords[0].shape == (1,):  # positions on a line: scipy's closed form
        positions = np.array([c[0] for c in coords])
        return float(wasserstein_distance(positions, positions, pv, qv))
    where = dict(zip(support, coords, strict=True))
    return earth_movers(pw, qw, lambda x, y: float(np.linalg.norm(where[x] - where[y])))


def divergence(
    p: Distribution,
    q: Distribution,
    *,
    kind: DivergenceKind = "kl",
    smoothing: float = 1e-6,
    ground: Ground | None = None,
    distance: Callable[[Any, Any], float] | None = None,
) -> float:
    """The divergence ``D(p ‖ q)`` between two discrete distributions.

    Both distributions are first normalised to sum to one and aligned on the union of their outcomes (a
    sequence / array of weights has outcomes ``0 … n-1``; a missing outcome has weight 0).

    ``kind="kl"``: the Kullback-Leibler divergence ``Σ_x p(x) ln(p(x) / q(x))`` in nats, computed with
    :func:`scipy.special.rel_entr`. Smoothing: ``smoothing`` is added to the probability of *every* outcome of
    the union support of both distributions and each is renormalised to sum to one, so an outcome that one
    distribution gives no mass stays finite. With ``smoothing=0`` the divergence is ``inf`` when ``q`` gives
    zero probability to an outcome ``p`` gives mass to. Rounding error below zero is clipped to 0.

    ``kind="wasserstein"``: the earth mover's distance (symmetric; ``smoothing`` is not applied, as the
    distance is finite for any supports). The ground metric is, in order of precedence: ``distance`` (any
    function of two states, solved exactly with :func:`earth_movers`); ``ground``, a mapping
    state -> position on a line (:func:`scipy.stats.wasserstein_distance`) or state -> coordinate vector
    (Euclidean, solved with :func:`earth_movers`); otherwise the states themselves must be numbers.

    Args:
        p: The first distribution (mapping outcome -> weight, or 1-D weights).
        q: The second distribution.
        kind: ``"kl"`` or ``"wasserstein"``.
        smoothing: Additive smoothing for ``kind="kl"``; finite and >= 0.
        ground: For ``kind="wasserstein"``: state -> position (number or 1-D coordinate vector).
        distance: For ``kind="wasserstein"``: the ground distance between two states (give it or ``ground``).

    Returns:
        ``D(p ‖ q) >= 0``; 0 when ``p`` and ``q`` are the same distribution.

    Raises:
        LanguageError: Negative, non-finite or all-zero weights, an unknown ``kind``, a negative ``smoothing``,
            ``ground`` / ``distance`` given with ``kind="kl"`` or both given, or non-numeric states with no
            ground metric.

    Example:
        >>> round(divergence({"a": 0.5, "b": 0.5}, {"a": 0.9, "b": 0.1}, smoothing=0), 6)
        0.510826
        >>> divergence([1, 1], {0: 2, 1: 2})
        0.0
        >>> divergence({0: 1.0}, {3: 1.0}, kind="wasserstein")
        3.0
    """
    if kind not in _KINDS:
        raise LanguageError(f"unknown divergence kind {kind!r}: expected one of {', '.join(map(repr, _KINDS))}")
    smoothing = _check_smoothing(smoothing)
    pw = _normalised(_weights(p, "p"))
    qw = _normalised(_weights(q, "q"))
    if kind == "wasserstein":
        if ground is not None and distance is not None:
            raise LanguageError("give ground or distance for kind='wasserstein', not both")
        return _wasserstein(pw, qw, ground, distance)
    if ground is not None or distance is not None:
        raise LanguageError("ground and distance only apply to kind='wasserstein'")
    _, pv, qv = _aligned(pw, qw)
    if smoothing > 0:
        pv = (pv + smoothing) / (pv + smoothing).sum()
        qv = (qv + smoothing) / (qv + smoothing).sum()
    value = float(np.sum(rel_entr(pv, qv)))
    return max(0.0, value)


# ---------------------------------------------------------------------------------------------------------
# Team fluency


@dataclass(frozen=True, eq=False)
class BehaviorExpectation:
    """A lead's expectation of one supportive behavior of one collaborator, next to the reality.

    Attributes:
        policy: The collaborator's policy for the behavior ``c_π^a``: a distribution over its actions or
            controller outcomes (mapping outcome -> weight, or 1-D weights).
        expected_policy: The lead's expectation of it, ``E^L(c_π^a)``.
        initiation: The distribution over states in which the collaborator starts the behavior,
            ``p(c_init^a)`` (mapping state -> weight).
        expected_initiation: The lead's expectation of it, ``E^L(p(c_init^a))``.
        termination: The distribution over states in which the collaborator stops, ``p(c_term^a)``.
        expected_termination: The lead's expectation of it, ``E^L(p(c_term^a))``.
        alpha: Weight of the policy term (hazard of mischaracterising the execution policy); >= 0.
        beta: Weight of the initiation term (hazard of misjudging when the behavior starts); >= 0.
        gamma: Weight of the termination term (hazard of misjudging when it stops); >= 0.
            ``alpha + beta + gamma`` must be positive; the three are normalised by their sum.

    Raises:
        LanguageError: A distribution has negative, non-finite or only zero weights, or the weights are negative,
            non-finite or all zero.

    Example:
        >>> hold = BehaviorExpectation(
        ...     policy={"grip": 0.9, "release": 0.1}, expected_policy={"grip": 0.9, "release": 0.1},
        ...     initiation={"frame placed": 1}, expected_initiation={"frame placed": 1},
        ...     termination={"screwed": 1}, expected_termination={"screwed": 1}, gamma=3.0)
        >>> hold.weight_sum
        5.0
    """

    policy: Distribution
    expected_policy: Distribution
    initiation: Distribution
    expected_initiation: Distribution
    termination: Distribution
    expected_termination: Distribution
    alpha: float = 1.0
    beta: float = 1.0
    gamma: float = 1.0

    _DISTRIBUTIONS: ClassVar[tuple[str, ...]] = (
        "policy",
        "expected_policy",
        "initiation",
        "expected_initiation",
        "termination",
        "expected_termination",
    )

    def __post_init__(self) -> None:
        for name in self._DISTRIBUTIONS:
            _weights(getattr(self, name), name)
        for name in ("alpha", "beta", "gamma"):
            raw = getattr(self, name)
            if not isinstance(raw, numbers.Real) or not math.isfinite(float(raw)) or float(raw) < 0:
                raise LanguageError(f"{name} must be a finite number >= 0, got {raw!r}")
        if self.weight_sum <= 0:
            raise LanguageError("alpha + beta + gamma must be positive (at least one component must count)")

    @property
    def weight_sum(self) -> float:
        """``alpha + beta + gamma``, the normaliser of the behavior's term."""
        return float(self.alpha) + float(self.beta) + float(self.gamma)


@dataclass(frozen=True)
class FluencyTerm:
    """One collaborator's behavior in Eq. 3.1: the three component divergences and the weighted term.

    Attributes:
        collaborator: The supportive collaborator ``c``.
        behavior: The supportive behavior ``a``.
        policy: ``D(c_π^a ‖ E^L(c_π^a))``.
        initiation: ``D(E^L(p(c_init^a)) ‖ p(c_init^a))`` (arguments swapped when ``reverse``).
        termination: ``D(E^L(p(c_term^a)) ‖ p(c_term^a))`` (arguments swapped when ``reverse``).
        alpha: The policy weight.
        beta: The initiation weight.
        gamma: The termination weight.
        weighted: ``(α·policy + β·initiation + γ·termination) / (α + β + γ)``.
    """

    collaborator: str
    behavior: str
    policy: float
    initiation: float
    termination: float
    alpha: float
    beta: float
    gamma: float
    weighted: float


@dataclass(frozen=True)
class FluencyReport:
    """Team fluency ``F`` (Eq. 3.1) and its terms; 0 is perfectly fluent, larger is less fluent.

    Attributes:
        total: ``F``, the sum of every term's ``weighted`` value.
        terms: Per ``(collaborator, behavior)``, its :class:`FluencyTerm`, in input order.
        kind: The divergence used (``"kl"`` or ``"wasserstein"``).
        reverse: Whether the initiation / termination terms used the reverse formulation.
    """

    total: float
    terms: Mapping[tuple[str, str], FluencyTerm] = field(default_factory=dict)
    kind: DivergenceKind = "kl"
    reverse: bool = False

    columns: ClassVar[tuple[str, ...]] = (
        "collaborator",
        "behavior",
        "policy",
        "initiation",
        "termination",
        "weighted",
    )
    """The headers of :meth:`table`'s rows."""

    def table(self) -> list[tuple[str, str, float, float, float, float]]:
        """One row per term, matching :attr:`columns`, for printing.

        Returns:
            ``(collaborator, behavior, policy, initiation, termination, weighted)`` rows in input order.
        """
        return [
            (t.collaborator, t.behavior, t.policy, t.initiation, t.termination, t.weighted)
            for t in self.terms.values()
        ]


def team_fluency(
    expectations: Mapping[str, Mapping[str, BehaviorExpectation]],
    *,
    kind: DivergenceKind = "kl",
    reverse: bool = False,
    smoothing: float = 1e-6,
    distance: Callable[[Any, Any], float] | None = None,
    ground: Ground | None = None,
) -> FluencyReport:
    """Team fluency ``F(L, C, S, A)`` of Eq. 3.1 from a lead's expectations of its collaborators.

    For each collaborator ``c`` and behavior ``a`` the term is
    ``(α·D(π ‖ E[π]) + β·D(E[init] ‖ init) + γ·D(E[term] ‖ term)) / (α + β + γ)``; ``F`` is their sum.
    With ``reverse=True`` the initiation and termination terms become ``D(init ‖ E[init])`` and
    ``D(term ‖ E[term])`` (the policy term is unchanged). For ``kind="wasserstein"`` the distance is
    symmetric, so ``reverse`` changes nothing.

    Args:
        expectations: collaborator -> behavior -> :class:`BehaviorExpectation`.
        kind: ``"kl"`` (partially observable or continuous settings) or ``"wasserstein"`` (perfectly
            observable, discrete states).
        reverse: Use the reverse (mass-covering) formulation for initiation and termination.
        smoothing: Additive smoothing for ``kind="kl"`` (see :func:`divergence`).
        distance: For ``kind="wasserstein"``: ground distance between two outcomes / states.
        ground: For ``kind="wasserstein"``: outcome / state -> position (number or coordinate vector).

    Returns:
        A :class:`FluencyReport`; its ``total`` is ``F >= 0``.

    Raises:
        LanguageError: As :func:`divergence`; the message names the collaborator, behavior and component.
        TypeError: A value of ``expectations`` is not a :class:`BehaviorExpectation`.

    Example:
        >>> same = {"grip": 1.0}
        >>> hand = BehaviorExpectation(
        ...     policy={"reach": 0.5, "hand over": 0.5}, expected_policy={"reach": 0.9, "hand over": 0.1},
        ...     initiation=same, expected_initiation=same, termination=same, expected_termination=same)
        >>> report = team_fluency({"robot": {"hand screwdriver": hand}}, smoothing=0)
        >>> round(report.total, 6)  # the policy's KL (0.510826) over alpha + beta + gamma = 3
        0.170275
        >>> report.table()[0][:2]
        ('robot', 'hand screwdriver')
    """
    if kind not in _KINDS:
        raise LanguageError(f"unknown divergence kind {kind!r}: expected one of {', '.join(map(repr, _KINDS))}")
    _check_smoothing(smoothing)

    def d(p: Distribution, q: Distribution, where: str) -> float:
        try:
            return divergence(p, q, kind=kind, smoothing=smoothing, ground=ground, distance=distance)
        except ValueError as exc:
            raise LanguageError(f"{where}: {exc}") from exc

    terms: dict[tuple[str, str], FluencyTerm] = {}
    for collaborator, behaviors in expectations.items():
        for behavior, e in behaviors.items():
            where = f"collaborator {collaborator!r}, behavior {behavior!r}"
            if not isinstance(e, BehaviorExpectation):
                raise TypeError(f"{where}: expected a BehaviorExpectation, got {type(e).__name__}")
            policy = d(e.policy, e.expected_policy, f"{where}, policy")
            if reverse:
                initiation = d(e.initiation, e.expected_initiation, f"{where}, initiation")
                termination = d(e.termination, e.expected_termination, f"{where}, termination")
            else:
                initiation = d(e.expected_initiation, e.initiation, f"{where}, initiation")
                termination = d(e.expected_termination, e.termination, f"{where}, termination")
            alpha, beta, gamma = float(e.alpha), float(e.beta), float(e.gamma)
            # a component weighted 0 does not count, even when its divergence is infinite (0·inf is nan)
            parts = [(alpha, policy), (beta, initiation), (gamma, termination)]
            weighted = math.fsum(w * v for w, v in parts if w > 0) / e.weight_sum
            terms[(collaborator, behavior)] = FluencyTerm(
                collaborator, behavior, policy, initiation, termination, alpha, beta, gamma, weighted
            )
    total = math.fsum(t.weighted for t in terms.values())
    return FluencyReport(total=total, terms=terms, kind=kind, reverse=reverse)
