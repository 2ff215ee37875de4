"""The learner-settings report: every setting of the grid on generated slips, and the one chosen."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from supportive.experiments.learner_settings.measure import (
    CLEAN_DEMONSTRATIONS,
    DEMONSTRATIONS,
    SHARE,
    SIZES,
)
from supportive.experiments.learner_settings.spread import RESAMPLES
from supportive.experiments.readings import Finding
from supportive.experiments.registry import HeadlineRow
from supportive.experiments.tables import markdown_table
from supportive.experiments.templates import render
from supportive.generate.mistakes import KINDS

__all__ = ["findings", "headline", "plots", "report", "worst_cells"]


def report(metrics: Mapping[str, Any]) -> str:
    """Markdown: per setting, precision / recall per kind and number of demonstrations, and clean reports (its
    prose: ``templates/report.md``)."""
    chosen = metrics["chosen"]
    cells = [f"{kind} {n}" for kind in KINDS for n in DEMONSTRATIONS]
    return render(
        __package__,
        "report.md",
        sizes=f"{SIZES[0]}–{SIZES[1]}",
        share=f"{SHARE:.0%}",
        clean_demonstrations=f"{CLEAN_DEMONSTRATIONS[0]}–{CLEAN_DEMONSTRATIONS[1]}",
        grid=_grid(metrics["settings"]),
        chosen=chosen or "none qualifies",
        table=markdown_table(
            ["setting", *cells, "clean", "clean, habits", "worst F1"],
            [
                [
                    f"**{name}**" if name == chosen else name,
                    *(f"{row['kinds'][c]['precision']:.2f} / {row['kinds'][c]['recall']:.2f}" for c in cells),
                    f"{row['clean_tasks_flagged']}/{row['clean_tasks']} ({row['clean_flagged']:.4%})",
                    f"{row['habits_tasks_flagged']}/{row['habits_tasks']} ({row['habits_flagged']:.4%})",
                    f"{row['worst_f1']:.3f}",
                ]
                for name, row in sorted(metrics["settings"].items(), key=lambda item: _values(item[0]))
            ],
        ),
        resamples=f"{RESAMPLES:,}",
        untold=_untold(metrics),
        spread=markdown_table(
            ["setting", "worst F1", "behind the chosen", "standard error", "best in"],
            [
                [name, f"{metrics['settings'][name]['worst_f1']:.3f}", f"{s['gap']:.4f}", f"{s['error']:.4f}", f"{s['best_share']:.1%}"]
                for name, s in sorted(metrics["spread"].items(), key=lambda item: (item[1]["gap"], _values(item[0])))
            ],
        ),
    )


def _untold(metrics: Mapping[str, Any]) -> str:
    """Which qualified settings the run does not tell from the chosen one (behind it by at most one standard
    error), as a sentence."""
    chosen = metrics["chosen"]
    if chosen is None:
        return "No setting qualifies."
    close = [name for name, s in metrics["spread"].items() if name != chosen and s["gap"] <= s["error"]]
    if not close:
        return "Every other qualified setting is behind the chosen one by more than one standard error."
    return "Behind the chosen one by at most one standard error, so not told apart from it by this run: " + "; ".join(
        f"`{name}`" for name in sorted(close, key=_values)
    ) + "."


def _parsed(name: str) -> list[tuple[str, float]]:
    """A setting's name as (parameter, value) pairs: ``slip_margin=0 slip_rate=0.1`` → ``[("slip_margin",
    0.0), ("slip_rate", 0.1)]``."""
    return [(key, float(value)) for key, value in (part.split("=") for part in name.split())]


def _values(name: str) -> tuple[float, ...]:
    """A setting's values in the order of its name: the grid's order, whatever order the metrics file keeps
    its keys in."""
    return tuple(value for _, value in _parsed(name))


def _grid(settings: Mapping[str, Any]) -> str:
    """The grid the run swept, read from its settings' names: ``slip_margin ∈ {0, 1}, …``."""
    values: dict[str, set[float]] = {}
    for name in settings:
        for key, value in _parsed(name):
            values.setdefault(key, set()).add(value)
    return ", ".join(
        k + " ∈ {" + ", ".join(f"{v:g}".replace("inf", "∞") for v in sorted(vs)) + "}" for k, vs in values.items()
    )


def plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    """No plots: the table says it."""
    return []


def headline(metrics: Mapping[str, Any]) -> list[HeadlineRow]:
    """The chosen setting and its worst F1."""
    chosen = metrics["chosen"]
    if chosen is None:
        return [("slip settings", "none qualifies", "–")]
    row = metrics["settings"][chosen]
    return [("slip settings chosen", chosen, f"worst F1 {row['worst_f1']:.3f}, {_clean(row)}")]


def _clean(row: Mapping[str, Any]) -> str:
    """How many clean tasks a setting reported a slip in, by people without habits and with them."""
    return (
        f"a slip in {row['clean_tasks_flagged']}/{row['clean_tasks']} clean tasks"
        f" ({row['habits_tasks_flagged']}/{row['habits_tasks']} by people with habits,"
        f" {row['habits_flagged']:.2%} of their steps)"
    )


def findings(metrics: Mapping[str, Any]) -> list[Finding]:
    """One row: the chosen setting, its worst precision and recall where the demonstrations are drawn uniformly
    (issue #23's case) and where people have habits, its clean reports, and how sure the choice is (how often
    it is best when the tasks are resampled, how many settings are within one standard error of it)."""
    chosen = metrics["chosen"]
    if chosen is None:
        return [Finding("slip search defaults on generated tasks", "– (not in the thesis)", (("", "none"),), "no setting qualifies")]
    row = metrics["settings"][chosen]
    worst = {people: worst_cells(cells) for people, cells in row["kinds_by_people"].items()}
    precision, recall = worst["uniform"]
    spread = metrics["spread"]
    close = sum(1 for name, s in spread.items() if name != chosen and s["gap"] <= s["error"])
    value = (
        f"{chosen}: worst P {precision:.2f}, worst R {recall:.2f} (with habits {worst['habits'][0]:.2f}, "
        f"{worst['habits'][1]:.2f}), {_clean(row)}; best in {spread[chosen]['best_share']:.0%} of "
        f"{RESAMPLES:,} resamples of the tasks, {close} other setting{'' if close == 1 else 's'} within one "
        "standard error"
    )
    verdict = "meets P ≥ 0.9, R ≥ 0.7" if precision >= 0.9 and recall >= 0.7 else "below P ≥ 0.9 or R ≥ 0.7"
    return [Finding("slip search defaults on generated tasks (issue #23)", "– (not in the thesis)", (("", value),), verdict)]


def worst_cells(cells: Mapping[str, Mapping[str, Any]]) -> tuple[float, float]:
    """The lowest precision and the lowest recall over the cells where mistakes were put in."""
    shown = [c for c in cells.values() if c["mistakes"]]
    return min((c["precision"] for c in shown), default=1.0), min((c["recall"] for c in shown), default=1.0)
