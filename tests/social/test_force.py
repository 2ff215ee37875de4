"""Social force (§3.4.4): the ellipse of recent hand positions, the force field, the streaming window."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import SocialError
from supportive.social import ForceEllipse, SocialForce, fit_ellipse

R = 0.05  # min_radius used below


def record(force: SocialForce, path: list[tuple[float, float, float]]) -> SocialForce:
    for t, x, y in path:
        force.update(t, (x, y))
    return force


def hand_path(
    start: tuple[float, float], velocity: tuple[float, float], seconds: float, hz: float = 30.0
) -> list[tuple[float, float, float]]:
    """A recorded hand path: positions at ``hz`` moving at constant ``velocity`` (m/s) from ``start``."""
    steps = round(seconds * hz)
    return [(i / hz, start[0] + velocity[0] * i / hz, start[1] + velocity[1] * i / hz) for i in range(steps + 1)]


# ----------------------------------------------------------------------------------------- hand-checked cases
def test_a_still_hand_is_a_circle_of_min_radius_on_the_hand() -> None:
    force = record(SocialForce(min_radius=R), hand_path((0.6, 0.3), (0.0, 0.0), 1.0))
    ellipse = force.ellipse()
    assert ellipse is not None
    assert ellipse.center == pytest.approx((0.6, 0.3))
    assert ellipse.half_axes == (R, R)
    assert force.value((0.6, 0.3)) == pytest.approx(1.0)
    assert force.value((0.6 + R / 2, 0.3)) == pytest.approx(0.5)
    assert force.value((0.6, 0.3 - R / 2)) == pytest.approx(0.5)
    assert force.value((0.6 + R, 0.3)) == pytest.approx(0.0, abs=1e-12)
    assert force.value((0.9, 0.3)) == 0.0


def test_four_samples_on_a_line_by_hand() -> None:
    # x = 0, 0.1, 0.2, 0.3 at t = 0 … 0.75: mean 0.15, variance (0.15² + 0.05²)·2/4 = 0.0125
    force = record(SocialForce(window=0.75, min_radius=R, sigmas=2.0), [(0.25 * i, 0.1 * i, 0.0) for i in range(4)])
    ellipse = force.ellipse()
    assert ellipse is not None
    assert ellipse.center == pytest.approx((0.45, 0.0))  # the hand (0.3) plus its inertia 0.3 − 0.15
    assert ellipse.half_axes == pytest.approx((2 * math.sqrt(0.0125), R))
    assert ellipse.axes[0] == pytest.approx((1.0, 0.0))
    assert ellipse.rotation == pytest.approx(0.0)
    assert force.value((0.45 + math.sqrt(0.0125), 0.0)) == pytest.approx(0.5)


def test_a_moving_hand_elongates_the_ellipse_along_its_path_and_leads_it() -> None:
    direction = np.array([3.0, 4.0]) / 5.0
    velocity = 0.4 * direction  # 0.4 m/s towards the upper right
    path = hand_path((0.2, 0.1), (float(velocity[0]), float(velocity[1])), 2.0)
    force = record(SocialForce(window=0.75, min_radius=R), path)
    ellipse = force.ellipse()
    assert ellipse is not None
    hand = np.array(path[-1][1:])
    # samples in the window: t in [1.25, 2.0] at 30 Hz, 23 of them, 0.4/30 m apart
    n, spacing = 23, 0.4 / 30
    assert len(force) == n
    assert np.array(ellipse.axes[0]) == pytest.approx(direction)
    assert ellipse.half_axes[0] == pytest.approx(2 * spacing * math.sqrt((n * n - 1) / 12))
    assert ellipse.half_axes[1] == R  # nothing across the path: clamped
    lead = np.array(ellipse.center) - hand
    assert lead == pytest.approx(direction * spacing * (n - 1) / 2)  # half the window's travel ahead
    ahead, behind = hand + 0.1 * direction, hand - 0.1 * direction
    assert force.value(ahead) > force.value(hand) > force.value(behind)
    side = hand + 0.1 * np.array([-direction[1], direction[0]])
    assert force.value(side) == 0.0


def test_collinear_vertical_samples_rotate_the_major_axis_upright() -> None:
    ellipse = fit_ellipse([(1.0, 0.0), (1.0, 0.2), (1.0, 0.4)], min_radius=R, sigmas=1.0)
    assert ellipse.axes[0] == pytest.approx((0.0, 1.0))
    assert ellipse.rotation == pytest.approx(math.pi / 2)
    assert ellipse.half_axes == pytest.approx((math.sqrt(0.08 / 3), R))


def test_one_sample_and_identical_samples() -> None:
    one = fit_ellipse([(0.3, 0.2)], min_radius=R, sigmas=2.0)
    same = fit_ellipse([(0.3, 0.2)] * 7, min_radius=R, sigmas=2.0)
    for ellipse in (one, same):
        assert ellipse.center == pytest.approx((0.3, 0.2))
        assert ellipse.half_axes == (R, R)
        assert ellipse.value((0.3, 0.2)) == pytest.approx(1.0)


def test_transform_maps_the_unit_circle_onto_the_ellipse() -> None:
    ellipse = fit_ellipse([(0.0, 0.0), (0.3, 0.1), (0.5, 0.4), (0.9, 0.5)], min_radius=R, sigmas=2.0)
    t, inverse = ellipse.transform, ellipse.inverse_transform
    assert t @ inverse == pytest.approx(np.eye(3))
    assert np.linalg.det(t[:2, :2]) == pytest.approx(ellipse.half_axes[0] * ellipse.half_axes[1])  # no mirror
    angles = np.linspace(0, 2 * np.pi, 16, endpoint=False)
    circle = np.stack([np.cos(angles), np.sin(angles), np.ones_like(angles)])
    boundary = (t @ circle)[:2].T
    assert ellipse.field(boundary) == pytest.approx(np.zeros(16), abs=1e-9)
    assert ellipse.field((t @ (0.5 * circle + [[0], [0], [0.5]]))[:2].T) == pytest.approx(np.full(16, 0.5))
    points = np.random.default_rng(1).uniform(-1, 2, size=(50, 2))
    unit = (inverse @ np.vstack([points.T, np.ones(50)]))[:2]
    assert ellipse.field(points) == pytest.approx(np.maximum(0, 1 - np.linalg.norm(unit, axis=0)))


# ----------------------------------------------------------------------------------------- the window
def test_old_samples_leave_the_window() -> None:
    path = hand_path((0.0, 0.0), (0.5, 0.1), 3.0)
    force = SocialForce(window=0.75, min_radius=R)
    for t, x, y in path:
        force.update(t, (x, y))
        times = force.times
        assert times[0] >= t - 0.75 - 1e-12 and times[-1] == t
        assert len(force) == sum(1 for s, _, _ in path if t - 0.75 <= s <= t)
    kept = [(x, y) for s, x, y in path if s >= path[-1][0] - 0.75]
    assert force.samples == pytest.approx(np.array(kept))
    assert force.ellipse() == fit_ellipse(kept, min_radius=R, sigmas=2.0)


def test_the_window_holds_exactly_its_boundary() -> None:
    force = SocialForce(window=0.5, min_radius=R)
    force.update(0.0, (0.0, 0.0))
    force.update(0.5, (1.0, 0.0))
    assert len(force) == 2  # t_now − window is inside
    force.update(0.75, (1.0, 0.0))
    assert force.times.tolist() == [0.5, 0.75]


def test_advancing_without_samples_lets_the_force_fade() -> None:
    force = record(SocialForce(min_radius=R), hand_path((0.4, 0.4), (0.2, 0.0), 0.5))
    assert force.value(force.samples[-1]) > 0
    force.advance(1.0)
    assert 0 < len(force) < 16
    force.advance(1.3)
    assert len(force) == 0 and force.ellipse() is None and force.now == 1.3
    assert force.field([(0.4, 0.4), (0.5, 0.4)]).tolist() == [0.0, 0.0]
    assert force.value((0.4, 0.4)) == 0.0
    with pytest.raises(SocialError, match="before the latest"):
        force.update(1.2, (0.0, 0.0))


def test_long_streams_and_bursts_keep_the_window_exact() -> None:
    force = SocialForce(window=0.75, min_radius=R)
    rng = np.random.default_rng(3)
    positions = rng.normal(0.5, 0.1, size=(3000, 2))
    times = np.repeat(np.arange(300) * 0.01, 10)  # ten samples per timestamp: bursts
    for t, p in zip(times, positions, strict=True):
        force.update(float(t), p)
    inside = times >= times[-1] - 0.75
    assert len(force) == int(inside.sum())
    assert force.ellipse() == fit_ellipse(positions[inside], min_radius=R, sigmas=2.0)


def test_no_samples_no_force() -> None:
    force = SocialForce()
    assert force.ellipse() is None and force.now is None and len(force) == 0
    assert force.field(np.zeros((3, 2))).tolist() == [0.0, 0.0, 0.0]


# ----------------------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("point", [(math.nan, 0.0), (0.0, math.inf), (1.0,), (1.0, 2.0, 3.0), "12", None])
def test_bad_positions_are_refused(point: object) -> None:
    force = SocialForce()
    with pytest.raises(SocialError, match=r"position at t=0\.0"):
        force.update(0.0, point)  # type: ignore[arg-type]
    assert len(force) == 0 and force.now is None  # nothing was recorded


@pytest.mark.parametrize("t", [math.nan, math.inf, -math.inf])
def test_bad_timestamps_are_refused(t: float) -> None:
    with pytest.raises(SocialError, match="timestamp must be finite"):
        SocialForce().update(t, (0.0, 0.0))


def test_time_must_not_go_backwards() -> None:
    force = SocialForce()
    force.update(2.0, (0.0, 0.0))
    force.update(2.0, (0.1, 0.0))  # the same time is fine
    with pytest.raises(SocialError, match=r"timestamp 1\.5 s is before the latest one, 2\.0 s"):
        force.update(1.5, (0.0, 0.0))
    assert len(force) == 2


@pytest.mark.parametrize(
    "kwargs",
    [{"window": 0}, {"window": -1}, {"window": math.inf}, {"min_radius": 0}, {"sigmas": math.nan}, {"sigmas": "2"}],
)
def test_bad_parameters_are_refused(kwargs: dict[str, object]) -> None:
    name = next(iter(kwargs))
    with pytest.raises(SocialError, match=f"{name} must be a positive number"):
        SocialForce(**kwargs)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("points", "message"),
    [(np.zeros((3, 3)), r"\(n, 2\)"), ([(0.0, math.nan)], "finite"), ([("a", "b")], "numbers")],
)
def test_bad_query_points_are_refused(points: object, message: str) -> None:
    force = SocialForce()
    force.update(0.0, (0.0, 0.0))
    with pytest.raises(SocialError, match=message):
        force.field(points)  # type: ignore[arg-type]
    with pytest.raises(SocialError, match=message):
        SocialForce().field(points)  # type: ignore[arg-type]


def test_bad_ellipses_and_fits_are_refused() -> None:
    with pytest.raises(SocialError, match="half-axes"):
        ForceEllipse((0.0, 0.0), (1.0, 0.0), ((1.0, 0.0), (0.0, 1.0)))
    with pytest.raises(SocialError, match="axes must be a unit vector"):
        ForceEllipse((0.0, 0.0), (1.0, 1.0), ((2.0, 0.0), (0.0, 2.0)))
    with pytest.raises(SocialError, match="axes must be a unit vector"):
        ForceEllipse((0.0, 0.0), (1.0, 1.0), ((1.0, 0.0), (0.0, -1.0)))  # a mirror
    with pytest.raises(SocialError, match="at least one sample"):
        fit_ellipse(np.zeros((0, 2)), min_radius=R, sigmas=2.0)
    with pytest.raises(SocialError, match="min_radius"):
        fit_ellipse([(0.0, 0.0)], min_radius=-1.0, sigmas=2.0)


# ----------------------------------------------------------------------------------------- invariants
coordinate = st.floats(-5.0, 5.0, allow_nan=False)
samples_strategy = st.lists(st.tuples(coordinate, coordinate), min_size=1, max_size=30)
radius = st.floats(0.01, 1.0)


@given(samples_strategy, radius, st.lists(st.tuples(coordinate, coordinate), min_size=1, max_size=20))
def test_force_is_within_zero_and_one(samples: list[tuple[float, float]], r: float, queries: list[tuple[float, float]]) -> None:
    ellipse = fit_ellipse(samples, min_radius=r, sigmas=2.0)
    values = ellipse.field(np.array(queries + samples))
    assert np.all((values >= 0.0) & (values <= 1.0))
    assert ellipse.value(ellipse.center) == pytest.approx(1.0)
    assert min(ellipse.half_axes) >= r and ellipse.half_axes[0] >= ellipse.half_axes[1]


@given(samples_strategy, radius, st.floats(0.0, 0.5), st.floats(0.0, 2 * math.pi), st.floats(0.0, 1.5))
def test_force_near_one_only_near_the_centre(
    samples: list[tuple[float, float]], r: float, delta: float, angle: float, distance: float
) -> None:
    ellipse = fit_ellipse(samples, min_radius=r, sigmas=2.0)
    major = ellipse.half_axes[0]
    point = np.array(ellipse.center) + distance * major * np.array([math.cos(angle), math.sin(angle)])
    if ellipse.value(point) >= 1.0 - delta:
        assert np.linalg.norm(point - ellipse.center) <= delta * major * (1 + 1e-9) + 1e-12


@given(samples_strategy, st.floats(-100.0, 100.0), st.floats(-100.0, 100.0))
def test_translating_the_samples_translates_the_field(samples: list[tuple[float, float]], dx: float, dy: float) -> None:
    shift = np.array([dx, dy])
    xy = np.array(samples)
    before = fit_ellipse(xy, min_radius=0.05, sigmas=2.0)
    after = fit_ellipse(xy + shift, min_radius=0.05, sigmas=2.0)
    assert np.array(after.center) == pytest.approx(np.array(before.center) + shift, abs=1e-9)
    queries = np.vstack([xy, before.center, xy.mean(axis=0), np.array(before.center) + before.half_axes[0] / 2])
    assert after.field(queries + shift) == pytest.approx(before.field(queries), abs=1e-6)


@given(samples_strategy, st.floats(0.0, 2 * math.pi))
def test_rotating_the_samples_rotates_the_field(samples: list[tuple[float, float]], angle: float) -> None:
    turn = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
    xy = np.array(samples)
    before = fit_ellipse(xy, min_radius=0.05, sigmas=2.0)
    after = fit_ellipse(xy @ turn.T, min_radius=0.05, sigmas=2.0)
    assert after.half_axes == pytest.approx(before.half_axes, rel=1e-6, abs=1e-9)
    queries = np.vstack([xy, before.center, xy.mean(axis=0)])
    assert after.field(queries @ turn.T) == pytest.approx(before.field(queries), abs=1e-6)


@given(st.lists(st.tuples(st.floats(0.0, 10.0), coordinate, coordinate), min_size=1, max_size=60), st.floats(0.1, 2.0))
def test_streaming_equals_fitting_the_window(rows: list[tuple[float, float, float]], window: float) -> None:
    rows = sorted(rows, key=lambda row: row[0])
    force = SocialForce(window=window, min_radius=0.05)
    for t, x, y in rows:
        force.update(t, (x, y))
    now = rows[-1][0]
    kept = [(x, y) for t, x, y in rows if t >= now - window]
    assert force.ellipse() == fit_ellipse(kept, min_radius=0.05, sigmas=2.0)
