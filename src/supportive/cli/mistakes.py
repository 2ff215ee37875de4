"""Mistake detection scored, as ``supportive evaluate FILE --mistakes`` and ``supportive captaincook --mistakes``
print it: every method's precision, recall and F1, per kind, the delay of missing steps, and the steps flagged
on clean demonstrations."""

from __future__ import annotations

import json
from typing import Any

from supportive.cli.output import out, say
from supportive.evaluation.mistakes import (
    KIND_HEADERS,
    METHODS,
    MistakeEvaluation,
    kind_rows,
    shown,
    shown_rates,
)
from supportive.render.tables import fitted_table

__all__ = ["print_mistakes"]


def print_mistakes(evaluation: MistakeEvaluation, title: str, *, as_json: bool, extra: dict[str, Any] | None = None) -> None:
    """Print a mistake evaluation as tables (or JSON, with ``extra`` fields merged in)."""
    data = evaluation.as_dict() | (extra or {})
    if as_json:
        out.print_json(json.dumps(data))
        return
    methods: dict[str, dict[str, Any]] = data["methods"]  # type: ignore[assignment]
    others = "the correct ones among the others" if evaluation.learned_from == "correct" else "all the others"
    say(
        f"{title}: {evaluation.held_out} demonstrations held out in turn, each judged by what was learned from "
        f"{others}; {evaluation.steps} steps, detector threshold {evaluation.thresholds[0]}"
    )
    rows = [
        [name, *shown_rates(m), shown(m["clean_flagged"], ".4f"), f"{m['not_visible']['flagged']}/{m['not_visible']['labels']}"]
        for name, m in methods.items()
    ]
    headers = ["method", "precision", "recall", "F1", "flagged on clean", "not-visible labels flagged"]
    out.print(fitted_table(out, "mistakes (overall)", headers, rows, numeric=range(1, 6)))
    for name in (name for name in methods if name not in METHODS):
        say(f"{name}: a reference, not a method: the precondition check on the task's true orders (it is told them)")
    out.print(fitted_table(out, "per kind", list(KIND_HEADERS), kind_rows(methods), numeric=range(2, 7)))
    delay = methods["progress-aware"]["missing_delay"]
    if delay["found"]:
        say(f"missing steps found by the detector: {delay['found']}, caught {delay['mean']} steps after their place on average (median {delay['median']})")
