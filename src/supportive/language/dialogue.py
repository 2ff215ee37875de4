"""A scripted conversation with the robot about how it helps (§3.3), as data: each line a person says is
parsed, grounded in the task's subtasks (Algorithm 6) and answered with the policy's explanation (Algorithm 7);
a stated preference becomes a behavior (confirmed when the robot is unsure) that later answers know about."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import replace

from supportive.language.explain import explain_behavior, explain_subtask
from supportive.language.grammar import ExplainBehavior, ExplainSubtask, Preference, parse_utterance
from supportive.language.states import TaskStates
from supportive.language.understand import Understanding
from supportive.tasks.spec import TaskSpec

__all__ = ["scripted_dialogue"]


def scripted_dialogue(spec: TaskSpec, lines: Iterable[str]) -> list[tuple[str, str]]:
    """The exchange of a person saying ``lines`` to the robot, as (``"person"`` or ``"robot"``, what) pairs;
    the robot's confirmation questions are answered ``yes``. Nothing is saved. The spec needs a structure and
    behaviors (what lines are grounded in and explained by).

    Raises:
        UnderstandingError: for a line the grammar cannot parse.
    """
    states = TaskStates.of(spec)
    understanding = Understanding(states)
    exchange: list[tuple[str, str]] = []
    for line in lines:
        exchange.append(("person", line))
        utterance = parse_utterance(line)
        if isinstance(utterance, ExplainSubtask):
            key = understanding.subtask_matcher.best(utterance.subtask_phrase).key
            exchange.append(("robot", explain_subtask(states, key).text))
        elif isinstance(utterance, ExplainBehavior):
            behavior = understanding.behavior_for(utterance.behavior_phrase)
            if behavior is not None:
                exchange.append(("robot", explain_behavior(states, behavior).text))
        elif isinstance(utterance, Preference):
            understood = understanding.apply(utterance)
            if not understood.confident:
                exchange.append(("robot", understood.confirmation))
                exchange.append(("person", "yes"))
            states = TaskStates.of(replace(spec, behaviors=(*spec.behaviors, understood.behavior)), states.structure)
            understanding = Understanding(states)
            exchange.append(("robot", f"OK. {explain_behavior(states, understood.behavior).text}"))
    return exchange
