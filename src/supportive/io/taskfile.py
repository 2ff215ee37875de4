"""Read and write task files: YAML, JSON (same schema) and CSV demonstrations.

Every problem becomes a :class:`~supportive.errors.TaskFileError` naming the file, the line when known, the
field (``demonstrations[1].steps[3]``) and what was wrong.
"""

from __future__ import annotations

import csv
import dataclasses
import difflib
import io
import json
from collections import Counter
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

import yaml
from pydantic import ValidationError

from supportive.errors import FormulaError, TaskFileError, TaskModelError
from supportive.io.atomic import atomic_write
from supportive.io.limits import MAX_NUMBER_CHARS, MAX_SECONDS
from supportive.io.safe_load import LIBYAML, check_kind, read_csv, read_text
from supportive.io.schema import NodeIn, PredicateIn, TaskIn
from supportive.io.structured import kind_of, line_of, load_structured, place_of, schema_error
from supportive.io.values import check_id, check_number, is_digits
from supportive.tasks.behaviors import (
    DERIVED_PREDICATES,
    BehaviorCategory,
    PredicateSpec,
    SupportiveBehavior,
    placeholders,
)
from supportive.tasks.formula import parse_formula, split_atom
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, Node, internal_nodes
from supportive.tasks.spec import Action, Demonstration, Keyframe, Step, TaskSpec, mistake_label

__all__ = [
    "CSV_COLUMNS",
    "Format",
    "csv_leaves_out",
    "dump_task",
    "format_of",
    "parse_task_file",
    "parse_task_string",
    "task_to_dict",
    "write_task_file",
]

Format = Literal["yaml", "json", "csv"]
CSV_COLUMNS = ("demonstration", "step", "action")
CSV_OPTIONAL = ("agent", "start", "end", "mistake")
_NOTHING_PERFORMED = "no step was performed: every step is labelled missing"
_SUFFIXES: dict[str, Format] = {".yaml": "yaml", ".yml": "yaml", ".json": "json", ".csv": "csv"}


def format_of(path: str | Path) -> Format:
    """The format a file name implies.

    Raises:
        TaskFileError: for an unknown suffix.
    """
    suffix = Path(path).suffix.lower()
    if Path(path).is_dir():
        raise TaskFileError("is a folder; expected a task file (.yaml, .yml, .json or .csv)", path=path)
    if suffix not in _SUFFIXES:
        raise TaskFileError(
            f"unsupported file type {suffix or '(none)'!r}; expected a task file (.yaml, .yml, .json or .csv)",
            path=path,
        )
    return _SUFFIXES[suffix]


def parse_task_file(path: str | Path, format: Format | None = None) -> TaskSpec:
    """Read a task file.

    Raises:
        TaskFileError: when the file is missing, unreadable or invalid.
    """
    path = Path(path)
    fmt = format or _SUFFIXES[check_kind(path, tuple(_SUFFIXES), "a task file", TaskFileError)]
    return parse_task_string(read_text(path, TaskFileError), fmt, path=path)


def parse_task_string(
    text: str, format: Format, *, path: str | Path | None = None, name: str | None = None
) -> TaskSpec:
    """Read a task from text. ``name`` names a CSV task (default: the file's stem)."""
    if not text.strip():
        raise TaskFileError("file is empty", path=path)
    if format == "csv":
        return _parse_csv(text, path, name or (Path(path).stem if path else "task"))
    data = load_structured(text, format, path, TaskFileError)
    if not isinstance(data, dict):
        raise TaskFileError(f"expected a mapping with at least 'name', got {kind_of(data)}", path=path, line=1)
    try:
        model = TaskIn.model_validate(data)
    except ValidationError as exc:
        raise schema_error(exc, text, path, TaskFileError, TaskIn) from None
    return _to_spec(model, text, path)


