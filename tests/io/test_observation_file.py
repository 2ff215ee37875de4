from __future__ import annotations

from pathlib import Path

import pytest

from supportive.errors import ObservationFileError
from supportive.io.observation_file import parse_observation_file


def test_jsonl_lists_and_objects(tmp_path: Path) -> None:
    path = tmp_path / "stream.jsonl"
    path.write_text('["a-b"]\n\n{"events": ["a-b", "b-c"], "time": 0.5}\n[]\n')
    assert parse_observation_file(path) == [
        (frozenset({"a-b"}), None),
        (frozenset({"a-b", "b-c"}), 0.5),
        (frozenset(), None),
    ]


@pytest.mark.parametrize("suffix", [".json", ".yaml"])
def test_lists_in_json_and_yaml(tmp_path: Path, suffix: str) -> None:
    path = tmp_path / f"stream{suffix}"
    path.write_text('{"observations": [["x-y"], {"events": [], "time": 2}]}')
    assert parse_observation_file(path) == [(frozenset({"x-y"}), None), (frozenset(), 2.0)]


BAD = {
    "empty.jsonl": ("", "file is empty"),
    "json.jsonl": ('["a"]\n{"events": [}\n', ":2: invalid JSON"),
    "number.jsonl": ('["a"]\n[1]\n', ":2: expected a list of contact events"),
    "key.jsonl": ('{"events": [], "colour": 1}\n', ":1: unknown key 'colour'"),
    "noevents.jsonl": ('{"time": 1}\n', ":1: missing required key 'events'"),
    "time.jsonl": ('{"events": [], "time": "soon"}\n', "time must be a number"),
    "notlist.json": ('{"a": 1}', "expected a list of moments"),
    "item.yaml": ("- [a]\n- 3\n", "observations[1]: expected a list"),
    "stream.txt": ("[]", "unsupported file type"),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_streams_are_located(tmp_path: Path, name: str) -> None:
    text, message = BAD[name]
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(ObservationFileError) as info:
        parse_observation_file(path)
    assert str(info.value).startswith(str(path)) and message in str(info.value)


def test_missing_file(tmp_path: Path) -> None:
    with pytest.raises(ObservationFileError, match="no such file"):
        parse_observation_file(tmp_path / "none.jsonl")
