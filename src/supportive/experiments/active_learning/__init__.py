"""Active learning of task structure (thesis §2.2.7–2.2.10, Figures 2.10 and 2.11).

Two experiments, both with simulated instructors (:class:`~supportive.learning.instructors.SimulatedInstructor`)
teaching learners that ask for actions (:class:`~supportive.learning.active.TeachingSession`):

* ``active-learning-blocks`` (Figure 2.10): the pilot study's three block tasks, panels of 6 instructors,
  passive vs random vs distance vs connectivity queries, solo / pairs / triads pooled (:mod:`.blocks`);
* ``active-learning`` (Figure 2.11): 12 food-preparation tasks, % of valid orderings known at iterations
  4, 8, 12, one instructor vs three pooled (:mod:`.food`).

>>> from supportive.experiments import get
>>> get("active-learning").default_trials, get("active-learning-blocks").default_trials
(50, 20)
"""

from supportive.experiments.active_learning import blocks, food
from supportive.experiments.active_learning.plots import blocks_plots, food_plots
from supportive.experiments.registry import declare

__all__ = ["ACTIVE_LEARNING", "ACTIVE_LEARNING_BLOCKS", "blocks", "food"]

ACTIVE_LEARNING_BLOCKS = declare(
    name="active-learning-blocks",
    title="Active learning strategies on the block tasks: solo, pairs and triads of instructors",
    reference="§2.2.7–2.2.10, Figure 2.10",
    parts=(blocks,),
    plots=blocks_plots,
)
"""The registered Figure 2.10 experiment."""

ACTIVE_LEARNING = declare(
    name="active-learning",
    title="Active learning strategies on 12 food tasks: solo vs pooled instructors",
    reference="§2.2.10.1, Figure 2.11",
    parts=(food,),
    plots=food_plots,
)
"""The registered Figure 2.11 experiment."""