def _to_spec(model: TaskIn, text: str, path: str | Path | None) -> TaskSpec:
    def fail(problem: str, loc: list[str | int]) -> TaskFileError:
        return TaskFileError(problem, path=path, place=place_of(loc), line=line_of(text, loc))

    actions = tuple(
        Action(
            a.id,
            a.text,
            a.events(),
            tuple(a.effects or ()),
            tuple(Keyframe(k.x, k.y, k.text, k.goal) for k in a.keyframes or ()),
        )
        for a in model.actions or ()
    )
    declared = {a.id for a in actions}
    seen_actions: set[str] = set()
    for index, action in enumerate(actions):
        if action.id in seen_actions:
            raise fail(f"duplicate action id {action.id!r}", ["actions", index, "id"])
        seen_actions.add(action.id)
    structure = None
    if model.structure is not None:
        structure = _node(model.structure, ["structure"], declared, fail, Counter())
    demos = []
    seen_ids: set[str] = set()
    for i, demo in enumerate(model.demonstrations or ()):
        demo_id = demo.id or f"d{i + 1}"
        if demo_id in seen_ids:
            raise fail(f"duplicate demonstration id {demo_id!r}", ["demonstrations", i, "id"])
        seen_ids.add(demo_id)
        entries = []
        for j, step in enumerate(demo.steps):
            if declared and step.action not in declared:
                raise fail(
                    f"action {step.action!r} is not declared in 'actions'{_did_you_mean(step.action, declared)}",
                    ["demonstrations", i, "steps", j],
                )
            try:
                state = None if step.state is None else frozenset(step.state)
                entries.append(Step(step.action, step.start, step.end, state, step.mistake))
            except TaskModelError as exc:
                raise fail(str(exc), ["demonstrations", i, "steps", j]) from None
        with_state = [step.state is not None for step in entries if not step.placeholder]
        if any(with_state) and not all(with_state):
            j = [k for k, step in enumerate(entries) if not step.placeholder][with_state.index(False)]
            raise fail("every step needs a 'state' when one step has it", ["demonstrations", i, "steps", j])
        if not with_state:
            raise fail(_NOTHING_PERFORMED, ["demonstrations", i, "steps"])
        initial = None if demo.initial_state is None else frozenset(demo.initial_state)
        demos.append(Demonstration.from_entries(entries, demo_id, demo.agent, initial))
    explicit = {d.has_states for d in demos}
    if len(explicit) > 1:
        index = next(i for i, d in enumerate(demos) if d.has_states != demos[0].has_states)
        raise fail("give explicit states in every demonstration or in none", ["demonstrations", index])
    objects = tuple((kind, tuple(names)) for kind, names in (model.objects or {}).items())
    predicates, behaviors = _behaviors(model, actions, structure, dict(objects), fail)
    return TaskSpec(model.name, actions, structure, tuple(demos), predicates, behaviors, objects)


def _predicate(p: PredicateIn, loc: list[str | int], objects: dict[str, tuple[str, ...]], fail: Any) -> PredicateSpec:
    """A declared predicate, its templates and parameter types checked."""
    typed = p.typed()
    params = tuple(name for name, _ in typed)
    if len(set(params)) != len(params):
        raise fail(f"predicate {p.name!r} names a parameter twice", [*loc, "params"])
    for j, (_, kind) in enumerate(typed):
        if kind is not None and objects and kind not in objects:
            raise fail(f"type {kind!r} is not declared in 'objects' (declared: {', '.join(objects)})", [*loc, "params", j])
    for key, template in (("text", p.text), ("negative", p.negative)):
        if template is None:
            continue
        used = placeholders(template)
        unknown = [u for u in used if u not in params]
        unsaid = [q for q in params if q not in used]
        if unknown or unsaid:
            wrong = f"uses ?{unknown[0]}, which is not a parameter" if unknown else f"does not say ?{unsaid[0]}"
            expected = ", ".join(f"?{q}" for q in params) or "no placeholders"
            raise fail(f"template {template!r} {wrong} (parameters of {p.name}: {expected})", [*loc, key])
    types = tuple(kind for _, kind in typed) if any(kind for _, kind in typed) else ()
    return PredicateSpec(p.name, params, p.text, p.negative, types)


