"""Reading structured user files (YAML or JSON checked against a pydantic schema), with every problem
reported as the caller's kind of :class:`~supportive.errors.FileFormatError`: the file, the line when known,
the field (``demonstrations[1].steps[3]``) and what was wrong.

>>> place_of(["demonstrations", 1, "steps", 3])
'demonstrations[1].steps[3]'
>>> text = chr(10).join(["name: x", "pieces:", "  - kind: led"])
>>> line_of(text, ["pieces", 0, "kind"])
3
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Sequence
from pathlib import Path
from typing import Any, Literal, get_args

import yaml
from pydantic import BaseModel, ValidationError

from supportive.errors import FileFormatError
from supportive.io.safe_load import compose_yaml, load_json, load_yaml

__all__ = ["kind_of", "line_of", "load_structured", "place_of", "plain_words", "schema_error", "schema_keys"]


def load_structured(
    text: str, format: Literal["yaml", "json"], path: str | Path | None, error: type[FileFormatError]
) -> Any:
    """The data in ``text`` (YAML or JSON), read by the safe loader (:mod:`supportive.io.safe_load`).

    Raises:
        error: for text that does not parse or breaks a limit, with the line of the problem.
    """
    if format == "json":
        return load_json(text, path, error)
    return load_yaml(text, path, error)


def kind_of(value: object) -> str:
    """What a parsed value is, in words (``a mapping``, ``a list``, ``int 3``)."""
    return {dict: "a mapping", list: "a list", str: "a string", type(None): "nothing"}.get(
        type(value), f"{type(value).__name__} {value!r}"
    )


def place_of(loc: Sequence[str | int]) -> str:
    """A field's path as people write it: keys joined by dots, list positions in brackets."""
    out = ""
    for part in loc:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out


def line_of(text: str, loc: Sequence[str | int]) -> int | None:
    """The line of the deepest node along ``loc`` that exists in the text (YAML and most JSON): for a
    mapping's key, the key's own line (its value may be a block that starts on the next line), for a list's
    item, the item's.

    >>> line_of("a: 1" + chr(10) + "b:" + chr(10) + "  - x" + chr(10), ["b"])
    2
    >>> line_of("a: 1" + chr(10) + "b:" + chr(10) + "  - x" + chr(10), ["b", 0])
    3
    """
    node = compose_yaml(text)
    line = None
    for part in loc:
        if node is None:
            break
        line = node.start_mark.line + 1
        if isinstance(node, yaml.MappingNode):
            pair = next(((k, v) for k, v in node.value if k.value == part), None)
            if pair is None:
                node = None
                continue
            line = int(pair[0].start_mark.line) + 1
            node = pair[1]
            if part == loc[-1] and node is not None and not isinstance(node, yaml.ScalarNode):
                return line  # the key names the place; its block value begins below it
        elif isinstance(node, yaml.SequenceNode) and isinstance(part, int) and part < len(node.value):
            node = node.value[part]
        else:
            node = None
    if node is not None:
        line = node.start_mark.line + 1
    return line


CLOSE = 0.75
"""How alike (difflib's ratio) an unknown key must be to a known one to be suggested ("chian" → "chain")."""

_MESSAGES = {
    "missing": "missing required key {key!r}",
    "extra_forbidden": "unknown key {key!r}",
    "list_type": "expected a list, got {got}",
    "string_type": "expected a string, got {got}",
    "float_type": "expected a number, got {got}",
    "float_parsing": "expected a number, got {got}",
    "int_type": "expected a whole number, got {got}",
    "int_parsing": "expected a whole number, got {got}",
    "int_from_float": "expected a whole number, got {got}",
    "bool_type": "expected true or false, got {got}",
    "bool_parsing": "expected true or false, got {got}",
    "model_type": "expected a mapping, got {got}",
    "dict_type": "expected a mapping, got {got}",
    "string_too_short": "must not be empty",
    "too_short": "must not be empty",
}


