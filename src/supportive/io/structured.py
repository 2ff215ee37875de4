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

from collections.abc import Sequence
from pathlib import Path
from typing import Any, Literal

import yaml
from pydantic import ValidationError

from supportive.errors import FileFormatError
from supportive.io.safe_load import compose_yaml, load_json, load_yaml

__all__ = ["kind_of", "line_of", "load_structured", "place_of", "schema_error"]


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
    """The line of the deepest node along ``loc`` that exists in the text (YAML and most JSON)."""
    node = compose_yaml(text)
    line = None
    for part in loc:
        if node is None:
            break
        line = node.start_mark.line + 1
        if isinstance(node, yaml.MappingNode):
            node = next((v for k, v in node.value if k.value == part), None)
        elif isinstance(node, yaml.SequenceNode) and isinstance(part, int) and part < len(node.value):
            node = node.value[part]
        else:
            node = None
    if node is not None:
        line = node.start_mark.line + 1
    return line


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
    exc: ValidationError, text: str, path: str | Path | None, error: type[FileFormatError]
) -> FileFormatError:
    """The first problem pydantic found, as one ``error`` naming its field and line."""
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
        message = first["msg"].removeprefix("Value error, ")
    else:
        message = template.format(key=key, got=kind_of(first.get("input")))
    return error(message, path=path, place=place_of(place_loc) or None, line=line_of(text, line_loc))