def _behaviors(
    model: TaskIn,
    actions: tuple[Action, ...],
    structure: Node | None,
    objects: dict[str, tuple[str, ...]],
    fail: Any,
) -> tuple[tuple[PredicateSpec, ...], tuple[SupportiveBehavior, ...]]:
    """The predicates and supportive behaviors, every formula checked against them, the structure and the
    declared objects."""
    predicates: dict[str, PredicateSpec] = {}
    for i, p in enumerate(model.predicates or ()):
        if p.name in predicates or p.name in DERIVED_PREDICATES:
            taken = "declared twice" if p.name in predicates else "derived from the structure"
            raise fail(f"predicate {p.name!r} is {taken}", ["predicates", i, "name"])
        predicates[p.name] = _predicate(p, ["predicates", i], objects, fail)
    known = {name for names in objects.values() for name in names}
    subtasks = (
        {node.name for node in internal_nodes(structure) if node.name} if structure is not None else set()
    )

    def check(text: str, loc: list[str | int], *, single: bool = False) -> None:
        try:
            formula = parse_formula(text)
        except FormulaError as exc:
            raise fail(str(exc), loc) from None
        if single and (len(formula.clauses) != 1 or len(formula.clauses[0]) != 1):
            raise fail(f"an effect is one atom, or 'not' and one atom, got {text!r}", loc)
        for literal in sorted(formula.atoms()):
            name, args = split_atom(literal)
            if name in DERIVED_PREDICATES:
                if len(args) != 1 or (structure is not None and args[0] not in subtasks):
                    raise fail(f"{literal}: {name}() takes one named subtask of the structure", loc)
            elif name not in predicates:
                raise fail(f"{literal}: predicate {name!r} is not declared in 'predicates'", loc)
            elif len(args) != len(predicates[name].params):
                raise fail(f"{literal}: {name} takes {len(predicates[name].params)} arguments", loc)
            elif objects:
                _check_arguments(literal, predicates[name], args, objects, known, loc, fail)

    for i, action in enumerate(actions):
        for j, effect in enumerate(action.effects):
            check(effect, ["actions", i, "effects", j], single=True)
    behaviors: list[SupportiveBehavior] = []
    for i, b in enumerate(model.behaviors or ()):
        if any(other.name == b.name for other in behaviors):
            raise fail(f"behavior {b.name!r} is declared twice", ["behaviors", i, "name"])
        for j, subtask in enumerate(b.subtasks):
            if structure is not None and subtask not in subtasks:
                raise fail(f"{subtask!r} is not a named subtask of the structure", ["behaviors", i, "subtasks", j])
        check(b.initiation, ["behaviors", i, "initiation"])
        check(b.termination, ["behaviors", i, "termination"])
        behaviors.append(
            SupportiveBehavior(
                b.name, b.text, BehaviorCategory(b.category), tuple(b.subtasks), b.initiation, b.termination
            )
        )
    return tuple(predicates.values()), tuple(behaviors)


def _check_arguments(
    literal: str,
    predicate: PredicateSpec,
    args: tuple[str, ...],
    objects: dict[str, tuple[str, ...]],
    known: set[str],
    loc: list[str | int],
    fail: Any,
) -> None:
    """Each argument is a declared object, of its parameter's type when the parameter has one."""
    types = predicate.types or (None,) * len(args)
    for param, kind, arg in zip(predicate.params, types, args, strict=True):
        if kind is not None and arg not in objects[kind]:
            raise fail(f"{literal}: ?{param} of {predicate.name} is a {kind} ({', '.join(objects[kind])}), got {arg!r}", loc)
        if kind is None and arg not in known:
            raise fail(f"{literal}: {arg!r} is not declared in 'objects'", loc)


