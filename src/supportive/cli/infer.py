"""``supportive infer``: what the teammate is doing after each observation, known action or bag frame."""

from __future__ import annotations

import json
import sys
from enum import StrEnum
from pathlib import Path
from typing import Annotated, Any

import typer

from supportive.cli.output import about, finite
from supportive.errors import OptionError, TaskFileError

__all__ = ["UnknownNames", "infer"]


class InferenceModel(StrEnum):
    """Goal-inference models."""

    progress = "progress"
    hierarchical = "hierarchical"
    flat = "flat"


def infer(
    file: Annotated[
        Path,
        typer.Argument(help="Task file whose actions declare their 'observations', or a bundled example's name."),
    ],
    observations: Annotated[
        Path | None,
        typer.Option("--observations", "-O", help="Observation stream: .jsonl, .json, .yaml or .yml."),
    ] = None,
    actions: Annotated[
        Path | None,
        typer.Option("--actions", "-A", help="Known actions instead, one action id per line (progress model)."),
    ] = None,
    model: Annotated[
        InferenceModel,
        typer.Option("--model", help="progress: knows what is done (default); or the thesis's HMMs."),
    ] = InferenceModel.progress,
    top: Annotated[
        int, typer.Option("--top", min=1, max=10_000, help="How many entries of each belief to print.")
    ] = 3,
    mean_duration: Annotated[
        float,
        typer.Option("--mean-duration", min=1.0, max=1e6, callback=finite, help="Mean observations per subgoal."),
    ] = 5.0,
    bag: Annotated[
        Path | None, typer.Option("--bag", help="Read contact events from a ROS bag instead (ros extra).")
    ] = None,
    contacts_topic: Annotated[
        str, typer.Option("--contacts-topic", help="The bag's contacts topic (see docs/ros.md).")
    ] = "/contacts",
    write_bag: Annotated[
        Path | None,
        typer.Option("--write-bag", help="Also write the beliefs as a new MCAP bag (with --bag)."),
    ] = None,
    types: Annotated[
        list[Path] | None,
        typer.Option(
            "--types",
            metavar="PATH",
            help="A .msg/.idl file or folder of message types the bag lacks; repeatable.",
        ),
    ] = None,
    strict: Annotated[
        bool,
        typer.Option(
            "--strict",
            help="Refuse (exit 2) an event or action the task does not know, instead of warning once per name.",
        ),
    ] = False,
) -> None:
    """Learn the task's CC-HTN, then print what the teammate is doing after each observation or known action
    (one JSON line each: top subgoals, enclosing subtasks and next steps, with probabilities; with the progress
    model, whether each step is a mistake and the help the robot offers)."""
    from supportive.examples import task_path
    from supportive.inference import FlatHMM, HierarchicalHMM, ObservationModel, ProgressHMM
    from supportive.inference.bags import belief_record, infer_bag
    from supportive.inference.filtering import Filter
    from supportive.inference.mistakes import MistakeDetector
    from supportive.io.action_file import parse_action_file
    from supportive.io.htn_json import htn_to_dict
    from supportive.io.observation_file import parse_observation_file
    from supportive.io.taskfile import parse_task_file
    from supportive.language.help import mistake_record
    from supportive.learning.learner import learn as learn_htn

    if sum(source is not None for source in (observations, bag, actions)) != 1:
        raise OptionError("give one source: --observations FILE, --actions FILE or --bag BAG")
    if write_bag is not None and bag is None:
        raise OptionError("--write-bag needs --bag: it writes the beliefs beside a recording")
    if actions is not None and model is not InferenceModel.progress:
        raise OptionError("--actions needs --model progress (the HMMs read contact events)")
    spec = parse_task_file(task_path(file))
    if not spec.demonstrations:
        raise TaskFileError("no demonstrations to learn from", path=file, place="demonstrations")
    steps = parse_action_file(actions) if actions is not None else []
    stream = parse_observation_file(observations) if observations is not None else []
    known_events = frozenset(ObservationModel.from_spec(spec).events) if actions is None else frozenset()
    source = actions or observations or bag
    assert source is not None  # one source, checked above
    unknown = UnknownNames(source, strict)
    for number, action in enumerate(steps, start=1):  # a file is checked whole before anything is printed
        unknown.check([action], frozenset(spec.action_ids()), "action", f"step {number}")
    for number, (moment, _) in enumerate(stream, start=1):
        unknown.check(sorted(moment), known_events, "event", f"moment {number}")
    unknown.report()
    detector: MistakeDetector | None = None
    running: Filter
    with about(file):
        learner = learn_htn(spec)
        if model is InferenceModel.progress:
            events = ObservationModel.from_spec(spec) if actions is None else None
            detector = MistakeDetector(ProgressHMM(learner.htn_, events, mean_duration=mean_duration).fit())
            running = detector.tracker if actions is not None else detector.events
        else:
            kind = HierarchicalHMM if model is InferenceModel.hierarchical else FlatHMM
            model_events = ObservationModel.from_spec(spec)
            running = kind(learner.htn_, model_events, mean_duration=mean_duration).fit().filter()
    texts = spec.texts()

    def emit(record: dict[str, object]) -> None:
        sys.stdout.write(json.dumps(record) + "\n")

    def frame(moment: frozenset[str], time: float | None) -> dict[str, Any]:
        unknown.check(sorted(moment), known_events, "event", f"the frame at {time} s")
        unknown.report()
        if detector is None:
            return belief_record(running, running.update(moment), top, time)
        verdict = detector.update(moment)
        record = belief_record(running, running.last, top, time)
        if verdict is not None:
            record["mistake"] = mistake_record(verdict, texts)
        return record

    if bag is not None:
        hierarchy = htn_to_dict(learner.htn_, learner.stats_.as_dict())
        infer_bag(frame, bag, contacts_topic, emit=emit, write_bag=write_bag, hierarchy=hierarchy, definitions=types or ())
    for moment, time in stream:
        emit(frame(moment, time))
    for action in steps:
        assert detector is not None  # --actions needs the progress model
        verdict = detector.observe(action)
        emit(belief_record(running, running.last, top, None) | {"mistake": mistake_record(verdict, texts)})



