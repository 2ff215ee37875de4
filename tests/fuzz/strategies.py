"""Hypothesis strategies for malformed inputs: task files (YAML, JSON, CSV), household maps, circuit scenarios,
observation streams and API bodies. Each starts from a valid input and breaks it the ways people and attackers
do — a wrong type or value at a random place, an unknown or repeated key, huge or non-finite numbers, control
characters, markup, lone surrogates, deep nesting, aliases, truncation, stray bytes — or is plain noise."""

from __future__ import annotations

import json
from typing import Any

import yaml
from hypothesis import strategies as st

NASTY_TEXT = st.sampled_from(
    [
        "",
        " ",
        "a#2",
        "[/]",
        "[bold]x",
        ":poop:",
        "\x1b[2J",
        "\u202e",
        "\udc80",
        "\x00",
        "x" * 300,
        "1e400",
        "NaN",
        "true",
        "~",
        "&a",
        "*a",
        "<<",
        "{",
        "]",
        '"',
    ]
)
NUMBERS = st.one_of(
    st.integers(-(10**6), 10**6),
    st.sampled_from([10**30, -(10**30), 2**63, 10**4000]),
    st.floats(allow_nan=True, allow_infinity=True),
)
SCALARS = st.one_of(st.none(), st.booleans(), NUMBERS, NASTY_TEXT, st.text(max_size=12))
JSON_VALUES = st.recursive(
    SCALARS, lambda inner: st.one_of(st.lists(inner, max_size=4), st.dictionaries(st.text(max_size=8), inner, max_size=4)), max_leaves=12
)

VALID_TASK: dict[str, Any] = {
    "name": "fuzz",
    "actions": [{"id": "a", "text": "do a"}, {"id": "b"}, "c"],
    "structure": {"chain": ["a", {"clique": ["b", "c"], "name": "B and C"}]},
    "demonstrations": [
        {"id": "d1", "steps": ["a", "b", "c"]},
        {"id": "d2", "steps": [{"action": "a", "start": 0.0, "end": 1.0}, "c", "b"]},
    ],
}