def _did_you_mean(name: str, known: set[str]) -> str:
    """"; did you mean 'x'?" for the known name closest to a mistyped one (difflib), or nothing.

    >>> _did_you_mean("gren", {"green", "red"}), _did_you_mean("zzz", {"green"})
    ("; did you mean 'green'?", '')
    """
    close = difflib.get_close_matches(name, sorted(known), n=1, cutoff=0.6)
    return f"; did you mean {close[0]!r}?" if close else ""


def _node(model: NodeIn, loc: list[str | int], declared: set[str], fail: Any, seen: Counter[str]) -> Node:
    if model.action is not None:
        if declared and model.action not in declared:
            raise fail(f"action {model.action!r} is not declared in 'actions'{_did_you_mean(model.action, declared)}", loc)
        seen[model.action] += 1
        return ActionNode(model.action, seen[model.action])
    if model.optional is not None:
        inner = _node(model.optional, [*loc, "optional"], declared, fail, seen)
        if model.name and not isinstance(inner, ActionNode):
            inner = dataclasses.replace(inner, name=model.name)
        return dataclasses.replace(inner, optional=True)
    key = "chain" if model.chain is not None else "clique"
    items = model.chain if model.chain is not None else (model.clique or [])
    children = tuple(_node(child, [*loc, key, i], declared, fail, seen) for i, child in enumerate(items))
    if len(children) == 1:
        return children[0]
    return ChainNode(children, model.name) if key == "chain" else CliqueNode(children, model.name)


# ---------------------------------------------------------------------------------------------- CSV
_CSV_FLAGS = {"true": True, "false": False}
"""A ``mistake`` cell of ``true`` or ``false`` (any case) means what it does in YAML; empty is no label."""


def _parse_csv(text: str, path: str | Path | None, name: str) -> TaskSpec:
    header, table = read_csv(text, path, TaskFileError)
    missing = [c for c in CSV_COLUMNS if c not in header]
    if missing:
        raise TaskFileError(
            f"missing column(s) {', '.join(missing)}; expected header {','.join(CSV_COLUMNS)}[,agent,start,end,mistake]",
            path=path,
            line=1,
        )
    unknown = [c for c in header if c not in CSV_COLUMNS + CSV_OPTIONAL]
    if unknown:
        raise TaskFileError(f"unknown column(s) {', '.join(unknown)}", path=path, line=1)
    rows: dict[str, list[tuple[int, Step, str | None]]] = {}
    for line, row in table:
        if not any(field.strip() for field in row):
            continue  # a blank line
        if len(row) > len(header):
            raise TaskFileError("more values than columns", path=path, line=line)
        values = dict(zip(header, (field.strip() for field in row), strict=False))
        demo, action = values.get("demonstration", ""), values.get("action", "")
        if not demo or not action:
            raise TaskFileError("'demonstration' and 'action' must not be empty", path=path, line=line)
        try:
            check_id(demo, what="a demonstration id")
            check_id(action, action=True, what="an action id")
            if values.get("agent"):
                check_id(values["agent"], what="an agent")
        except ValueError as exc:
            raise TaskFileError(str(exc), path=path, line=line) from None
        step = values.get("step", "")
        if not (is_digits(step) and len(step) <= 9):
            raise TaskFileError(f"step must be an integer of at most 9 digits, got {step[:20]!r}", path=path, line=line)
        start, end = (_seconds(values.get(k, ""), k, path, line) for k in ("start", "end"))
        if start is not None and end is not None and start > end:
            raise TaskFileError(f"start {start} is after end {end}", path=path, line=line)
        label = values.get("mistake", "")
        try:
            entry = Step(action, start, end, mistake=mistake_label(_CSV_FLAGS.get(label.lower(), label or None)))
        except TaskModelError as exc:
            raise TaskFileError(str(exc), path=path, place="mistake", line=line) from None
        rows.setdefault(demo, []).append((int(step), entry, values.get("agent") or None))
    if not rows:
        raise TaskFileError("no demonstration rows after the header", path=path, line=2)
    demos = []
    for demo_id, steps in rows.items():
        numbers = [n for n, _, _ in steps]
        if len(set(numbers)) != len(numbers):
            raise TaskFileError(f"demonstration {demo_id!r} repeats a step number", path=path)
        agents = {a for _, _, a in steps if a}
        if len(agents) > 1:
            raise TaskFileError(
                f"demonstration {demo_id!r} names several agents: {sorted(agents)}", path=path
            )
        ordered = [step for _, step, _ in sorted(steps, key=lambda item: item[0])]
        if all(step.placeholder for step in ordered):
            raise TaskFileError(f"demonstration {demo_id!r}: {_NOTHING_PERFORMED}", path=path)
        demos.append(Demonstration.from_entries(ordered, demo_id, agents.pop() if agents else None))
    return TaskSpec(name, (), None, tuple(demos))