class UnknownNames:
    """Events or actions an input names that the task does not know: warned about once per name on stderr
    (the models ignore an unknown event; an unknown action is judged a mistake), or, ``strict``, refused.

    Args:
        source: The input file or bag (named in the warning or error).
        strict: Refuse the first unknown name (exit 2) instead of warning.
    """

    def __init__(self, source: Path, strict: bool) -> None:
        self.source = source
        self.strict = strict
        self.warned: set[tuple[str, str]] = set()
        self._new: list[tuple[str, str, str]] = []

    def check(self, names: list[str], known: frozenset[str], kind: str, place: str) -> None:
        """Note the names not in ``known`` (``kind`` "event" or "action", first seen at ``place``).

        Raises:
            ObservationFileError: with ``strict``, for the first unknown name.
        """
        from supportive.errors import ObservationFileError

        for name in names:
            if name in known or (kind, name) in self.warned:
                continue
            if self.strict:
                raise ObservationFileError(
                    f"unknown {kind} {name!r}: the task has no such {kind} (--strict refuses it)",
                    path=self.source,
                    place=place,
                )
            self.warned.add((kind, name))
            self._new.append((kind, name, place))

    def report(self) -> None:
        """Warn, one line each, about the names noted since the last report."""
        from supportive.cli.output import say

        effect = {"event": "the model ignores it", "action": "it is judged a mistake"}
        for kind, name, place in self._new:
            say(
                f"supportive: warning: {self.source}: {place}: unknown {kind} {name!r} ({effect[kind]}; "
                "said once per name; --strict refuses it)",
                to_stderr=True,
            )
        self._new.clear()
