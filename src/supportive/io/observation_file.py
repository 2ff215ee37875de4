"""Read observation streams: one moment's contact events after another.

* ``.jsonl`` / ``.ndjson``: one moment per line, a JSON list of events (``["hand-peg", "peg-frame"]``) or an
  object ``{"events": [...], "time": 1.25}``; blank lines are skipped.
* ``.json`` / ``.yaml`` / ``.yml``: a list of such moments, or ``{"observations": [...]}``.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import yaml

from supportive.errors import ObservationFileError
from supportive.io.text import read_text

__all__ = ["Moment", "parse_observation_file"]

Moment = tuple[frozenset[str], float | None]
"""The events that hold at one moment, and the moment's time when the file gives one."""


def parse_observation_file(path: str | Path) -> list[Moment]:
    """Read an observation stream.

    Raises:
        ObservationFileError: naming the file, the line or item, and the problem.
    """
    path = Path(path)
    text = read_text(path, ObservationFileError)
    if not text.strip():
        raise ObservationFileError("file is empty", path=path)
    suffix = path.suffix.lower()
    if suffix in (".jsonl", ".ndjson"):
        moments = []
        for number, line in enumerate(text.splitlines(), start=1):
            if not line.strip():
                continue
            try:
                item = json.loads(line)
            except json.JSONDecodeError as exc:
                raise ObservationFileError(f"invalid JSON: {exc.msg}", path=path, line=number) from None
            moments.append(_moment(item, path, None, number))
        return moments
    if suffix not in (".json", ".yaml", ".yml"):
        raise ObservationFileError(
            f"unsupported file type {suffix or '(none)'!r}; use .jsonl, .json, .yaml or .yml", path=path
        )
    try:
        data = json.loads(text) if suffix == ".json" else yaml.safe_load(text)
    except json.JSONDecodeError as exc:
        raise ObservationFileError(f"invalid JSON: {exc.msg}", path=path, line=exc.lineno) from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        raise ObservationFileError(
            "invalid YAML", path=path, line=None if mark is None else mark.line + 1
        ) from None
    if isinstance(data, dict) and set(data) == {"observations"}:
        data = data["observations"]
    if not isinstance(data, list):
        raise ObservationFileError("expected a list of moments (or {observations: [...]})", path=path)
    return [_moment(item, path, f"observations[{i}]", None) for i, item in enumerate(data)]


def _moment(item: Any, path: Path, place: str | None, line: int | None) -> Moment:
    time = None
    if isinstance(item, dict):
        unknown = set(item) - {"events", "time"}
        if unknown:
            raise ObservationFileError(
                f"unknown key {sorted(unknown)[0]!r}", path=path, place=place, line=line
            )
        if "events" not in item:
            raise ObservationFileError("missing required key 'events'", path=path, place=place, line=line)
        time = item.get("time")
        if time is not None and (isinstance(time, bool) or not isinstance(time, int | float)):
            raise ObservationFileError(
                f"time must be a number, got {time!r}", path=path, place=place, line=line
            )
        item = item["events"]
    if not isinstance(item, list) or not all(isinstance(e, str) and e for e in item):
        raise ObservationFileError(
            "expected a list of contact events (non-empty strings)", path=path, place=place, line=line
        )
    return frozenset(item), None if time is None else float(time)