def _seconds(value: str, column: str, path: str | Path | None, line: int) -> float | None:
    if not value:
        return None
    try:
        number = float(value) if len(value) <= MAX_NUMBER_CHARS else None
    except ValueError:
        number = None
    if number is None:
        raise TaskFileError(f"{column} must be a number, got {value[:20]!r}", path=path, line=line)
    try:
        return check_number(number, column, low=-MAX_SECONDS, high=MAX_SECONDS)
    except ValueError as exc:
        raise TaskFileError(str(exc), path=path, line=line) from None


# ---------------------------------------------------------------------------------------------- writing
def _node_to_data(node: Node) -> object:
    if node.optional:
        return {"optional": _node_to_data(dataclasses.replace(node, optional=False))}
    if isinstance(node, ActionNode):
        return node.action
    data: dict[str, object] = {node.kind: [_node_to_data(child) for child in node.children]}
    if node.name:
        data["name"] = node.name
    return data


def _action_to_data(action: Action) -> dict[str, object]:
    data: dict[str, object] = {"id": action.id}
    if action.text:
        data["text"] = action.text
    if action.observations:
        data["observations"] = dict(action.observations)
    if action.effects:
        data["effects"] = list(action.effects)
    if action.keyframes:
        data["keyframes"] = [_keyframe_to_data(k) for k in action.keyframes]
    return data


class _Pair(list[float]):
    """A keyframe's ``[x, y]``, which YAML writes on one line."""


if TYPE_CHECKING or LIBYAML:
    from yaml import CSafeDumper as _SafeDumper
else:
    from yaml import SafeDumper as _SafeDumper


class _Dumper(_SafeDumper):
    """The safe dumper (libyaml's emitter, three times as fast as PyYAML's Python one on a 5,000-action task;
    the Python one where PyYAML has no libyaml), writing keyframe pairs in flow style."""


_Dumper.add_representer(
    _Pair, lambda dumper, pair: dumper.represent_sequence("tag:yaml.org,2002:seq", pair, flow_style=True)
)


def _keyframe_to_data(keyframe: Keyframe) -> object:
    if keyframe.text is None and not keyframe.goal:
        return _Pair((keyframe.x, keyframe.y))
    data: dict[str, object] = {"x": keyframe.x, "y": keyframe.y}
    if keyframe.text is not None:
        data["text"] = keyframe.text
    if keyframe.goal:
        data["goal"] = True
    return data


def _step_to_data(step: Step) -> object:
    if step.start is None and step.end is None and step.state is None and step.mistake is None:
        return step.action
    data: dict[str, object] = {"action": step.action}
    if step.start is not None:
        data["start"] = step.start
    if step.end is not None:
        data["end"] = step.end
    if step.state is not None:
        data["state"] = sorted(step.state)
    if step.mistake is not None:
        data["mistake"] = True if step.mistake == "true" else step.mistake
    return data


def _params_to_data(predicate: PredicateSpec) -> list[object]:
    types = predicate.types or (None,) * len(predicate.params)
    return [name if kind is None else {name: kind} for name, kind in zip(predicate.params, types, strict=True)]


