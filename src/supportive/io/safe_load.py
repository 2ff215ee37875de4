"""The one safe loader for users' files: text, YAML, JSON and CSV, each within :mod:`supportive.io.limits`.

* text: only regular files (a FIFO, a device or a directory is refused before it is read, so ``/dev/zero``
  cannot fill memory and a FIFO cannot hang), at most :data:`MAX_FILE_BYTES`, UTF-8;
* YAML and JSON: at most :data:`MAX_DEPTH` levels of nesting and :data:`MAX_NODES` values (aliases counted as
  what they repeat, so an alias bomb is refused before anything expands it), no key twice in one mapping, no
  number longer than :data:`MAX_NUMBER_CHARS` (nor JSON's non-standard NaN and Infinity), no lone surrogate in a
  string (whether a number is finite and in range is for :mod:`supportive.io.values`, which names the field);
* CSV: strict quoting (an unterminated quote is an error, not the rest of the file swallowed into one field),
  fields of at most :data:`MAX_CSV_FIELD` characters, no column twice.

Every refusal is the caller's kind of :class:`~supportive.errors.FileFormatError`, naming the file and, where
known, the line.

>>> load_json('{"a": [1, 2.5]}', None, FileFormatError)
{'a': [1, 2.5]}
>>> load_yaml("a: 1" + chr(10) + "a: 2", "t.yaml", FileFormatError)
Traceback (most recent call last):
...
supportive.errors.FileFormatError: t.yaml:2: key 'a' appears twice in this mapping
"""

from __future__ import annotations

import csv
import io
import json
import os
import re
import stat
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any

import yaml
from yaml.composer import Composer
from yaml.constructor import SafeConstructor
from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode
from yaml.parser import Parser
from yaml.reader import Reader
from yaml.resolver import Resolver
from yaml.scanner import Scanner

from supportive.errors import FileFormatError
from supportive.io.limits import MAX_CSV_FIELD, MAX_DEPTH, MAX_FILE_BYTES, MAX_NODES, MAX_NUMBER_CHARS

__all__ = ["LIBYAML", "check_kind", "compose_yaml", "load_json", "load_yaml", "read_csv", "read_text"]

_SURROGATE = re.compile("[\ud800-\udfff]")
_JSON_TOKENS = re.compile(r'"(?:[^"\\]|\\.)*"|[\[\]{}]')


def check_kind(path: Path, suffixes: tuple[str, ...], what: str, error: type[FileFormatError]) -> str:
    """The suffix (lower case) of a file to read as ``what`` ("a task file"), one of ``suffixes``.

    Raises:
        error: naming the file, saying what is wrong — a folder, no such file, or another suffix — and what
            was expected.

    >>> check_kind(Path("/"), (".yaml", ".json"), "a task file", FileFormatError)
    Traceback (most recent call last):
    ...
    supportive.errors.FileFormatError: /: is a folder; expected a task file (.yaml or .json)
    """
    suffix = path.suffix.lower()
    expected = f"{what} ({', '.join(suffixes[:-1])} or {suffixes[-1]})" if len(suffixes) > 1 else f"{what} ({suffixes[0]})"
    if path.is_dir():
        raise error(f"is a folder; expected {expected}", path=path)
    if suffix not in suffixes:
        if not path.exists():
            raise error(f"no such file; expected {expected}", path=path)
        raise error(f"unsupported file type {suffix or '(none)'!r}; expected {expected}", path=path)
    return suffix


class _Refused(Exception):
    """A limit or rule broken while loading: what, and the 1-based line when known."""

    def __init__(self, problem: str, line: int | None = None) -> None:
        super().__init__(problem)
        self.problem = problem
        self.line = line


