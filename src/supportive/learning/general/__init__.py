"""The ``general`` learner (issues #13 and #23): chains, cliques, repeats and optional steps the evidence
supports, a partial order where no tree fits, slips found as noise (docs/learning.md §0).

It shares nothing with :mod:`supportive.learning.strict` (an import-linter contract keeps the two wings
independent); :class:`~supportive.learning.learner.HTNLearner` chooses between them.
"""

from supportive.learning.general.learner import GeneralResult, alternatives_of, learn_general, refit
from supportive.learning.general.noise import Deviation, NoiseEstimate, NoiseSettings, SlipSearchCache
from supportive.learning.general.structure import FittedStructure, StructureSettings

__all__ = [
    "Deviation",
    "FittedStructure",
    "GeneralResult",
    "NoiseEstimate",
    "NoiseSettings",
    "SlipSearchCache",
    "StructureSettings",
    "alternatives_of",
    "learn_general",
    "refit",
]
