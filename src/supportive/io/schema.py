"""The task-file schema (pydantic), shared by the YAML and JSON readers.

Shorthands: an action may be written as its id alone, a step as its action id alone (``mistake: true``
labels a step with a mistake of unknown kind, ``false`` is no label), a structure leaf as an
action id, a keyframe as its ``[x, y]`` pair. A structure node is ``{chain: [...]}`` or ``{clique: [...]}`` with an optional ``name``,
or ``{optional: node}`` for a node that may be skipped.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import (
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    StringConstraints,
    field_validator,
    model_validator,
)

from supportive.errors import InvalidValueError
from supportive.io.values import ActionId, Coordinate, Ident, Seconds, Text
from supportive.tasks.spec import mistake_label

__all__ = [
    "DEFAULT_EVENT_PROBABILITY",
    "ActionIn",
    "BehaviorIn",
    "DemonstrationIn",
    "KeyframeIn",
    "NodeIn",
    "PredicateIn",
    "StepIn",
    "TaskIn",
]

Name = Ident
Sentence = Annotated[Text, StringConstraints(strip_whitespace=True, min_length=1)]


def _wrap(key: str) -> Any:
    return BeforeValidator(lambda value: {key: value} if isinstance(value, str) else value)


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


DEFAULT_EVENT_PROBABILITY = 0.9
"""Probability given to an observation listed without one."""


def _keyframe_pair(value: Any) -> Any:
    """``[x, y]`` → ``{x, y}``; any other list is refused with the expected forms."""
    if isinstance(value, list | tuple):
        if len(value) != 2:
            raise InvalidValueError(f"a keyframe is [x, y] or {{x, y, text, goal}}, got a list of length {len(value)}")
        return {"x": value[0], "y": value[1]}
    return value


class KeyframeIn(_Strict):
    """``{x, y, text, goal}`` or ``[x, y]``: a point the skill's end effector passes (workspace units, e.g.
    metres), what happens there, and whether it is a goal state of the skill."""

    x: Coordinate
    y: Coordinate
    text: Text | None = None
    goal: bool = False


class ActionIn(_Strict):
    """``{id, text, observations, effects, keyframes}``: observations are contact events, as a list (each
    holding with probability 0.9 while the action runs) or a mapping from event to probability; keyframes are
    the points the skill's end effector passes, in order."""

    id: ActionId
    text: Text | None = None
    observations: list[Name] | dict[Name, Annotated[float, Field(gt=0.0, lt=1.0)]] | None = None
    effects: list[Name] | None = None
    keyframes: list[Annotated[KeyframeIn, BeforeValidator(_keyframe_pair)]] | None = None

    def events(self) -> tuple[tuple[str, float], ...]:
        """The observations as ``(event, probability)`` pairs, sorted by event."""
        if self.observations is None:
            return ()
        if isinstance(self.observations, list):
            return tuple(sorted((e, DEFAULT_EVENT_PROBABILITY) for e in set(self.observations)))
        return tuple(sorted(self.observations.items()))


class StepIn(_Strict):
    """``{action, start, end, state, mistake}``: timing in seconds; ``state`` lists the fluents true after the
    step; ``mistake`` is a label (:data:`~supportive.tasks.spec.MISTAKE_LABELS`), ``true`` for a mistake of
    unknown kind, ``false`` for none (``missing`` makes the step a placeholder for a skipped one)."""

    action: ActionId
    start: Seconds | None = None
    end: Seconds | None = None
    state: list[Name] | None = None
    mistake: Annotated[str | None, BeforeValidator(mistake_label)] = None

    @model_validator(mode="after")
    def _timing(self) -> StepIn:
        if self.start is not None and self.end is not None and self.start > self.end:
            raise InvalidValueError(f"start {self.start} is after end {self.end}")
        return self


class DemonstrationIn(_Strict):
    """``{id, agent, initial_state, steps}``."""

    id: Name | None = None
    agent: Name | None = None
    initial_state: list[Name] | None = None
    steps: Annotated[list[Annotated[StepIn, _wrap("action")]], Field(min_length=1)]


class NodeIn(_Strict):
    """A structure node: exactly one of ``action``, ``chain``, ``clique`` or ``optional`` (a node that may be
    skipped whole: ``{optional: add_sugar}``); an optional ``name``."""

    action: ActionId | None = None
    chain: list[Annotated[NodeIn, _wrap("action")]] | None = None
    clique: list[Annotated[NodeIn, _wrap("action")]] | None = None
    optional: Annotated[NodeIn, _wrap("action")] | None = None
    name: Name | None = None

    @model_validator(mode="after")
    def _one_kind(self) -> NodeIn:
        kinds = [k for k in ("action", "chain", "clique", "optional") if getattr(self, k) is not None]
        if len(kinds) != 1:
            raise InvalidValueError(
                "a structure node needs exactly one of 'chain', 'clique', 'optional' or an action id"
            )
        children = self.chain if self.chain is not None else self.clique
        if children is not None and not children:
            raise InvalidValueError(f"'{kinds[0]}' needs at least one child")
        return self


Identifier = Annotated[str, StringConstraints(pattern=r"^[A-Za-z_][A-Za-z0-9_]*$")]


class PredicateIn(_Strict):
    """``{name, params, text, negative}``: ``text`` is a template with ``?param`` placeholders; a parameter is
    a name (``x``) or a name with its type (``{x: part}``, in YAML flow style ``[x: part, y: part]``)."""

    name: Annotated[str, StringConstraints(pattern=r"^[A-Za-z_][A-Za-z0-9_\-]*$")]
    params: list[Identifier | dict[Identifier, Identifier]] = []
    text: Sentence
    negative: Text | None = None

    @field_validator("params")
    @classmethod
    def _one_type_each(cls, params: list[str | dict[str, str]]) -> list[str | dict[str, str]]:
        for i, param in enumerate(params):
            if isinstance(param, dict) and len(param) != 1:
                raise InvalidValueError(f"a typed parameter is one 'name: type' pair, got {param} (parameter {i + 1})")
        return params

    def typed(self) -> list[tuple[str, str | None]]:
        """Each parameter's name and type (None: untyped)."""
        return [(p, None) if isinstance(p, str) else next(iter(p.items())) for p in self.params]


class BehaviorIn(_Strict):
    """``{name, text, category, subtasks, initiation, termination}``; the two regions are formulas."""

    name: Name
    text: Sentence
    category: Literal[
        "materials stabilization",
        "materials retrieval",
        "collaborative object manipulation",
        "enhancing awareness",
        "task progression guidance",
    ]
    subtasks: list[Name] = []
    initiation: Sentence = "true"
    termination: Sentence = "false"


class TaskIn(_Strict):
    """A whole task file."""

    name: Name
    actions: list[Annotated[ActionIn, _wrap("id")]] | None = None
    structure: Annotated[NodeIn, _wrap("action")] | None = None
    demonstrations: list[DemonstrationIn] | None = None
    objects: dict[Identifier, list[Identifier]] | None = None
    predicates: list[PredicateIn] | None = None
    behaviors: list[BehaviorIn] | None = None