def read_text(path: Path, error: type[FileFormatError], *, limit: int = MAX_FILE_BYTES) -> str:
    """The text of a user's file: a regular file of at most ``limit`` bytes of UTF-8.

    Raises:
        error: "no such file", "not a regular file", "larger than …", "not UTF-8 …" or "cannot read: …",
            naming the file.
    """
    try:
        descriptor = os.open(path, os.O_RDONLY | os.O_NONBLOCK)  # a FIFO opens without waiting for a writer
    except FileNotFoundError:
        raise error("no such file", path=path) from None
    except OSError as exc:
        raise error(f"cannot read: {exc.strerror}", path=path) from None
    try:
        mode = os.fstat(descriptor).st_mode
        if not stat.S_ISREG(mode):
            kind = "a directory" if stat.S_ISDIR(mode) else "a FIFO" if stat.S_ISFIFO(mode) else "a device or socket"
            raise error(f"not a regular file ({kind})", path=path)
        chunks = []
        size = 0
        while size <= limit:
            chunk = os.read(descriptor, min(1 << 20, limit + 1 - size))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
    except OSError as exc:
        raise error(f"cannot read: {exc.strerror}", path=path) from None
    finally:
        os.close(descriptor)
    data = b"".join(chunks)
    if len(data) > limit:
        raise error(f"file is larger than {limit:,} bytes, the limit", path=path)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[: exc.start].count(b"\n") + 1
        raise error(f"not UTF-8 text: byte 0x{data[exc.start]:02x} cannot be decoded", path=path, line=line) from None


# ------------------------------------------------------------------------------------------------- YAML
class _PythonEvents(Reader, Scanner, Parser):
    """PyYAML's Python reader, scanner and parser: the events of a text, for a PyYAML built without libyaml."""

    def __init__(self, stream: str) -> None:
        Reader.__init__(self, stream)
        Scanner.__init__(self)
        Parser.__init__(self)


LIBYAML: bool = yaml.__with_libyaml__
"""Whether PyYAML has libyaml (its wheels do): YAML is read, and task files written, by it; else by PyYAML's
Python reader and emitter, the same, slower. A reader error's position then counts characters, not bytes."""

if TYPE_CHECKING or LIBYAML:
    from yaml._yaml import CParser as _Events
else:
    _Events = _PythonEvents


class _Loader(_Events, Composer, SafeConstructor, Resolver):
    """PyYAML's safe loader with the limits: nesting depth while composing, no duplicate key, no overlong or
    non-finite number, no lone surrogate (refused before parsing; libyaml refuses one written as an escape).

    The text is read and parsed into events by libyaml (PyYAML's ``CParser``, five times as fast as its
    Python reader and scanner on a 5,000-action task file; those where PyYAML has no libyaml); the events are
    composed into nodes here, in Python (PyYAML's ``Composer``), so that the depth is checked as each node
    opens."""

    get_single_node = Composer.get_single_node
    compose_document = Composer.compose_document
    check_node = Composer.check_node
    get_node = Composer.get_node

    def __init__(self, stream: str) -> None:
        lone = _SURROGATE.search(stream)  # libyaml reads UTF-8, which cannot hold one
        if lone:
            offset = len(stream[: lone.start()].encode("utf-8")) if LIBYAML else lone.start()
            raise yaml.reader.ReaderError("<text>", offset, ord(lone.group()), "unicode", "special characters are not allowed")
        _Events.__init__(self, stream)
        Composer.__init__(self)
        SafeConstructor.__init__(self)
        Resolver.__init__(self)
        self._depth = 0

    def compose_node(self, parent: Node | None, index: int) -> Node | None:
        if self.check_event(yaml.AliasEvent):
            return Composer.compose_node(self, parent, index)
        self._depth += 1
        try:
            if self._depth > MAX_DEPTH:
                event = self.peek_event()
                mark = None if event is None else event.start_mark
                raise _Refused(f"nested deeper than {MAX_DEPTH} levels, the limit", None if mark is None else mark.line + 1)
            return Composer.compose_node(self, parent, index)
        finally:
            self._depth -= 1

    def construct_mapping(self, node: MappingNode, deep: bool = False) -> dict[Any, Any]:
        seen: set[Any] = set()
        for key_node, _ in node.value if isinstance(node, MappingNode) else ():
            if key_node.tag == "tag:yaml.org,2002:merge":
                continue
            key = self.construct_object(key_node, deep=True)
            try:
                if key in seen:
                    raise _Refused(f"key {key!r} appears twice in this mapping", key_node.start_mark.line + 1)
                seen.add(key)
            except TypeError:
                continue  # an unhashable key: PyYAML's own error says so
        return super().construct_mapping(node, deep=deep)

    def construct_yaml_int(self, node: ScalarNode) -> int:
        _number_length(node)
        return super().construct_yaml_int(node)

    def construct_yaml_float(self, node: ScalarNode) -> float:
        _number_length(node)
        return super().construct_yaml_float(node)


