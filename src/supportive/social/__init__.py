"""Social force and the roles it gives a robot (§3.4): student, peer, instructor.

* :class:`SocialForce` turns a stream of an agent's hand positions into an ellipse of where it is about to be
  and a force field in ``[0, 1]`` (§3.4.4); :class:`ForceField` combines several named agents.

See docs/social.md for the model and every reading of the thesis it takes.
"""

from supportive.social.ellipse import ForceEllipse, fit_ellipse
from supportive.social.field import ForceField
from supportive.social.force import ForceSource, SocialForce

__all__ = ["ForceEllipse", "ForceField", "ForceSource", "SocialForce", "fit_ellipse"]
