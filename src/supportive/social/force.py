"""Streaming social force (§3.4.4): one agent's recent end-effector positions and the field they project.

Feed it the tracked hand (or end effector) as it comes, ``update(t, (x, y))``; it keeps the samples of the
last ``window`` seconds, ``[t_now − window, t_now]``, and gives the ellipse of likely future positions and the
force at any point (see :mod:`supportive.social.ellipse` for the model and our readings of the thesis).

Samples live in one growing array, appended at the end and dropped from the front, so the window is always one
contiguous slice: an update is O(1) amortised and the ellipse is computed from the slice when first asked for
after a change (about 15 µs for 100 samples: no incremental sums are needed, and none can drift).
"""

from __future__ import annotations

import math
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from supportive.errors import SocialError
from supportive.social.checks import as_point, as_points, positive
from supportive.social.ellipse import ForceEllipse, fit_ellipse

__all__ = ["ForceSource", "SocialForce"]

_INITIAL_CAPACITY = 64


class ForceSource(Protocol):
    """Anything that gives the social force at points: a :class:`SocialForce`, a
    :class:`~supportive.social.field.ForceField`, a :class:`~supportive.social.ellipse.ForceEllipse`."""

    def field(self, points: ArrayLike) -> NDArray[np.float64]:
        """The force at each of ``points`` (an ``(n, 2)`` array), each in ``[0, 1]``."""
        ...


class SocialForce:
    """The social force of one agent, from a stream of its positions.

    Args:
        window: Seconds of history kept (the thesis's ``t_duration``, 0.75 s): longer windows soften sharp
            motions, shorter ones strengthen them.
        min_radius: The smallest half-axis of the ellipse, in the positions' unit (default 5 cm, for metres):
            a still hand still exerts force around itself.
        sigmas: Half-axes in standard deviations of the window's positions.

    Raises:
        SocialError: when a parameter is not a positive number.

    >>> force = SocialForce(window=0.75, min_radius=0.05)
    >>> for i in range(4):
    ...     force.update(0.25 * i, (0.25 * i, 0.0))   # moving right at 1 m/s
    >>> force.ellipse().center                        # led ahead of the hand, which is at x = 0.75
    (1.125, 0.0)
    >>> force.value((1.125, 0.0)), force.value((0.75, 0.3))
    (1.0, 0.0)
    """

    def __init__(self, window: float = 0.75, min_radius: float = 0.05, sigmas: float = 2.0) -> None:
        self.window = positive(window, "window")
        self.min_radius = positive(min_radius, "min_radius")
        self.sigmas = positive(sigmas, "sigmas")
        self._times = np.empty(_INITIAL_CAPACITY)
        self._points = np.empty((_INITIAL_CAPACITY, 2))
        self._start = 0
        self._end = 0
        self._now: float | None = None
        self._ellipse: ForceEllipse | None = None

    @property
    def now(self) -> float | None:
        """The latest time seen (a sample's or :meth:`advance`'s), None before any."""
        return self._now

    def __len__(self) -> int:
        """How many samples the window holds."""
        return self._end - self._start

    @property
    def samples(self) -> NDArray[np.float64]:
        """A copy of the window's positions, ``(n, 2)``, oldest first."""
        return self._points[self._start : self._end].copy()

    @property
    def times(self) -> NDArray[np.float64]:
        """A copy of the window's timestamps, oldest first."""
        return self._times[self._start : self._end].copy()

    def update(self, t: float, point: ArrayLike) -> None:
        """Add the agent's position ``point = (x, y)`` at time ``t`` (seconds) and drop samples older than
        ``t − window``.

        Raises:
            SocialError: when ``t`` is before the latest time seen, or ``t`` or the point is not finite.
        """
        x, y = as_point(point, f"the position at t={t}")
        self.advance(t)
        if self._end == len(self._times):
            self._make_room()
        self._times[self._end] = self._now
        self._points[self._end] = (x, y)
        self._end += 1
        self._ellipse = None

    def advance(self, t: float) -> None:
        """Move the clock to ``t`` without a sample (the agent is out of sight): samples older than
        ``t − window`` leave, and once all have left the agent exerts no force.

        Raises:
            SocialError: when ``t`` is before the latest time seen or not finite.
        """
        now = float(t)
        if not math.isfinite(now):
            raise SocialError(f"a timestamp must be finite, got {t!r}")
        if self._now is not None and now < self._now:
            raise SocialError(
                f"timestamp {now} s is before the latest one, {self._now} s: samples must come in time order"
            )
        self._now = now
        live = self._times[self._start : self._end]
        first = self._start + int(np.searchsorted(live, now - self.window, side="left"))
        if first != self._start:
            self._start = first
            self._ellipse = None

    def _make_room(self) -> None:
        """Move the window to the front of the arrays, doubling them when it fills more than half."""
        count = self._end - self._start
        if count > len(self._times) // 2:
            times, points = np.empty(2 * len(self._times)), np.empty((2 * len(self._times), 2))
        else:
            times, points = self._times, self._points
        times[:count] = self._times[self._start : self._end]
        points[:count] = self._points[self._start : self._end]
        self._times, self._points, self._start, self._end = times, points, 0, count

    def ellipse(self) -> ForceEllipse | None:
        """The ellipse of likely future positions, None while the window is empty."""
        if self._ellipse is None and self._end > self._start:
            self._ellipse = fit_ellipse(
                self._points[self._start : self._end], min_radius=self.min_radius, sigmas=self.sigmas
            )
        return self._ellipse

    def field(self, points: ArrayLike) -> NDArray[np.float64]:
        """The force at each of ``points`` (an ``(n, 2)`` array), in ``[0, 1]``; zeros while the window is
        empty.

        Raises:
            SocialError: when ``points`` is not ``(n, 2)`` or not finite.
        """
        ellipse = self.ellipse()
        if ellipse is None:
            return np.zeros(len(as_points(points, "points")))
        return ellipse.field(points)

    def value(self, point: ArrayLike) -> float:
        """The force at one point ``(x, y)``; see :meth:`field`."""
        return float(self.field([as_point(point, "point")])[0])