_Loader.yaml_constructors = {
    **SafeConstructor.yaml_constructors,
    "tag:yaml.org,2002:int": _Loader.construct_yaml_int,
    "tag:yaml.org,2002:float": _Loader.construct_yaml_float,
}


def _line_at(text: str, position: int) -> int:
    """The 1-based line of a reader error's position in ``text``."""
    if LIBYAML:
        return text.encode("utf-8", "surrogatepass")[:position].count(b"\n") + 1
    return text.count("\n", 0, position) + 1


def _number_length(node: ScalarNode) -> None:
    if len(node.value) > MAX_NUMBER_CHARS:
        raise _Refused(f"a number of {len(node.value):,} characters (at most {MAX_NUMBER_CHARS})", node.start_mark.line + 1)


def _count(root: Node) -> None:
    """Refuse a node graph holding more than :data:`MAX_NODES` values once aliases are expanded (each
    distinct node is counted once, with what it contains, so the count itself takes linear time)."""
    sizes: dict[int, int] = {}
    open_nodes: set[int] = set()

    def size(node: Node) -> int:
        key = id(node)
        if key in sizes:
            return sizes[key]
        if key in open_nodes:
            raise _Refused("an alias refers to a node that contains it", node.start_mark.line + 1)
        open_nodes.add(key)
        total = 1
        if isinstance(node, SequenceNode):
            total += sum(size(child) for child in node.value)
        elif isinstance(node, MappingNode):
            total += sum(size(k) + size(v) for k, v in node.value)
        open_nodes.discard(key)
        if total > MAX_NODES:
            raise _Refused(
                f"the document holds more than {MAX_NODES:,} values once its aliases are expanded, the limit",
                node.start_mark.line + 1,
            )
        sizes[key] = total
        return total

    size(root)


def _compose(text: str) -> Node | None:
    loader = _Loader(text)
    try:
        node = loader.get_single_node()
        if node is not None:
            _count(node)
        return node
    finally:
        loader.dispose()


def compose_yaml(text: str) -> Node | None:
    """The YAML node graph of ``text`` within the limits (for finding the line of a field); None when the
    text does not compose."""
    try:
        return _compose(text)
    except (yaml.YAMLError, _Refused, RecursionError):
        return None


def load_yaml(text: str, path: str | Path | None, error: type[FileFormatError]) -> Any:
    """The data of a YAML document, within the limits.

    Raises:
        error: for text that does not parse or breaks a limit, with the line.
    """
    loader: _Loader | None = None
    try:
        loader = _Loader(text)  # libyaml checks the characters as it reads: a ReaderError may come later
        node = loader.get_single_node()
        if node is None:
            return None
        _count(node)
        return loader.construct_document(node)
    except _Refused as exc:
        raise error(exc.problem, path=path, line=exc.line) from None
    except yaml.reader.ReaderError as exc:
        line = _line_at(text, exc.position)
        raise error(f"invalid YAML: character U+{exc.character:04X} is not allowed in YAML", path=path, line=line) from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        raise error(f"invalid YAML: {problem}", path=path, line=None if mark is None else mark.line + 1) from None
    finally:
        if loader is not None:
            loader.dispose()


