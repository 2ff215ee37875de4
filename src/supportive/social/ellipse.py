"""The social-force ellipse (§3.4.4): second moments of recent hand positions, pushed ahead by their inertia.

From the samples ``P`` of a window (the latest one ``p``):

* ``M`` is their covariance (population, ``1/n``: the second-order moments of the sample, defined for one
  sample too) and ``numpy.linalg.eigh`` gives its eigenvectors and eigenvalues;
* the axes lie along the eigenvectors, with half-lengths ``sigmas · sqrt(eigenvalue)``, each at least
  ``min_radius``. The thesis uses "eigenvalues as axis lengths", but an eigenvalue of a covariance is a
  *variance* (m²): taken as a length it depends on the unit (a 5 cm spread is 0.0025 "m" in metres and 25 "cm"
  in centimetres) and makes slow hands' ellipses vanish. Standard deviations are lengths; ``sigmas = 2`` covers
  about 86 % of a 2-D Gaussian spread of samples;
* the centre is ``p + c`` with the inertia ``c = p − mean(P)``. The thesis translates the ellipse "by c"; the
  moments' ellipse sits at ``mean(P)``, and translating that by ``c`` would put it back on the hand. The
  ellipse is meant as "a projection of anticipated motion", so we place it at the latest sample and move it on
  by ``c``: for a hand moving steadily at speed ``v`` over a window of ``w`` seconds, ``c ≈ v·w/2``, so the
  centre is where the hand will be half a window from now. A still hand's ellipse is centred on it.

The ellipse is the unit circle under ``T = translate(centre) · rotate(axes) · scale(half-axes)``; a point
``x`` reads ``max(0, 1 − ‖T⁻¹x‖)``: 1 at the centre, falling linearly along each ray to 0 on the boundary, 0
outside. That is our reading of "the distance of x' from the origin along each axis may be used to scale the
social force value": the distance of ``x' = T⁻¹x`` from the origin is the point's distance from the centre
measured in half-axes (the elliptical, Mahalanobis-like radius), so the force falls off with it the same way
along every axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from supportive.errors import SocialError
from supportive.social.checks import Vector, as_point, as_points, positive

__all__ = ["ForceEllipse", "fit_ellipse"]


@dataclass(frozen=True)
class ForceEllipse:
    """Where an agent is likely to be soon: an ellipse and the force it exerts.

    Attributes:
        center: The centre ``(x, y)``.
        half_axes: The half-lengths ``(major, minor)``, major first, both positive.
        axes: The unit directions ``(major, minor)`` of the axes; ``minor`` is ``major`` turned 90°
            counter-clockwise (:func:`fit_ellipse` also makes ``major`` point to ``x ≥ 0``).

    >>> e = ForceEllipse((1.0, 0.0), (2.0, 1.0), ((1.0, 0.0), (0.0, 1.0)))
    >>> e.value((1.0, 0.0)), e.value((2.0, 0.0)), e.value((3.0, 0.0)), e.value((1.0, 0.5))
    (1.0, 0.5, 0.0, 0.5)
    """

    center: Vector
    half_axes: Vector
    axes: tuple[Vector, Vector]

    def __post_init__(self) -> None:
        if not all(math.isfinite(h) and h > 0 for h in self.half_axes):
            raise SocialError(f"an ellipse's half-axes must be positive and finite, got {self.half_axes}")
        (ux, uy), (vx, vy) = self.axes
        if not (abs(ux * ux + uy * uy - 1.0) < 1e-9 and abs(vx + uy) < 1e-9 and abs(vy - ux) < 1e-9):
            raise SocialError(
                f"an ellipse's axes must be a unit vector and the same turned 90° counter-clockwise, got {self.axes}"
            )

    @property
    def rotation(self) -> float:
        """The major axis's angle from the x axis, in radians (in ``(−π/2, π/2]`` for a fitted ellipse)."""
        return math.atan2(self.axes[0][1], self.axes[0][0])

    @property
    def transform(self) -> NDArray[np.float64]:
        """The 3×3 homogeneous transform ``T`` taking the unit circle onto the ellipse (scale, rotate, then
        translate)."""
        (ux, uy), (vx, vy) = self.axes
        a, b = self.half_axes
        cx, cy = self.center
        return np.array([[ux * a, vx * b, cx], [uy * a, vy * b, cy], [0.0, 0.0, 1.0]])

    @property
    def inverse_transform(self) -> NDArray[np.float64]:
        """``T⁻¹``, taking the ellipse onto the unit circle."""
        (ux, uy), (vx, vy) = self.axes
        a, b = self.half_axes
        cx, cy = self.center
        rows = np.array([[ux / a, uy / a], [vx / b, vy / b]])
        return np.block([[rows, -(rows @ np.array([cx, cy]))[:, None]], [np.zeros((1, 2)), np.ones((1, 1))]])

    def field(self, points: ArrayLike) -> NDArray[np.float64]:
        """The force at each of ``points``, an ``(n, 2)`` array: ``max(0, 1 − ‖T⁻¹x‖)``, in ``[0, 1]``.

        Raises:
            SocialError: when ``points`` is not ``(n, 2)`` or holds a non-finite value.
        """
        xy = as_points(points, "points")
        offset = xy - np.asarray(self.center)
        unit = (offset @ np.asarray(self.axes).T) / np.asarray(self.half_axes)
        force: NDArray[np.float64] = np.maximum(0.0, 1.0 - np.hypot(unit[:, 0], unit[:, 1]))
        return force

    def value(self, point: ArrayLike) -> float:
        """The force at one point ``(x, y)``; see :meth:`field`."""
        return float(self.field([as_point(point, "point")])[0])


def fit_ellipse(samples: ArrayLike, *, min_radius: float, sigmas: float) -> ForceEllipse:
    """The ellipse of ``samples`` (an ``(n, 2)`` array in time order, ``n ≥ 1``; the last is the latest).

    Args:
        samples: The window's positions, oldest first.
        min_radius: The smallest half-axis (the same unit as the samples), positive: one sample, identical
            samples or samples on a line still give an ellipse that has an area.
        sigmas: Half-axes in standard deviations of the samples along each axis.

    Raises:
        SocialError: when there are no samples, one is not finite, or ``min_radius`` or ``sigmas`` is not
            positive.

    >>> e = fit_ellipse([(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)], min_radius=0.1, sigmas=2.0)
    >>> e.center, round(e.half_axes[0], 3), e.half_axes[1]
    ((3.0, 0.0), 1.633, 0.1)
    """
    min_radius, sigmas = positive(min_radius, "min_radius"), positive(sigmas, "sigmas")
    xy = as_points(samples, "samples")
    if len(xy) == 0:
        raise SocialError("an ellipse needs at least one sample")
    latest = xy[-1]
    mean = xy.mean(axis=0)
    offsets = xy - mean
    variances, vectors = np.linalg.eigh(offsets.T @ offsets / len(xy))
    major = vectors[:, 1]
    if major[0] < 0 or (major[0] == 0 and major[1] < 0):
        major = -major
    ux, uy = float(major[0]), float(major[1])
    spread = sigmas * np.sqrt(np.maximum(variances, 0.0))
    cx, cy = (2.0 * latest - mean).tolist()
    return ForceEllipse(
        (cx, cy),
        (max(float(spread[1]), min_radius), max(float(spread[0]), min_radius)),
        ((ux, uy), (-uy, ux)),
    )