def task_to_dict(spec: TaskSpec) -> dict[str, Any]:
    """The task as plain data in the file schema (shorthands used where nothing is lost)."""
    data: dict[str, Any] = {"name": spec.name}
    if spec.actions:
        data["actions"] = [_action_to_data(a) for a in spec.actions]
    if spec.structure is not None:
        data["structure"] = _node_to_data(spec.structure)
    if spec.demonstrations:
        demos = []
        for demo in spec.demonstrations:
            item: dict[str, Any] = {"id": demo.id}
            if demo.agent:
                item["agent"] = demo.agent
            if demo.initial_state is not None:
                item["initial_state"] = sorted(demo.initial_state)
            item["steps"] = [_step_to_data(s) for s in demo.entries]
            demos.append(item)
        data["demonstrations"] = demos
    if spec.objects:
        data["objects"] = {kind: list(names) for kind, names in spec.objects}
    if spec.predicates:
        data["predicates"] = [
            {"name": p.name, "params": _params_to_data(p), "text": p.text}
            | ({"negative": p.negative} if p.negative else {})
            for p in spec.predicates
        ]
    if spec.behaviors:
        data["behaviors"] = [
            {
                "name": b.name,
                "text": b.text,
                "category": b.category.value,
                "subtasks": list(b.subtasks),
                "initiation": b.initiation,
                "termination": b.termination,
            }
            for b in spec.behaviors
        ]
    return data


def dump_task(spec: TaskSpec, format: Format) -> str:
    """The task as YAML, JSON or CSV text (CSV holds the demonstrations only)."""
    if format == "csv":
        out = io.StringIO()
        columns = list(CSV_COLUMNS)
        if any(d.agent for d in spec.demonstrations):
            columns.append("agent")
        if any(s.start is not None or s.end is not None for d in spec.demonstrations for s in d.steps):
            columns += ["start", "end"]
        if any(d.labelled for d in spec.demonstrations):
            columns.append("mistake")
        writer = csv.writer(out, lineterminator="\n")
        writer.writerow(columns)
        for demo in spec.demonstrations:
            for number, step in enumerate(demo.entries, start=1):
                row: dict[str, object] = {"demonstration": demo.id, "step": number, "action": step.action}
                row |= {"agent": demo.agent or "", "start": _blank(step.start), "end": _blank(step.end)}
                row["mistake"] = step.mistake or ""
                writer.writerow([row[c] for c in columns])
        return out.getvalue()
    data = task_to_dict(spec)
    if format == "json":
        return json.dumps(data, indent=2, ensure_ascii=False) + "\n"
    return yaml.dump(data, Dumper=_Dumper, sort_keys=False, allow_unicode=True, width=110)


def csv_leaves_out(spec: TaskSpec) -> list[str]:
    """What a CSV of ``spec`` does not hold (CSV has the demonstrations only), in words; empty when nothing.

    >>> from supportive.tasks.htn import ActionNode
    >>> csv_leaves_out(TaskSpec("t", (Action("a", "do a"),), ActionNode("a")))
    ['the structure', 'the actions and their texts']
    """
    lost = []
    if spec.structure is not None:
        lost.append("the structure")
    if any(a.text not in (None, a.id) or a.observations or a.effects or a.keyframes for a in spec.actions):
        lost.append("the actions and their texts")
    lost += [words for present, words in (
        (spec.predicates, "the predicates"), (spec.behaviors, "the supportive behaviors"), (spec.objects, "the objects"),
    ) if present]
    return lost


def _blank(value: float | None) -> object:
    return "" if value is None else value


def write_task_file(spec: TaskSpec, path: str | Path, format: Format | None = None) -> None:
    """Write a task file atomically (:func:`~supportive.io.atomic.atomic_write`: mode and symlinks kept); the
    text is produced before the file is opened, so a failure writes nothing.

    Raises:
        TaskFileError: naming the file, when it cannot be written.
    """
    text = dump_task(spec, format or format_of(path))
    atomic_write(path, text, error=TaskFileError)
