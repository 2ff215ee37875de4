"""Goal inference over a ROS bag: a contacts topic streamed through a goal filter, each frame's belief printed
as ``supportive infer`` prints it and, optionally, written back as a new bag beside the recording.

:func:`belief_record` is the one place a belief becomes a message: the JSON record ``infer`` prints for
``--observations`` and for ``--bag`` alike, and the bag's topics are made from it.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from contextlib import AbstractContextManager, nullcontext
from pathlib import Path
from typing import Any

from supportive.inference.filtering import Belief, Filter

__all__ = ["belief_record", "infer_bag"]


def belief_record(running: Filter, belief: Belief, top: int, time: float | None) -> dict[str, Any]:
    """A belief of any :class:`~supportive.inference.filtering.Filter` as plain data: the filter's summary (the
    ``top`` most probable current subgoals, enclosing subtasks and next subgoals — those at probability 0 left
    out, but for the first of each list — the step and the log-likelihood), the frame's ``time`` in seconds when
    known, and ``surprise`` when the belief has such an attribute (a filter that measures how unexpected each
    observation was; without one the key is left out).

    >>> from supportive.learning import HTNLearner
    >>> from supportive.inference import HierarchicalHMM, ObservationModel
    >>> htn = HTNLearner().fit([["a", "b"]]).htn_
    >>> running = HierarchicalHMM(htn, ObservationModel({"a": {"x": .9}, "b": {"y": .9}})).fit().filter()
    >>> record = belief_record(running, running.update({"x"}), 1, 12.5)
    >>> record["subgoals"], record["time"], "surprise" in record
    ([['a', 1.0]], 12.5, False)
    """
    record: dict[str, Any] = running.summary(belief, top)
    for key in ("subgoals", "subtasks", "next"):  # an entry at probability 0 says nothing: left out
        entries = record.get(key)
        if isinstance(entries, list) and entries:
            record[key] = [e for e in entries if e[1] > 0] or entries[:1]
    surprise = getattr(belief, "surprise", None)
    if surprise is not None:
        record["surprise"] = float(surprise)
    if time is not None:
        record["time"] = time
    return record


def infer_bag(
    record: Callable[[frozenset[str], float], dict[str, Any]],
    bag: Path,
    topic: str,
    *,
    emit: Callable[[dict[str, Any]], None],
    write_bag: Path | None = None,
    hierarchy: Mapping[str, Any] | None = None,
    definitions: Sequence[Path] = (),
) -> int:
    """Run a bag's contact frames (streamed, never all in memory) through ``record`` — one frame's events and
    time in seconds to its record, e.g. a filter's :func:`belief_record` and the mistake judged there — then
    ``emit`` each record and, with ``write_bag``, write them to a new MCAP bag at the frames' times (the
    hierarchy as a latched topic). The topic is read through once first, so a damaged bag fails before
    anything is emitted or written (twice the reading, still in constant memory). How many frames there were.

    Raises:
        BagError: for a missing, empty or wrongly typed topic, a damaged bag, or an output that exists;
            a bag being written is removed when anything fails.
        FileFormatError: for an output that is the bag or inside it (or a ``definitions`` folder).
    """
    from supportive.io.atomic import check_apart
    from supportive.io.rosbag import BeliefBag, read_contact_frames
    from supportive.io.rosbag.bags import seconds

    if write_bag is not None:
        check_apart(write_bag, [bag, *definitions], "--write-bag")

    for _ in read_contact_frames(bag, topic, definitions):  # a damaged bag fails here, before any output
        pass
    frames = read_contact_frames(bag, topic, definitions)
    sink: AbstractContextManager[BeliefBag | None] = (
        nullcontext() if write_bag is None else BeliefBag(write_bag, hierarchy or {})
    )
    count = 0
    with sink as out:
        for events, time in frames:
            frame = record(events, seconds(time))
            if out is not None:
                out.write(time, frame)
            emit(frame)
            count += 1
    return count
