"""Read observation streams: one moment's contact events after another.

* ``.jsonl`` / ``.ndjson``: one moment per line, a JSON list of events (``["hand-peg", "peg-frame"]``) or an
  object ``{"events": [...], "time": 1.25}``; blank lines are skipped.
* ``.json`` / ``.yaml`` / ``.yml``: a list of such moments, or ``{"observations": [...]}``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from supportive.errors import ObservationFileError
from supportive.io.limits import MAX_SECONDS
from supportive.io.safe_load import check_kind, load_json, load_yaml, read_text
from supportive.io.values import check_id, check_number

__all__ = ["SUFFIXES", "Moment", "parse_observation_file"]

SUFFIXES = (".jsonl", ".ndjson", ".json", ".yaml", ".yml")
"""The file types of an observation stream: JSON lines, or one JSON or YAML document."""

Moment = tuple[frozenset[str], float | None]
"""The events that hold at one moment, and the moment's time when the file gives one."""


def parse_observation_file(path: str | Path) -> list[Moment]:
    """Read an observation stream.

    Raises:
        ObservationFileError: naming the file, the line or item, and the problem.
    """
    path = Path(path)
    suffix = check_kind(path, SUFFIXES, "an observation stream", ObservationFileError)
    text = read_text(path, ObservationFileError)
    if not text.strip():
        raise ObservationFileError("file is empty", path=path)
    if suffix in (".jsonl", ".ndjson"):
        moments = []
        for number, line in enumerate(text.splitlines(), start=1):
            if not line.strip():
                continue
            item = load_json(line, path, ObservationFileError, line=number)
            moments.append(_moment(item, path, None, number))
        return moments
    if suffix == ".json":
        data = load_json(text, path, ObservationFileError)
    else:
        data = load_yaml(text, path, ObservationFileError)
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
        if time is not None:
            try:
                check_number(time, "time", low=-MAX_SECONDS, high=MAX_SECONDS)
            except ValueError as exc:
                raise ObservationFileError(str(exc), path=path, place=place, line=line) from None
        item = item["events"]
    if not isinstance(item, list) or not all(isinstance(e, str) and e for e in item):
        raise ObservationFileError(
            "expected a list of contact events (non-empty strings)", path=path, place=place, line=line
        )
    for event in item:
        try:
            check_id(event, what="a contact event")
        except ValueError as exc:
            raise ObservationFileError(str(exc), path=path, place=place, line=line) from None
    return frozenset(item), None if time is None else float(time)