def _paths(value: Any, prefix: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    out = [prefix]
    if isinstance(value, dict):
        for key, item in value.items():
            out += _paths(item, (*prefix, key))
    elif isinstance(value, list):
        for index, item in enumerate(value):
            out += _paths(item, (*prefix, index))
    return out


def _replace(value: Any, path: tuple[Any, ...], new: Any) -> Any:
    if not path:
        return new
    head, rest = path[0], path[1:]
    if isinstance(value, dict):
        return {**value, head: _replace(value[head], rest, new)}
    copy = list(value)
    copy[head] = _replace(copy[head], rest, new)
    return copy


@st.composite
def broken_documents(draw: st.DrawFn, valid: dict[str, Any]) -> Any:
    """``valid`` with one to three random places replaced by random values or given an unknown key."""
    document: Any = valid
    for _ in range(draw(st.integers(1, 3))):
        path = draw(st.sampled_from(_paths(document)))
        if draw(st.booleans()):
            document = _replace(document, path, draw(JSON_VALUES))
        else:
            target: Any = document
            for part in path:
                target = target[part]
            if isinstance(target, dict):
                document = _replace(document, path, {**target, draw(st.sampled_from(["colour", "id", "x"])): draw(SCALARS)})
    return document


def _yaml(document: Any) -> str:
    try:
        return yaml.safe_dump(document, allow_unicode=True, sort_keys=False)
    except (yaml.YAMLError, UnicodeEncodeError, ValueError, OverflowError):
        return json.dumps(document, ensure_ascii=True, default=str)


def _json(document: Any) -> str:
    try:
        return json.dumps(document)
    except (ValueError, OverflowError):
        return "{" + repr(document)


RAW_TEXT = st.one_of(
    st.text(max_size=200),
    st.sampled_from(
        [
            "name: t\nname: u\n",
            "name: t\nactions: [&x a, *x, *y]\n",
            "name: t\nstructure: &a {chain: [x, *a]}\n",
            "name: t\nstructure: " + "[" * 300 + "]" * 300 + "\n",
            "{" * 500,
            "name: [t\n",
            "\ufeffname: t\n",
            "name: !!python/object:os.system x\n",
            "name: t\nactions: [a]\ndemonstrations:\n  - steps: [{action: a, start: " + "9" * 5000 + "}]\n",
        ]
    ),
)


@st.composite
def task_files(draw: st.DrawFn) -> tuple[str, str]:
    """``(suffix, text)`` of a task file that is valid, broken at random places, or noise."""
    suffix = draw(st.sampled_from([".yaml", ".json", ".csv"]))
    kind = draw(st.sampled_from(["broken", "broken", "raw", "truncated"]))
    if suffix == ".csv":
        return suffix, draw(csv_texts())
    if kind == "raw":
        return suffix, draw(RAW_TEXT)
    document = draw(broken_documents(VALID_TASK))
    text = _yaml(document) if suffix == ".yaml" else _json(document)
    if kind == "truncated":
        text = text[: draw(st.integers(0, len(text)))]
    return suffix, text


@st.composite
def csv_texts(draw: st.DrawFn) -> str:
    header = draw(
        st.sampled_from(
            ["demonstration,step,action", "demonstration,step,action,start,end", "demonstration,action,action", "step", ""]
        )
    )
    field = st.one_of(NASTY_TEXT.map(lambda t: t.replace("\udc80", "?")), st.sampled_from(["d1", "1", "2", "a", "b", '"x', "x\ny"]))
    rows = draw(st.lists(st.lists(field, min_size=1, max_size=5).map(",".join), max_size=5))
    return "\n".join([header, *rows]) + draw(st.sampled_from(["", "\n", '\n"']))


@st.composite
def map_texts(draw: st.DrawFn) -> str:
    """A household map: a random grid of map characters (and some that are not), sometimes ragged."""
    rows = draw(st.integers(1, 8))
    cols = draw(st.integers(1, 10))
    alphabet = st.sampled_from(list("##....SBTCRx \t"))
    grid = ["".join(draw(st.lists(alphabet, min_size=cols, max_size=cols))) for _ in range(rows)]
    if draw(st.booleans()):
        grid = ["#" * cols, *("#" + line[1:-1] + "#" if cols > 2 else line for line in grid), "#" * cols]
    return "\n".join(grid) + "\n"


VALID_SCENARIO: dict[str, Any] = {
    "name": "fuzz-circuit",
    "table": {"width": 104, "depth": 70},
    "goal": {"light": "led", "batteries_in_series": 2, "switch_controls": True},
    "scatter": {"seed": 3, "pieces": {"battery": 2, "switch": 1, "led": 1, "wire2": 3, "wire3": 2}},
    "planner": {"environments": 2},
}


@st.composite
def scenario_files(draw: st.DrawFn) -> tuple[str, str]:
    suffix = draw(st.sampled_from([".yaml", ".json"]))
    document = draw(broken_documents(VALID_SCENARIO))
    return suffix, _yaml(document) if suffix == ".yaml" else _json(document)


@st.composite
def observation_streams(draw: st.DrawFn) -> tuple[str, str]:
    """``(suffix, text)``: JSON Lines of moments, some valid (``["hand-seat"]``), some not."""
    moment = st.one_of(
        st.just(["hand-left_frame"]),
        st.builds(lambda e, t: {"events": e, "time": t}, st.lists(st.sampled_from(["hand-seat", "hand-peg"]), max_size=2), NUMBERS),
        JSON_VALUES,
    )
    lines = draw(st.lists(moment, min_size=1, max_size=5))
    return ".jsonl", "\n".join(_json(line) for line in lines) + "\n"


API_BODIES = st.one_of(
    JSON_VALUES,
    st.fixed_dictionaries({"progress": NUMBERS}),
    st.fixed_dictionaries({"x": NUMBERS, "y": NUMBERS}, optional={"t": NUMBERS, "z": SCALARS}),
    st.fixed_dictionaries({"events": st.lists(SCALARS, max_size=70)}),
)
"""Bodies for the API's POST operations: well-formed, out of range, of the wrong type, or noise."""


PAST_A_LIMIT = st.sampled_from(["-1", "-5", "10000000000", str(10**30), "1e999", "nan", "inf", "-inf", "", "x", "1.5e"])
"""Command-line values past any bound an option has (or no number at all)."""


@st.composite
def session_refused_tasks(draw: st.DrawFn) -> tuple[str, str]:
    """``(suffix, text)`` of a task file that reads, but that ``teach`` or ``chat`` cannot start a session on
    (no action; explicit states that contradict each other; no structure to enumerate states from), or a
    broken one."""
    kind = draw(st.sampled_from(["no-action", "contradiction", "no-structure", "broken"]))
    if kind == "broken":
        return draw(task_files())
    if kind == "no-action":
        document: dict[str, Any] = {"name": draw(st.sampled_from(["t", "no actions"])), "actions": []}
        if draw(st.booleans()):
            del document["actions"]
    elif kind == "contradiction":
        first, second = draw(st.permutations(["a", "b"]))
        state = draw(st.sampled_from([["x"], ["x", "y"]]))
        document = {
            "name": "contradiction",
            "demonstrations": [
                {"steps": [{"action": first, "state": state}, {"action": second, "state": ["z"]}]},
                {"steps": [{"action": second, "state": state}, {"action": first, "state": ["w"]}]},
            ],
        }
    else:
        document = {"name": "flat", "actions": ["a", "b"], "demonstrations": [{"steps": ["a", "b"]}]}
    suffix = draw(st.sampled_from([".yaml", ".json"]))
    return suffix, _yaml(document) if suffix == ".yaml" else _json(document)
