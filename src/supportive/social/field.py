"""The social force of several agents at once: one :class:`SocialForce` per named agent, combined by max.

Max, not sum: a combined force stays in ``[0, 1]``, so a threshold (a student's ``min_force``, a peer's
``halt_below``, an instructor's ``trigger``) means the same with one person in the workcell or three, and two
people moving mildly near a subtask do not add up to one person reaching into it. Where agents' ellipses
overlap, the field is the strongest of them.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from supportive.errors import SocialError
from supportive.social.checks import as_points, positive
from supportive.social.force import SocialForce

__all__ = ["ForceField"]


class ForceField:
    """Named agents' social forces, each from its own stream of positions.

    Args:
        window: Seconds of history per agent (see :class:`SocialForce`).
        min_radius: Smallest half-axis of each agent's ellipse.
        sigmas: Half-axes in standard deviations.

    Raises:
        SocialError: when a parameter is not a positive number.

    >>> field = ForceField()
    >>> field.update("alice", 0.0, (0.2, 0.3))
    >>> field.update("bob", 0.0, (1.2, 0.3))
    >>> field.agents
    ('alice', 'bob')
    >>> field.field([(0.2, 0.3), (1.2, 0.3), (0.7, 0.3)]).tolist()
    [1.0, 1.0, 0.0]
    >>> field.field([(0.2, 0.3), (1.2, 0.3)], agents=["bob"]).tolist()
    [0.0, 1.0]
    """

    def __init__(self, window: float = 0.75, min_radius: float = 0.05, sigmas: float = 2.0) -> None:
        self.window = positive(window, "window")
        self.min_radius = positive(min_radius, "min_radius")
        self.sigmas = positive(sigmas, "sigmas")
        self._forces: dict[str, SocialForce] = {}

    @property
    def agents(self) -> tuple[str, ...]:
        """The agents seen so far, in the order they first appeared."""
        return tuple(self._forces)

    def force(self, agent: str) -> SocialForce:
        """One agent's social force.

        Raises:
            SocialError: for an agent never updated.
        """
        if agent not in self._forces:
            known = ", ".join(self._forces) or "none yet"
            raise SocialError(f"no agent {agent!r} in the force field (agents: {known})")
        return self._forces[agent]

    def update(self, agent: str, t: float, point: ArrayLike) -> None:
        """Add ``agent``'s position at time ``t``; a new name starts a new agent.

        Raises:
            SocialError: as :meth:`SocialForce.update`.
        """
        if agent not in self._forces:
            self._forces[agent] = SocialForce(self.window, self.min_radius, self.sigmas)
        self._forces[agent].update(t, point)

    def advance(self, t: float) -> None:
        """Move every agent's clock to ``t`` (see :meth:`SocialForce.advance`).

        Raises:
            SocialError: when ``t`` is before some agent's latest time.
        """
        for force in self._forces.values():
            force.advance(t)

    def forces_at(self, points: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """Each agent's force at each of ``points`` (``(n, 2)``), by agent.

        Raises:
            SocialError: when ``points`` is not ``(n, 2)`` or not finite.
        """
        xy = as_points(points, "points")
        return {agent: force.field(xy) for agent, force in self._forces.items()}

    def field(self, points: ArrayLike, agents: Iterable[str] | None = None) -> NDArray[np.float64]:
        """The combined force at each of ``points``: the largest of the agents' (all of them, or only
        ``agents``); zeros when there are none.

        Raises:
            SocialError: for an unknown agent, or ``points`` not ``(n, 2)`` or not finite.
        """
        xy = as_points(points, "points")
        names = self.agents if agents is None else tuple(agents)
        combined = np.zeros(len(xy))
        for name in names:
            np.maximum(combined, self.force(name).field(xy), out=combined)
        return combined
