"""Plane geometry of a tabletop, in centimetres: points, axis-aligned rectangles, distances.

>>> Rect(0, 0, 10, 5).overlaps(Rect(9, 4, 12, 8)), Rect(0, 0, 10, 5).overlaps(Rect(10.5, 0, 12, 5))
(True, False)
>>> round(segment_distance((0, 0), (10, 0), (5, 3), (5, 10)), 6)
3.0
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Point", "Rect", "distance", "segment_distance"]

Point = tuple[float, float]
"""A position on the table plane (x, y), centimetres."""


def distance(a: Point, b: Point) -> float:
    """The straight-line distance between two points."""
    return math.hypot(a[0] - b[0], a[1] - b[1])


@dataclass(frozen=True)
class Rect:
    """An axis-aligned rectangle [x0, x1] × [y0, y1]."""

    x0: float
    y0: float
    x1: float
    y1: float

    @property
    def center(self) -> Point:
        """The rectangle's centre."""
        return ((self.x0 + self.x1) / 2, (self.y0 + self.y1) / 2)

    @property
    def width(self) -> float:
        """Its extent along x."""
        return self.x1 - self.x0

    @property
    def height(self) -> float:
        """Its extent along y."""
        return self.y1 - self.y0

    def contains(self, point: Point) -> bool:
        """Whether ``point`` lies inside or on the border."""
        return self.x0 <= point[0] <= self.x1 and self.y0 <= point[1] <= self.y1

    def encloses(self, other: Rect) -> bool:
        """Whether ``other`` lies wholly inside."""
        return self.x0 <= other.x0 and other.x1 <= self.x1 and self.y0 <= other.y0 and other.y1 <= self.y1

    def overlaps(self, other: Rect, gap: float = 0.0) -> bool:
        """Whether the two rectangles come closer than ``gap`` (touching counts as overlap when gap > 0)."""
        return (
            self.x0 < other.x1 + gap
            and other.x0 < self.x1 + gap
            and self.y0 < other.y1 + gap
            and other.y0 < self.y1 + gap
        )

    def grown(self, margin: float) -> Rect:
        """The rectangle grown by ``margin`` on every side."""
        return Rect(self.x0 - margin, self.y0 - margin, self.x1 + margin, self.y1 + margin)


def _point_segment(p: Point, a: Point, b: Point) -> float:
    dx, dy = b[0] - a[0], b[1] - a[1]
    length = dx * dx + dy * dy
    if length == 0.0:
        return distance(p, a)
    t = max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length))
    return distance(p, (a[0] + t * dx, a[1] + t * dy))


def _cross(o: Point, a: Point, b: Point) -> float:
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def segment_distance(a: Point, b: Point, c: Point, d: Point) -> float:
    """The shortest distance between segments ab and cd (0 when they cross)."""
    d1, d2 = _cross(c, d, a), _cross(c, d, b)
    d3, d4 = _cross(a, b, c), _cross(a, b, d)
    if ((d1 > 0) != (d2 > 0)) and ((d3 > 0) != (d4 > 0)) and d1 and d2 and d3 and d4:
        return 0.0
    return min(
        _point_segment(a, c, d), _point_segment(b, c, d), _point_segment(c, a, b), _point_segment(d, a, b)
    )