def schema_error(
    exc: ValidationError,
    text: str,
    path: str | Path | None,
    error: type[FileFormatError],
    model: type[BaseModel] | None = None,
) -> FileFormatError:
    """The first problem pydantic found, as one ``error`` naming its field and line, in plain words; an
    unknown key gets a "did you mean" from the keys of ``model`` (the file's schema) when one is close."""
    first = exc.errors()[0]
    loc = [p for p in first["loc"] if not (isinstance(p, str) and p.startswith("function-"))]
    kind = first["type"]
    key = loc[-1] if loc else ""
    if kind in ("missing", "extra_forbidden"):
        place_loc = loc[:-1]
        line_loc = loc if kind == "extra_forbidden" else loc[:-1]
    else:
        place_loc = line_loc = loc
    template = _MESSAGES.get(kind)
    if template is None:
        message = plain_words(first["msg"].removeprefix("Value error, "), first.get("input"))
    else:
        message = template.format(key=key, got=kind_of(first.get("input")))
    if kind == "extra_forbidden" and model is not None:
        close = difflib.get_close_matches(str(key), sorted(schema_keys(model)), n=1, cutoff=CLOSE)
        if close:
            message += f"; did you mean {close[0]!r}?"
    return error(message, path=path, place=place_of(place_loc) or None, line=line_of(text, line_loc))


_PYDANTIC = (
    (re.compile(r"^Input should be greater than or equal to (.+)$"), "expected at least {0}"),
    (re.compile(r"^Input should be less than or equal to (.+)$"), "expected at most {0}"),
    (re.compile(r"^Input should be (greater|less) than (.+)$"), "expected {0} than {1}"),
    (re.compile(r"^Input should be a valid integer.*$"), "expected a whole number"),
    (re.compile(r"^Input should be a valid (?:number|float).*$"), "expected a number"),
    (re.compile(r"^Input should be a valid boolean.*$"), "expected true or false"),
    (re.compile(r"^Input should be (?:a valid |an? )?(.*?)(?:, unable to parse .*)?$"), "expected {0}"),
    (re.compile(r"^(?:List|Tuple|Dictionary|Set) should have at (most|least) (\d+) items? after validation, not (\d+)$"), "expected at {0} {1} items, got {2}"),
    (re.compile(r"^String should have at (most|least) (\d+) characters?$"), "expected at {0} {1} characters"),
    (re.compile(r"^String should match pattern '(.*)'$"), "not in the expected form"),
)


def plain_words(message: str, value: object = None) -> str:
    """pydantic's wording of a problem ("Input should be 'chain' or 'clique'") in the words the rest of the
    errors use ("expected 'chain' or 'clique', got 'chian'").

    >>> plain_words("Input should be greater than or equal to 0", -1)
    'expected at least 0, got -1'
    >>> plain_words("List should have at most 3 items after validation, not 5", [])
    'expected at most 3 items, got 5'
    >>> plain_words("Input should be a valid integer, unable to parse string as an integer")
    'expected a whole number'
    """
    for pattern, words in _PYDANTIC:
        found = pattern.match(message)
        if found is not None:
            said = words.format(*found.groups())
            if words.startswith("expected") and "got" not in words and isinstance(value, str | int | float) and not isinstance(value, bool):
                said += f", got {value!r}" if len(repr(value)) <= 60 else ", got a value that is not"
            return said
    return message


def schema_keys(model: type[BaseModel]) -> set[str]:
    """Every key a pydantic model of a file's schema reads, at any depth (names and aliases): what an unknown
    key's "did you mean" is chosen from."""
    keys: set[str] = set()
    seen: set[type[BaseModel]] = set()

    def visit(current: type[BaseModel]) -> None:
        if current in seen:
            return
        seen.add(current)
        for name, info in current.model_fields.items():
            keys.add(info.alias or name)
            for inner in _models_in(info.annotation):
                visit(inner)

    visit(model)
    return keys


def _models_in(annotation: object) -> list[type[BaseModel]]:
    """The pydantic models a type annotation mentions (inside lists, unions, ``Annotated`` …)."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    return [m for arg in get_args(annotation) for m in _models_in(arg)]