# ------------------------------------------------------------------------------------------------- JSON
def _pairs(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in pairs:
        if key in out:
            raise _Refused(f"key {key!r} appears twice in this object")
        out[key] = value
    return out


def _json_int(text: str) -> int:
    if len(text) > MAX_NUMBER_CHARS:
        raise _Refused(f"a number of {len(text):,} characters (at most {MAX_NUMBER_CHARS})")
    return int(text)


def _json_float(text: str) -> float:
    if len(text) > MAX_NUMBER_CHARS:
        raise _Refused(f"a number of {len(text):,} characters (at most {MAX_NUMBER_CHARS})")
    return float(text)  # 1e400 is inf: the schema that reads it refuses it, naming the field


def _json_constant(name: str) -> float:
    raise _Refused(f"{name} is not a JSON number")


def _json_depth(text: str) -> None:
    depth = 0
    for match in _JSON_TOKENS.finditer(text):
        token = match.group()
        if token in "[{":
            depth += 1
            if depth > MAX_DEPTH:
                raise _Refused(f"nested deeper than {MAX_DEPTH} levels, the limit", text.count("\n", 0, match.start()) + 1)
        elif token in "]}":
            depth -= 1


def _walk_strings(data: Any) -> Iterator[str]:
    stack = [data]
    while stack:
        item = stack.pop()
        if isinstance(item, str):
            yield item
        elif isinstance(item, dict):
            stack.extend(item)
            stack.extend(item.values())
        elif isinstance(item, list):
            stack.extend(item)


def load_json(text: str, path: str | Path | None, error: type[FileFormatError], *, line: int | None = None) -> Any:
    """The data of a JSON document, within the limits (``line``: the line the text starts on, for JSON Lines).

    Raises:
        error: for text that does not parse or breaks a limit, with the line when known.
    """
    try:
        _json_depth(text)
        data = json.loads(
            text, object_pairs_hook=_pairs, parse_int=_json_int, parse_float=_json_float, parse_constant=_json_constant
        )
    except _Refused as exc:
        where = exc.line if line is None or exc.line is None else line + exc.line - 1
        raise error(exc.problem, path=path, line=where if where is not None else line) from None
    except json.JSONDecodeError as exc:
        raise error(f"invalid JSON: {exc.msg}", path=path, line=exc.lineno if line is None else line + exc.lineno - 1) from None
    except RecursionError:  # only below the depth limit when the interpreter's stack is already deep
        raise error(f"nested deeper than {MAX_DEPTH} levels, the limit", path=path, line=line) from None
    if any(_SURROGATE.search(s) for s in _walk_strings(data)):
        raise error("a string holds a lone surrogate (not a character)", path=path, line=line)
    return data


# -------------------------------------------------------------------------------------------------- CSV
def read_csv(text: str, path: str | Path | None, error: type[FileFormatError]) -> tuple[list[str], list[tuple[int, list[str]]]]:
    """The header (names stripped) and every row of CSV text with the line it starts on.

    Raises:
        error: for an unterminated quote, a field over :data:`MAX_CSV_FIELD` characters, or a column named
            twice, with the line.
    """
    reader = csv.reader(io.StringIO(text, newline=""), strict=True)
    rows: list[tuple[int, list[str]]] = []
    start = 1
    try:
        for row in reader:
            if any(len(field) > MAX_CSV_FIELD for field in row):
                raise error(f"a field longer than {MAX_CSV_FIELD:,} characters, the limit", path=path, line=start)
            rows.append((start, row))
            start = reader.line_num + 1
    except csv.Error as exc:
        problem = str(exc)
        if "end of data" in problem or "unexpected end" in problem:
            problem = "a quoted field is never closed"
        elif "field larger than field limit" in problem:
            problem = f"a field longer than {MAX_CSV_FIELD:,} characters, the limit"
        raise error(f"invalid CSV: {problem}", path=path, line=start) from None
    if not rows:
        return [], []
    header = [name.strip() for name in rows[0][1]]
    twice = sorted({name for name in header if header.count(name) > 1})
    if twice:
        raise error(f"column {twice[0]!r} appears twice in the header", path=path, line=1)
    return header, rows[1:]
