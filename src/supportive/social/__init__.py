"""Social force and the roles it gives a robot (§3.4): student, peer, instructor.

* :class:`SocialForce` turns a stream of an agent's hand positions into an ellipse of where it is about to be
  and a force field in ``[0, 1]`` (§3.4.4); :class:`ForceField` combines several named agents.
* :class:`StudentPolicy` (attractive force) and :class:`PeerPolicy` (repulsive force) choose among
  :class:`Candidate` subtasks and return a :class:`RoleDecision` (§3.4.3, §3.4.5.1–2).
* :class:`InstructorPolicy` demonstrates skills in growing stages of their keyframes until the student's force
  at the skill reaches a trigger (§3.4.5.3).
* :class:`TaskBoard` is the shared task tree agents claim subtasks from (§3.4.3); the board service
  (:mod:`supportive.service`) keeps it in a database and serves it.

See docs/social.md for the model and every reading of the thesis it takes.
"""

from supportive.social.board import BoardNode, TaskBoard
from supportive.social.ellipse import ForceEllipse, fit_ellipse
from supportive.social.field import ForceField
from supportive.social.force import ForceSource, SocialForce
from supportive.social.instructor import InstructorPolicy, demonstrable
from supportive.social.reading import reading
from supportive.social.roles import Candidate, PeerPolicy, RoleAction, RoleDecision, StudentPolicy

__all__ = [
    "BoardNode",
    "Candidate",
    "ForceEllipse",
    "ForceField",
    "ForceSource",
    "InstructorPolicy",
    "PeerPolicy",
    "RoleAction",
    "RoleDecision",
    "SocialForce",
    "StudentPolicy",
    "TaskBoard",
    "demonstrable",
    "fit_ellipse",
    "reading",
]
