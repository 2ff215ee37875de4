"""A held-out demonstration replayed as contact events through the progress-aware tracker: what the robot
believed at the end of each action."""

from __future__ import annotations

from dataclasses import dataclass

from supportive.inference.observations import ObservationModel
from supportive.inference.tracker import ProgressHMM
from supportive.learning.learner import HTNLearner
from supportive.seeding import Seed, rng_from
from supportive.tasks.naming import known_names
from supportive.tasks.spec import TaskSpec

__all__ = ["WatchedStep", "watch"]


@dataclass(frozen=True)
class WatchedStep:
    """What the robot believed at the last moment of one action of a watched demonstration."""

    truth: str
    subgoal: tuple[str, float]
    subtask: tuple[str, float]
    next_subgoal: tuple[str, float]


def watch(spec: TaskSpec, held_out: int = -1, seed: Seed = 7, mean_duration: float = 4.0) -> list[WatchedStep]:
    """Learn from every demonstration but one, then replay that one as a stream of contact events (drawn from
    the task's observation model, a geometric number of moments per action) through the progress-aware tracker,
    and report the belief at the end of each action.

    Raises:
        LearningError: when an action of the spec declares no observations, or no demonstration is left.
    """
    demos = list(spec.demonstrations)
    watched = demos.pop(held_out)
    htn = HTNLearner(names=known_names(spec.structure)).fit(demos, spec.name).htn_
    model = ObservationModel.from_spec(spec)
    running = ProgressHMM(htn, model, mean_duration=mean_duration).fit().filter()
    rng = rng_from(seed)
    steps = []
    for action in watched.actions:
        for _ in range(int(rng.geometric(1.0 / mean_duration))):
            belief = running.update(model.sample(action, rng))
        steps.append(
            WatchedStep(
                truth=action,
                subgoal=running.top(belief.subgoals, running.subgoal_labels, 1)[0],
                subtask=running.top(belief.enclosing, running.enclosing_labels, 1)[0],
                next_subgoal=max(belief.next_actions.items(), key=lambda kv: (kv[1], kv[0])),
            )
        )
    return steps
