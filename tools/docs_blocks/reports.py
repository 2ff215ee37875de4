"""Parts of an experiment's report (``report.md``, ``timing.md``) made from its recorded metrics in
``docs/results/``."""

from __future__ import annotations

import re
import tempfile
from pathlib import Path

from .common import RESULTS, Block, read_json


def _report(experiment: str, file: str) -> str:
    """The experiment's ``report.md`` made from the recorded ``metrics.json``."""
    from supportive.experiments import get

    return get(experiment).report(read_json(RESULTS / file))


def nth_table(experiment: str, file: str, header: str, n: int = 0) -> str:
    """The ``n``-th table of ``experiment``'s report (from ``docs/results/FILE``) whose header starts with
    ``header``."""
    tables = re.findall(r"(?:^\|.*\|\n)+", _report(experiment, file) + "\n", re.M)
    matching = [str(t) for t in tables if t.startswith(header)]
    if len(matching) <= n:
        raise ValueError(f"{experiment}'s report has no table {n} starting {header!r}")
    return matching[n]


def report_table(experiment: str, file: str, header: str, n: int = 0) -> Block:
    """The ``n``-th (by default the first) table of ``experiment``'s report (from ``docs/results/FILE``) whose
    header starts with ``header``."""
    return Block(
        f"docs/results/{file} (supportive reproduce {experiment})",
        lambda: nth_table(experiment, file, header, n),
    )


def report_part(experiment: str, file: str, first: str, stop: str) -> Block:
    """The lines of ``experiment``'s report from the heading ``first`` up to the heading ``stop``, its
    headings two levels down (they sit under a section of the docs)."""

    def make() -> str:
        text = _report(experiment, file)
        part = text[text.index(f"\n{first}") + 1 : text.index(f"\n{stop}") + 1]
        return re.sub(r"^## ", "#### ", part, flags=re.M)

    return Block(f"docs/results/{file} (supportive reproduce {experiment})", make)


def timing_part(experiment: str, file: str, first: str, stop: str | None = None) -> Block:
    """The lines of the ``timing.md`` that ``experiment``'s ``timing_report`` writes from the recorded
    ``timing.json`` (``docs/results/FILE``): from the line starting ``first`` up to the one starting ``stop``
    (or the end), headings two levels down."""

    def make() -> str:
        from supportive.experiments import get

        report = get(experiment).timing_report
        if report is None:
            raise ValueError(f"{experiment} has no timing report")
        with tempfile.TemporaryDirectory() as folder:
            report(read_json(RESULTS / file)["trials"], Path(folder))
            text = (Path(folder) / "timing.md").read_text(encoding="utf-8")
        start = text.index(f"\n{first}") + 1
        end = len(text) if stop is None else text.index(f"\n{stop}", start) + 1
        return re.sub(r"^## ", "#### ", text[start:end].rstrip("\n") + "\n", flags=re.M)

    return Block(f"docs/results/{file} (supportive reproduce {experiment}: timing.json)", make)
