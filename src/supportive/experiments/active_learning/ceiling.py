"""The ceiling the instructor model sets: every demonstration a simulated instructor could give, whatever
the learner asks.

A :class:`~supportive.learning.instructors.SimulatedInstructor` follows her path for the day and changes it
only for a query she can fit in within her horizon, and queries come only at the schedule's steps. So under
a given schedule each demonstration she gives is one of a small set: the demonstrations reached by asking,
at each scheduled step, for nothing or for any action she would heed there. No strategy can show the
learner anything outside those sets, so the known paths of the task graph of *all* of them bound what any
strategy could reach with the same instructor (a task graph's paths only grow as demonstrations are added).
The bound is loose where the sets are large (it pools every branch, a learner sees one per demonstration),
tight where a task's freedom lies beyond the queries' reach — which is what it is for: telling a strategy's
limit from the instructor model's.

>>> from supportive.learning.active import QuerySchedule
>>> from supportive.learning.instructors import SimulatedInstructor
>>> from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode
>>> task = ChainNode((ActionNode("a"), CliqueNode((ActionNode("b"), ActionNode("c"), ActionNode("d")))))
>>> person = SimulatedInstructor(task, perturbation=0.0)
>>> sorted(reachable_demonstrations(person, QuerySchedule(after_steps=(1,)), 0, ["a", "b", "c", "d"]))
[('a', 'b', 'c', 'd'), ('a', 'c', 'b', 'd'), ('a', 'd', 'b', 'c')]
"""

from __future__ import annotations

import copy
from collections import Counter
from collections.abc import Iterable, Sequence

from supportive.learning.active import QuerySchedule
from supportive.learning.instructors import SimulatedInstructor
from supportive.tasks.task_graph import TaskGraph

__all__ = ["ceiling_paths", "reachable_demonstrations"]


def reachable_demonstrations(
    instructor: SimulatedInstructor,
    schedule: QuerySchedule,
    demonstration: int,
    actions: Sequence[str],
) -> set[tuple[str, ...]]:
    """Every demonstration ``instructor`` could give as demonstration number ``demonstration`` (0-based) of a
    session on ``schedule``, whatever the learner asked; the instructor is then moved past it, as a real
    demonstration would (her unprompted variation for the day is drawn exactly as
    :func:`~supportive.learning.active.run_session` draws it, so the next call sees the next day's).

    Within a demonstration the instructor's next step depends on what is done (as a set: she picks among
    the actions allowed next by her preference for the day) and on the query she is following, if any (the
    latest heeded one, until its action is done), so the possible rest of a demonstration is computed once
    per such state.

    Args:
        instructor: The instructor (advanced by one demonstration).
        schedule: When the learner may ask.
        demonstration: The demonstration's index in the session (the schedule may skip the first ones).
        actions: Everything the learner could ask for.
    """
    instructor.begin_demonstration()  # as run_session does; the first next_action begins again
    memo: dict[tuple[object, ...], frozenset[tuple[str, ...]]] = {}
    found: set[tuple[str, ...]] = set()
    for query in _queries(instructor, schedule, demonstration, (), 0, actions):
        # At the start she draws her path for the day, so each branch gets a full copy of her (the same
        # draws in each); later steps draw nothing, and a shallow copy is a snapshot.
        person = copy.deepcopy(instructor)
        first = person.next_action((), query)
        if first is None:
            found.add(())
            continue
        target = _target_after(query, (), first)
        rest = _rest(person, (first,), target, int(query is not None), schedule, demonstration, actions, memo)
        found.update((first, *tail) for tail in rest)
    instructor.next_action((), None)  # the second draw of the day, as in a real demonstration
    return found


def _rest(
    person: SimulatedInstructor,
    done: tuple[str, ...],
    target: tuple[str, int] | None,
    asked: int,
    schedule: QuerySchedule,
    demonstration: int,
    actions: Sequence[str],
    memo: dict[tuple[object, ...], frozenset[tuple[str, ...]]],
) -> frozenset[tuple[str, ...]]:
    """Every way the demonstration can go on from ``done`` while the instructor follows ``target``."""
    limited = schedule.max_per_demonstration is not None and schedule.max_per_demonstration < len(
        schedule.after_steps
    )
    key = (frozenset(Counter(done).items()), target, asked if limited else 0)  # asked matters only if limited
    cached = memo.get(key)
    if cached is not None:
        return cached
    out: set[tuple[str, ...]] = set()
    for query in _queries(person, schedule, demonstration, done, asked, actions):
        branch = copy.copy(person)
        action = branch.next_action(done, query)
        if action is None:
            out.add(())
            continue
        following = (
            _target_after(query, done, action) if query is not None else _done_with(target, done, action)
        )
        tails = _rest(
            branch, (*done, action), following, asked + int(query is not None), schedule, demonstration,
            actions, memo,
        )  # fmt: skip
        out.update((action, *tail) for tail in tails)
    memo[key] = result = frozenset(out)
    return result


def _target_after(query: str | None, done: tuple[str, ...], action: str) -> tuple[str, int] | None:
    """The query the instructor follows after heeding ``query`` at ``done`` and doing ``action``."""
    if query is None:
        return None
    return _done_with((query, done.count(query) + 1), done, action)


def _done_with(target: tuple[str, int] | None, done: tuple[str, ...], action: str) -> tuple[str, int] | None:
    """``target``, or None once ``action`` performed it (she then follows her preference again)."""
    if target is not None and target == (action, done.count(action) + 1):
        return None
    return target


def _queries(
    person: SimulatedInstructor,
    schedule: QuerySchedule,
    demonstration: int,
    done: tuple[str, ...],
    asked: int,
    actions: Sequence[str],
) -> list[str | None]:
    """No query, and every query the instructor would heed now (an ignored query changes nothing, so it is
    the same branch as none)."""
    if not schedule.should_query(demonstration=demonstration, step=len(done), asked=asked):
        return [None]
    heeded = []
    for action in actions:
        steps = person.steps_to(done, action)
        if steps is not None and steps <= person.horizon:
            heeded.append(action)
    return [None, *heeded]


def ceiling_paths(demonstrations: Iterable[Iterable[tuple[str, ...]]]) -> int:
    """Known paths of the task graph of every demonstration in the given sets (pooled)."""
    graph = TaskGraph()
    count = 0
    for group in demonstrations:
        for actions in sorted(group):
            count += 1
            graph.add(list(actions), f"r{count}")
    return graph.path_count()
