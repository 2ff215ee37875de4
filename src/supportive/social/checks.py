"""Checks of what callers pass to social force and the role policies; each failure is a SocialError."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from supportive.errors import SocialError

__all__ = ["Vector", "as_point", "as_points", "positive", "within"]

Vector = tuple[float, float]


def as_point(point: ArrayLike, what: str) -> Vector:
    """``point`` as a finite ``(x, y)`` pair of floats.

    Raises:
        SocialError: naming ``what`` when it is not two numbers or one is NaN or infinite.
    """
    try:
        xy = np.asarray(point, dtype=np.float64)
    except (TypeError, ValueError):
        xy = np.empty(0)
    if xy.shape != (2,):
        raise SocialError(f"{what} must be an (x, y) pair of numbers, got {point!r}")
    x, y = float(xy[0]), float(xy[1])
    if not (math.isfinite(x) and math.isfinite(y)):
        raise SocialError(f"{what} must be finite, got ({x}, {y})")
    return x, y


def as_points(points: ArrayLike, what: str) -> NDArray[np.float64]:
    """``points`` as a finite ``(n, 2)`` float array.

    Raises:
        SocialError: naming ``what`` when the shape is wrong or a value is NaN or infinite.
    """
    try:
        xy = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError):
        raise SocialError(f"{what} must be (x, y) numbers, got {points!r}") from None
    if xy.ndim != 2 or xy.shape[1] != 2:
        raise SocialError(f"{what} must be an (n, 2) array of (x, y) pairs, got shape {xy.shape}")
    if not np.isfinite(xy).all():
        raise SocialError(f"{what} must be finite, got NaN or infinity")
    return xy


def _number(value: object) -> float:
    """``value`` as a float, NaN when it is not a number (text and booleans are not)."""
    if isinstance(value, str | bytes | bool):
        return math.nan
    try:
        return float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return math.nan


def within(value: float, name: str, low: float, high: float, *, low_included: bool = True) -> float:
    """``value`` as a float in ``[low, high]`` (``(low, high]`` when ``low_included`` is false).

    Raises:
        SocialError: naming ``name`` otherwise.
    """
    number = _number(value)
    if not (low <= number <= high and (low_included or number > low)):
        bracket = "[" if low_included else "("
        raise SocialError(f"{name} must be a number in {bracket}{low:g}, {high:g}], got {value!r}")
    return number


def positive(value: float, name: str) -> float:
    """``value`` as a float when it is positive and finite.

    Raises:
        SocialError: naming ``name`` otherwise.
    """
    number = _number(value)
    if not (math.isfinite(number) and number > 0):
        raise SocialError(f"{name} must be a positive number, got {value!r}")
    return number
