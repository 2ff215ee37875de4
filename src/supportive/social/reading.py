"""A subtask's social-force reading: the force where its skill's end effector will go (§3.4.5).

The reading is the **largest** force at the skill's keyframes, not the mean. A skill collides with a person if
any one of its keyframes does, so the peer must see a single conflicting keyframe at full strength; a gesture
at the green block must read fully on "push the blue block", whose path only ends there; and a maximum does not
depend on how many keyframes a skill was taught with (a mean would favour skills with few keyframes). A skill
without keyframes reads 0: no social force is measured for it.
"""

from __future__ import annotations

from collections.abc import Sequence

from supportive.social.force import ForceSource

__all__ = ["reading"]


def reading(force: ForceSource, keyframes: Sequence[tuple[float, float]]) -> float:
    """The largest force at ``keyframes`` (``(x, y)`` points), 0.0 when there are none.

    >>> from supportive.social.force import SocialForce
    >>> hand = SocialForce(min_radius=0.25)
    >>> hand.update(0.0, (0.5, 0.5))
    >>> reading(hand, [(0.0, 0.0), (0.5, 0.625)]), reading(hand, [])
    (0.5, 0.0)
    """
    if not keyframes:
        return 0.0
    return float(force.field(keyframes).max())
