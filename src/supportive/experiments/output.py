"""The files a run writes: ``metrics.json`` (deterministic), ``report.md``, ``run.json`` (wall time and
where it ran) and, when trials measured wall-clock times, ``timing.json``."""

from __future__ import annotations

import json
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from supportive.errors import ExperimentError

__all__ = ["METRICS_FILE", "REPORT_FILE", "RUN_FILE", "TIMING_FILE", "dump_json", "write_text"]

METRICS_FILE = "metrics.json"
"""The metrics: the same trials give the same bytes, however many workers ran them."""
REPORT_FILE = "report.md"
"""The markdown report: this run's numbers beside the thesis's."""
RUN_FILE = "run.json"
"""How the run went: wall time, workers, scheduler, versions. Differs from run to run by design."""
TIMING_FILE = "timing.json"
"""The trials' wall-clock measurements (their ``"timing"``), in trial order. Differs from run to run by
design."""


def dump_json(data: Mapping[str, Any], *, what: str = "metrics") -> str:
    """``data`` as JSON text that depends on nothing but its content: sorted keys, fixed indentation.

    Raises:
        ExperimentError: when ``data`` is not plain JSON data (or holds NaN or infinity).

    >>> dump_json({"b": 1, "a": [0.5, None]})
    '{\\n  "a": [\\n    0.5,\\n    null\\n  ],\\n  "b": 1\\n}\\n'
    """
    try:
        return json.dumps(data, sort_keys=True, indent=2, ensure_ascii=False, allow_nan=False) + "\n"
    except (TypeError, ValueError) as exc:
        raise ExperimentError(f"{what} are not plain JSON data: {exc}") from None


def write_text(path: Path, text: str) -> Path:
    """Write ``text`` to ``path`` (UTF-8), creating its directory.

    Raises:
        ExperimentError: when the file cannot be written.
    """
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise ExperimentError(f"{path}: cannot write: {exc.strerror or exc}") from None
    return path
