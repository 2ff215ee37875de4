"""What every block module shares: where the results are, what a block is, reading a recorded file, running
a quick command, and filling a template from a file of numbers."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
RESULTS = ROOT / "docs" / "results"
BENCHMARKS = ROOT / "benchmarks" / "results"


@dataclass(frozen=True)
class Block:
    """How one generated passage is made.

    Attributes:
        source: Where its numbers come from, in words (a results file and the command that writes it).
        make: The passage's markdown: lines ending with a newline, or a phrase for an inline block.
        runs_command: Whether ``make`` runs a command (seconds) rather than reading a file.
        inline: Whether the block sits inside a line (``… <!-- numbers:x -->0.9<!-- /numbers:x --> …``)
            rather than on lines of its own.
    """

    source: str
    make: Callable[[], str]
    runs_command: bool = False
    inline: bool = False

    def body(self) -> str:
        """What goes between the markers."""
        return self.make() if self.inline else "\n" + self.make()


def read_json(path: Path) -> Any:
    return json.loads(path.read_text(encoding="utf-8"))


def command(*args: str) -> str:
    """The standard output of ``supportive ARGS`` (200 columns, so no line wraps), run from the repository."""
    env = {**os.environ, "COLUMNS": "200", "NO_COLOR": "1", "TERM": "dumb"}
    done = subprocess.run(
        [sys.executable, "-m", "supportive.cli", *args],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        check=False,
    )
    if done.returncode:
        raise RuntimeError(f"supportive {' '.join(args)} failed ({done.returncode}): {done.stderr.strip()}")
    return done.stdout


_FIELD = re.compile(r"\{(?P<path>[\w./-]+)(?:\|(?P<unit>ms|us|k|pct))?(?::(?P<format>[^}]*))?\}")
_SCALE = {"ms": 1e3, "us": 1e6, "k": 1e-3, "pct": 100.0}


def filled(template: str, data: Mapping[str, Any]) -> str:
    """``template`` with each ``{a.b.c|unit:format}`` replaced by ``data["a"]["b"]["c"]`` (a number picks an
    item of a list: ``{load.0}``), scaled by the unit (``ms``, ``us``: seconds to milli-/microseconds; ``k``:
    thousands; ``pct``: a share in per cent) and formatted.

    >>> filled("{x.y|ms:.1f} ms, {n:,}, load {load.0:.1f}", {"x": {"y": 0.01234}, "n": 1904, "load": [1.93, 2.0]})
    '12.3 ms, 1,904, load 1.9'
    """

    def value(match: re.Match[str]) -> str:
        item: Any = data
        for key in match["path"].split("."):
            item = item[int(key)] if isinstance(item, list) else item[key]
        if match["unit"]:
            item = item * _SCALE[match["unit"]]
        return format(item, match["format"] or "")

    return _FIELD.sub(value, template)
