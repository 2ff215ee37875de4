"""Team fluency (§3.3.5.1, Eq. 3.1): divergences against hand-computed values, weights, reverse, smoothing."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.stats import wasserstein_distance

from supportive.language.fluency import (
    BehaviorExpectation,
    FluencyReport,
    divergence,
    earth_movers,
    team_fluency,
)

HALF = {"a": 0.5, "b": 0.5}
SKEW = {"a": 0.9, "b": 0.1}
KL_HALF_SKEW = 0.5 * math.log(0.5 / 0.9) + 0.5 * math.log(0.5 / 0.1)
KL_SKEW_HALF = 0.9 * math.log(0.9 / 0.5) + 0.1 * math.log(0.1 / 0.5)

STEPS = {"a": 0, "b": 1, "c": 2}


def path(x: Any, y: Any) -> float:
    """The path metric on a - b - c."""
    return float(abs(STEPS[x] - STEPS[y]))


def behavior(**overrides: Any) -> BehaviorExpectation:
    """A behavior whose expectations all match reality, with some fields replaced."""
    fields: dict[str, Any] = {
        "policy": HALF,
        "expected_policy": HALF,
        "initiation": HALF,
        "expected_initiation": HALF,
        "termination": HALF,
        "expected_termination": HALF,
    }
    fields.update(overrides)
    return BehaviorExpectation(**fields)


# ---------------------------------------------------------------------------------------------------------
# KL divergence


def test_kl_by_hand() -> None:
    assert divergence(HALF, SKEW, smoothing=0) == pytest.approx(KL_HALF_SKEW, rel=1e-12)
    assert divergence(SKEW, HALF, smoothing=0) == pytest.approx(KL_SKEW_HALF, rel=1e-12)


def test_kl_default_smoothing_is_close_to_exact() -> None:
    assert divergence(HALF, SKEW) == pytest.approx(KL_HALF_SKEW, abs=1e-5)


def test_kl_normalises_weights_and_accepts_arrays() -> None:
    assert divergence({"a": 5, "b": 5}, {"a": 9, "b": 1}, smoothing=0) == pytest.approx(KL_HALF_SKEW)
    assert divergence([1, 1], np.array([0.9, 0.1]), smoothing=0) == pytest.approx(KL_HALF_SKEW)
    assert divergence([1, 1], {0: 0.9, 1: 0.1}, smoothing=0) == pytest.approx(KL_HALF_SKEW)


def test_kl_aligns_supports_by_key_not_order() -> None:
    assert divergence({"b": 0.5, "a": 0.5}, {"a": 0.9, "b": 0.1}, smoothing=0) == pytest.approx(KL_HALF_SKEW)
    # q has an outcome p lacks: it contributes 0 to Σ p log(p/q)
    assert divergence({"a": 1.0}, {"a": 0.5, "b": 0.5}, smoothing=0) == pytest.approx(math.log(2))


def test_zero_when_equal() -> None:
    assert divergence(HALF, HALF) == 0.0
    assert divergence(SKEW, dict(SKEW), smoothing=0) == 0.0
    assert divergence({1: 0.2, 2: 0.8}, {1: 0.2, 2: 0.8}, kind="wasserstein") == 0.0
    assert earth_movers(HALF, HALF, path) == pytest.approx(0.0, abs=1e-12)


def test_smoothing_keeps_disjoint_supports_finite() -> None:
    p, q = {"a": 1.0}, {"b": 1.0}
    assert divergence(p, q, smoothing=0) == math.inf
    values = [divergence(p, q, smoothing=s) for s in (1e-1, 1e-3, 1e-6, 1e-9)]
    assert all(math.isfinite(v) for v in values)
    assert values == sorted(values) and len(set(values)) == len(values)  # grows as smoothing shrinks
    # by hand: add s to both outcomes of the union support {a, b}, renormalise by 1 + 2s
    s = 1e-3
    big, small = (1 + s) / (1 + 2 * s), s / (1 + 2 * s)
    expected = big * math.log(big / small) + small * math.log(small / big)
    assert values[1] == pytest.approx(expected, rel=1e-12)


# ---------------------------------------------------------------------------------------------------------
# Wasserstein / earth mover's distance


def test_wasserstein_numeric_states_match_scipy() -> None:
    p = {0.0: 0.2, 1.5: 0.3, 4.0: 0.5}
    q = {1.0: 0.6, 4.0: 0.1, 7.0: 0.3}
    expected = wasserstein_distance(list(p), list(q), list(p.values()), list(q.values()))
    assert divergence(p, q, kind="wasserstein") == pytest.approx(expected)
    assert divergence(p, q, kind="wasserstein", distance=lambda x, y: abs(x - y)) == pytest.approx(expected)


def test_wasserstein_path_metric_by_hand() -> None:
    # keep b's half in place, move a's half two steps to c: 0.5 * 2 = 1.0
    p, q = {"a": 0.5, "b": 0.5}, {"b": 0.5, "c": 0.5}
    assert earth_movers(p, q, path) == pytest.approx(1.0)
    assert divergence(p, q, kind="wasserstein", distance=path) == pytest.approx(1.0)
    assert divergence(p, q, kind="wasserstein", ground=STEPS) == pytest.approx(1.0)
    p2, q2 = {"a": 0.5, "b": 0.5}, {"c": 0.5, "b": 0.5}
    assert earth_movers(p2, q2, path) == pytest.approx(1.0)
    assert earth_movers({"a": 1}, {"c": 1}, path) == pytest.approx(2.0)


def test_wasserstein_coordinate_ground_is_euclidean() -> None:
    ground = {"door": (0.0, 0.0), "table": (3.0, 4.0), "shelf": (0.0, 4.0)}
    assert divergence({"door": 1}, {"table": 1}, kind="wasserstein", ground=ground) == pytest.approx(5.0)
    got = divergence({"door": 1, "shelf": 1}, {"table": 2}, kind="wasserstein", ground=ground)
    assert got == pytest.approx(0.5 * 5.0 + 0.5 * 3.0)


def test_wasserstein_ignores_smoothing() -> None:
    p, q = {0: 1.0}, {2: 1.0}
    assert divergence(p, q, kind="wasserstein", smoothing=0.5) == pytest.approx(2.0)


# ---------------------------------------------------------------------------------------------------------
# Team fluency


def test_team_fluency_zero_when_expectations_match() -> None:
    report = team_fluency({"robot": {"hold": behavior(), "hand": behavior()}, "arm": {"hold": behavior()}})
    assert report.total == 0.0
    assert len(report.terms) == 3
    assert all(row[2:] == (0.0, 0.0, 0.0, 0.0) for row in report.table())


def test_team_fluency_empty_is_zero() -> None:
    assert team_fluency({}).total == 0.0


def test_alpha_weights_only_the_policy_term() -> None:
    e = behavior(policy=HALF, expected_policy=SKEW, alpha=2.0, beta=1.0, gamma=1.0)
    term = team_fluency({"robot": {"hold": e}}, smoothing=0).terms[("robot", "hold")]
    assert term.policy == pytest.approx(KL_HALF_SKEW)
    assert term.initiation == 0.0 and term.termination == 0.0
    assert term.weighted == pytest.approx(2.0 * KL_HALF_SKEW / 4.0)
    # raising β or γ only dilutes the policy term (normalised by α + β + γ)
    e2 = behavior(policy=HALF, expected_policy=SKEW, alpha=2.0, beta=5.0, gamma=1.0)
    assert team_fluency({"r": {"h": e2}}, smoothing=0).total == pytest.approx(2.0 * KL_HALF_SKEW / 8.0)


def test_weights_are_normalised_by_their_sum() -> None:
    diverging = {
        "policy": HALF,
        "expected_policy": SKEW,
        "initiation": SKEW,
        "expected_initiation": HALF,
        "termination": {"a": 0.3, "b": 0.7},
        "expected_termination": HALF,
    }
    one = team_fluency({"r": {"h": behavior(**diverging, alpha=1, beta=2, gamma=3)}}, smoothing=0)
    ten = team_fluency({"r": {"h": behavior(**diverging, alpha=10, beta=20, gamma=30)}}, smoothing=0)
    assert one.total == pytest.approx(ten.total)
    t = one.terms[("r", "h")]
    assert t.weighted == pytest.approx((1 * t.policy + 2 * t.initiation + 3 * t.termination) / 6)
    only_term = team_fluency({"r": {"h": behavior(**diverging, alpha=0, beta=0, gamma=7)}}, smoothing=0)
    assert only_term.total == pytest.approx(t.termination)


def test_zero_weight_ignores_an_infinite_component() -> None:
    e = behavior(policy={"a": 1}, expected_policy={"b": 1}, alpha=0.0)
    report = team_fluency({"r": {"h": e}}, smoothing=0)
    assert report.terms[("r", "h")].policy == math.inf
    assert report.total == 0.0


def test_forward_formulation_argument_order() -> None:
    e = behavior(
        policy=HALF, expected_policy=SKEW, initiation=HALF, expected_initiation=SKEW,
        termination=HALF, expected_termination=SKEW,
    )  # fmt: skip
    t = team_fluency({"r": {"h": e}}, smoothing=0).terms[("r", "h")]
    assert t.policy == pytest.approx(KL_HALF_SKEW)  # D(reality ‖ expectation)
    assert t.initiation == pytest.approx(KL_SKEW_HALF)  # D(expectation ‖ reality)
    assert t.termination == pytest.approx(KL_SKEW_HALF)


def test_reverse_differs_and_equals_swapped_arguments() -> None:
    e = behavior(
        initiation=HALF, expected_initiation=SKEW, termination=SKEW, expected_termination=HALF, gamma=3
    )
    forward = team_fluency({"r": {"h": e}}, smoothing=0)
    reverse = team_fluency({"r": {"h": e}}, smoothing=0, reverse=True)
    assert reverse.reverse and not forward.reverse
    assert forward.total != pytest.approx(reverse.total)
    f, r = forward.terms[("r", "h")], reverse.terms[("r", "h")]
    assert f.initiation == pytest.approx(KL_SKEW_HALF)  # D(E[init] ‖ init)
    assert r.initiation == pytest.approx(KL_HALF_SKEW)  # D(init ‖ E[init])
    assert (r.initiation, r.termination) == pytest.approx((f.termination, f.initiation))
    # reverse on e is forward on e with reality and expectation swapped for init and term
    swapped = behavior(
        initiation=SKEW, expected_initiation=HALF, termination=HALF, expected_termination=SKEW, gamma=3
    )
    assert reverse.total == pytest.approx(team_fluency({"r": {"h": swapped}}, smoothing=0).total)


def test_reverse_leaves_the_policy_term_alone() -> None:
    e = behavior(policy=HALF, expected_policy=SKEW)
    assert team_fluency({"r": {"h": e}}, reverse=True).total == pytest.approx(
        team_fluency({"r": {"h": e}}).total
    )


def test_team_fluency_wasserstein_with_distance() -> None:
    e = behavior(
        policy={"a": 1}, expected_policy={"c": 1},
        initiation={"a": 0.5, "b": 0.5}, expected_initiation={"b": 0.5, "c": 0.5},
    )  # fmt: skip
    report = team_fluency({"r": {"h": e}}, kind="wasserstein", distance=path)
    t = report.terms[("r", "h")]
    assert (t.policy, t.initiation, t.termination) == pytest.approx((2.0, 1.0, 0.0))
    assert report.total == pytest.approx(1.0)
    assert report.kind == "wasserstein"


def test_report_table_rows() -> None:
    e = behavior(policy=HALF, expected_policy=SKEW)
    report = team_fluency({"robot": {"hold": e}, "arm": {"hand": behavior()}}, smoothing=0)
    assert isinstance(report, FluencyReport)
    rows = report.table()
    assert [r[:2] for r in rows] == [("robot", "hold"), ("arm", "hand")]
    assert len(FluencyReport.columns) == len(rows[0])
    assert rows[0][2] == pytest.approx(KL_HALF_SKEW)
    assert report.total == pytest.approx(sum(r[-1] for r in rows))


# ---------------------------------------------------------------------------------------------------------
# Input errors


@pytest.mark.parametrize(
    ("p", "message"),
    [
        ({"a": -0.1, "b": 1.0}, "negative"),
        ({"a": 0.0, "b": 0.0}, "only zero"),
        ({}, "empty"),
        ({"a": math.nan}, "not finite"),
        ({"a": "x"}, "not a number"),
        (np.ones((2, 2)), "1-D"),
        ("ab", "string"),
    ],
)
def test_bad_distributions(p: Any, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        divergence(p, HALF)


def test_unknown_kind() -> None:
    with pytest.raises(ValueError, match="unknown divergence kind 'js'"):
        divergence(HALF, SKEW, kind="js")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="unknown divergence kind"):
        team_fluency({}, kind="tv")  # type: ignore[arg-type]


def test_bad_options() -> None:
    with pytest.raises(ValueError, match="smoothing"):
        divergence(HALF, SKEW, smoothing=-1)
    with pytest.raises(ValueError, match="only apply to kind='wasserstein'"):
        divergence(HALF, SKEW, distance=path)
    with pytest.raises(ValueError, match="not both"):
        divergence(HALF, SKEW, kind="wasserstein", distance=path, ground=STEPS)
    with pytest.raises(ValueError, match="numeric states or a ground metric"):
        divergence(HALF, SKEW, kind="wasserstein")
    with pytest.raises(ValueError, match="no position for state 'b'"):
        divergence(HALF, SKEW, kind="wasserstein", ground={"a": 0.0})
    with pytest.raises(ValueError, match="ground distance must be finite"):
        earth_movers(HALF, SKEW, lambda x, y: -1.0)


def test_bad_behavior_weights() -> None:
    with pytest.raises(ValueError, match="beta must be a finite number >= 0"):
        behavior(beta=-1.0)
    with pytest.raises(ValueError, match="must be positive"):
        behavior(alpha=0, beta=0, gamma=0)
    with pytest.raises(ValueError, match="expected_termination has only zero weights"):
        behavior(expected_termination={"a": 0})


def test_team_fluency_error_names_the_place() -> None:
    with pytest.raises(
        ValueError, match=r"collaborator 'robot', behavior 'hold', initiation: .*numeric states"
    ):
        team_fluency({"robot": {"hold": behavior(policy=[1, 0], expected_policy=[0, 1])}}, kind="wasserstein")
    with pytest.raises(TypeError, match="BehaviorExpectation"):
        team_fluency({"robot": {"hold": HALF}})  # type: ignore[dict-item]


# ---------------------------------------------------------------------------------------------------------
# Invariants

weights = st.floats(min_value=0.0, max_value=10.0, allow_nan=False)
outcomes = st.sampled_from(["a", "b", "c", "d"])
distributions = st.dictionaries(outcomes, weights, min_size=1).filter(lambda d: sum(d.values()) > 0)
numeric_distributions = st.dictionaries(st.integers(min_value=-5, max_value=5), weights, min_size=1).filter(
    lambda d: sum(d.values()) > 0
)


@given(distributions, distributions, st.sampled_from([0.0, 1e-9, 1e-6, 0.1]))
def test_kl_nonnegative(p: dict[str, float], q: dict[str, float], smoothing: float) -> None:
    assert divergence(p, q, smoothing=smoothing) >= 0.0
    assert divergence(p, p, smoothing=smoothing) == pytest.approx(0.0, abs=1e-9)


@given(numeric_distributions, numeric_distributions)
def test_wasserstein_symmetric_nonnegative(p: dict[int, float], q: dict[int, float]) -> None:
    pq = divergence(p, q, kind="wasserstein")
    qp = divergence(q, p, kind="wasserstein")
    assert pq >= 0.0
    assert pq == pytest.approx(qp, abs=1e-9)
    # the exact transport LP agrees with scipy's 1-D closed form
    assert earth_movers(p, q, lambda x, y: abs(x - y)) == pytest.approx(pq, abs=1e-7)


@given(distributions, distributions)
def test_earth_movers_path_metric_symmetric_nonnegative(p: dict[str, float], q: dict[str, float]) -> None:
    metric = {"a": 0, "b": 1, "c": 3, "d": 4}
    pq = earth_movers(p, q, lambda x, y: abs(metric[x] - metric[y]))
    assert pq >= 0.0
    assert pq == pytest.approx(earth_movers(q, p, lambda x, y: abs(metric[x] - metric[y])), abs=1e-7)


@given(
    st.lists(st.tuples(*[distributions] * 6, weights, weights, weights), min_size=1, max_size=3),
    st.booleans(),
)
def test_fluency_nonnegative(
    rows: list[tuple[Any, ...]],
    reverse: bool,
) -> None:
    behaviors: dict[str, BehaviorExpectation] = {}
    for i, row in enumerate(rows):
        alpha, beta, gamma = row[6:]
        if alpha + beta + gamma <= 0:
            alpha = 1.0
        names = ("policy", "expected_policy", "initiation", "expected_initiation", "termination")
        dists = dict(zip((*names, "expected_termination"), row[:6], strict=True))
        behaviors[f"b{i}"] = BehaviorExpectation(**dists, alpha=alpha, beta=beta, gamma=gamma)
    report = team_fluency({"robot": behaviors}, reverse=reverse)
    assert report.total >= 0.0
    assert all(t.weighted >= 0.0 for t in report.terms.values())
