"""Readings and findings: how an experiment reads an under-specified detail of the thesis, and what each
reading gives beside the thesis's own number.

Where the thesis leaves a detail open (when the learner asks, what a macro action does, what "efficiency
increase" means), an experiment declares each reasonable reading as a named :class:`Reading` and runs them
all, so that its report shows every reading side by side with the thesis. The first reading is the default:
the one whose text is closest to the thesis's (its ``why`` says so). A run may be restricted to some
readings (``run_experiment(..., readings=("at-start",))``, ``supportive reproduce NAME --reading at-start``).

An experiment's ``findings`` turn its metrics into :class:`Finding` rows — quantity, the thesis's number,
this run's number under each reading, a verdict — which ``reproduce all`` gathers into one summary table
(:func:`findings_table`).

>>> finding = Finding("comprehension at 12", "65.4 %", (("pilot", "43.1 %"), ("at-start", "61.7 %")), "not reproduced")
>>> finding.value("at-start")
'61.7 %'
>>> print(findings_table([("active-learning", "Figure 2.11", [finding])]).splitlines()[-1])
| active-learning | Figure 2.11 | comprehension at 12 | 65.4 % | **pilot 43.1 %** · at-start 61.7 % | not reproduced |
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from supportive.errors import ExperimentError
from supportive.experiments.tables import markdown_table

__all__ = ["Finding", "Reading", "findings_table", "reading_names", "readings_table", "select_readings"]

_NAME = re.compile(r"^[a-z0-9]+(?:-[a-z0-9]+)*$")


@dataclass(frozen=True)
class Reading:
    """One reading of an under-specified detail of the thesis.

    Attributes:
        name: Lowercase words joined by hyphens (``at-start``), unique within its experiment.
        summary: What this reading does, in one line.
        why: The thesis text it reads, and (for the default) why that text is the closest.
    """

    name: str
    summary: str
    why: str

    def __post_init__(self) -> None:
        if not _NAME.match(self.name):
            raise ExperimentError(f"reading name {self.name!r}: expected lowercase words joined by hyphens")


@dataclass(frozen=True)
class Finding:
    """One row of the summary table: a quantity, the thesis's number and this run's under each reading.

    Attributes:
        quantity: What is compared (``"solo distance, % known at 12"``).
        thesis: The thesis's number or claim, as printed.
        values: ``(reading, this run's number)`` pairs, the default reading first; the reading is ``""`` for
            an experiment without readings.
        verdict: Reproduced or not, and what limits it, in a few words.
    """

    quantity: str
    thesis: str
    values: tuple[tuple[str, str], ...]
    verdict: str

    def value(self, reading: str = "") -> str:
        """This run's number under ``reading``.

        Raises:
            ExperimentError: when the finding has no value under that reading.
        """
        for name, value in self.values:
            if name == reading:
                return value
        raise ExperimentError(f"finding {self.quantity!r} has no value under reading {reading!r}")

    def as_json(self) -> dict[str, Any]:
        """Plain JSON."""
        return {
            "quantity": self.quantity,
            "thesis": self.thesis,
            "values": [{"reading": r, "value": v} for r, v in self.values],
            "verdict": self.verdict,
        }


def reading_names(readings: Iterable[Reading]) -> tuple[str, ...]:
    """The names of ``readings``, in order."""
    return tuple(r.name for r in readings)


def select_readings(
    experiment: str, known: Sequence[Reading], wanted: Sequence[str] | None
) -> tuple[str, ...]:
    """The readings a run covers: all of ``known`` (default first) when ``wanted`` is None, else ``wanted``
    in the order of ``known``.

    Raises:
        ExperimentError: for an experiment without readings asked for some, an unknown reading or none.
    """
    names = reading_names(known)
    if wanted is None:
        return names
    if isinstance(wanted, str):
        wanted = (wanted,)
    if not names:
        raise ExperimentError(f"experiment {experiment} has no readings to choose from")
    unknown = [w for w in wanted if w not in names]
    if unknown:
        raise ExperimentError(
            f"experiment {experiment}: unknown reading {unknown[0]!r}; its readings are {', '.join(names)}"
        )
    if not wanted:
        raise ExperimentError(f"experiment {experiment}: choose at least one reading ({', '.join(names)})")
    return tuple(n for n in names if n in wanted)


def readings_table(
    known: Sequence[Reading],
    run: Sequence[str],
    column: str,
    extra: tuple[str, Mapping[str, str]] | None = None,
) -> list[str]:
    """The lines of a report's markdown table of the readings a run covered (``run``, names of ``known``):
    name (the default marked), an optional ``extra`` column (title, value per reading), what the reading does
    under the title ``column``, and the thesis's text.

    >>> readings_table([Reading("a", "asks early", "the text")], ["a"], "schedule")[2]
    '| `a` (default) | asks early | the text |'
    """
    titles = ["reading", *([extra[0]] if extra else []), column, "the thesis's text"]
    rows = []
    for name in run:
        reading = next(r for r in known if r.name == name)
        default = " (default)" if name == known[0].name else ""
        rows.append([f"`{name}`{default}", *([extra[1][name]] if extra else []), reading.summary, reading.why])
    return markdown_table(titles, rows, align="l" * len(titles))


def _cell(finding: Finding) -> str:
    parts = []
    for i, (reading, value) in enumerate(finding.values):
        text = f"{reading} {value}" if reading else value
        parts.append(f"**{text}**" if i == 0 and len(finding.values) > 1 else text)
    return " · ".join(parts)


def findings_table(rows: Iterable[tuple[str, str, Sequence[Finding | Mapping[str, Any]]]]) -> str:
    """The summary table (markdown) of ``(experiment, thesis figure, findings)`` rows; the default reading's
    number is bold when there are several. Findings may be given as :class:`Finding` or as its JSON."""
    header = ["experiment", "thesis", "quantity", "thesis's number", "ours, by reading (default first, bold)", "verdict"]
    cells = []
    for experiment, figure, findings in rows:
        for item in findings:
            finding = item if isinstance(item, Finding) else _from_json(item)
            cells.append([experiment, figure, finding.quantity, finding.thesis, _cell(finding), finding.verdict])
    return "\n".join(markdown_table(header, cells, align="l" * len(header)))


def _from_json(data: Mapping[str, Any]) -> Finding:
    values = tuple((v["reading"], v["value"]) for v in data["values"])
    return Finding(data["quantity"], data["thesis"], values, data["verdict"])
