"""Goal inference: the markdown report, the timing report and the terminal headline, this run beside the
thesis.

``report.md`` is built from ``metrics.json`` alone, so it is as deterministic as the metrics; the wall-clock
times, which the harness keeps out of the metrics, get their own ``timing.md`` (:func:`timing_markdown`,
written by :func:`~.plots.timing_report`).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from supportive.evaluation.mistakes import shown
from supportive.experiments.goal_inference.design import MEAN_DURATION, steps_for
from supportive.experiments.goal_inference.summary import LEVELS
from supportive.experiments.goal_inference.thesis import THESIS
from supportive.experiments.goal_inference.timing import TIMING_PLOT, TIMING_REPORT
from supportive.experiments.output import TIMING_FILE
from supportive.experiments.registry import HeadlineRow
from supportive.experiments.statistics import above_zero, below_zero, format_ci
from supportive.experiments.tables import markdown_table
from supportive.experiments.templates import render

__all__ = ["LABELS", "accuracy_verdict", "headline", "report", "setting_label", "timing_markdown"]

LABELS = {"flat": "flat HMM", "hierarchical": "hierarchical HMM (CC-HTN)"}
"""How the report names the two models."""


def setting_label(setting: Mapping[str, Any]) -> str:
    """``overlap 0.8, noisy (1 stray, p 0.6)``: a setting for people (stray events per moment, probability
    that an event the action produces is seen).

    >>> setting_label({"overlap": 0.8, "noise": "clean", "spurious": 0.3, "strength": 0.85})
    'overlap 0.8, clean (0.3 stray, p 0.85)'
    """
    return (
        f"overlap {setting['overlap']:.1f}, {setting['noise']} "
        f"({setting['spurious']:g} stray, p {setting['strength']:g})"
    )


def _overlaps(metrics: Mapping[str, Any]) -> list[float]:
    return sorted({s["overlap"] for s in metrics["settings"]})


def accuracy_verdict(metrics: Mapping[str, Any]) -> list[str]:
    """Per level (subgoal, subtask), one paragraph built from the numbers alone: in how many settings the
    hierarchical model is at least as accurate on average, where the paired 95% CI of the difference excludes
    zero, and whether the difference grows with overlap (what the thesis's statement leads one to expect)."""
    settings = metrics["settings"]
    accuracy = metrics["accuracy"]
    paragraphs = []
    for level in LEVELS:
        deltas = {s["key"]: accuracy[s["key"]]["difference"][level] for s in settings}
        ahead = sum(d["mean"] >= 0 for d in deltas.values())
        better = [setting_label(s) for s in settings if above_zero(deltas[s["key"]])]
        worse = [setting_label(s) for s in settings if below_zero(deltas[s["key"]])]
        by_overlap = []
        for overlap in _overlaps(metrics):
            keys = [s["key"] for s in settings if s["overlap"] == overlap]
            by_overlap.append((overlap, sum(deltas[k]["mean"] for k in keys) / len(keys)))
        grows = all(b[1] >= a[1] for a, b in itertools.pairwise(by_overlap)) and (
            by_overlap[-1][1] > by_overlap[0][1]
        )
        trend = ", ".join(f"{d:+.4f} at overlap {o:.1f}" for o, d in by_overlap)
        sentence = (
            f"**{level.capitalize()}.** The hierarchical model is at least as accurate as the flat one on "
            f"average in {ahead} of {len(settings)} settings; the paired 95% CI of the difference lies above "
            f"zero for {'; '.join(better) if better else 'no setting'} and below zero for "
            f"{'; '.join(worse) if worse else 'no setting'}. Mean difference (hierarchical − flat, averaged "
            f"over the noise levels): {trend}: "
        )
        sentence += (
            "the benefit grows with observation overlap, as the thesis's statement leads one to expect."
            if grows
            else "it does not grow steadily with observation overlap."
        )
        paragraphs.append(sentence)
    return paragraphs


def _sizes_line(metrics: Mapping[str, Any]) -> str:
    return ", ".join(f"{row['trials']} × {row['subgoals']}" for row in metrics["sizes"])


def _accuracy_table(metrics: Mapping[str, Any]) -> list[str]:
    rows = []
    for setting in metrics["settings"]:
        a = metrics["accuracy"][setting["key"]]
        cells = [setting_label(setting)]
        for level in LEVELS:
            cells += [
                format_ci(a["flat"][level]),
                format_ci(a["hierarchical"][level]),
                format_ci(a["difference"][level], signed=True),
            ]
        cells.append(f"{a['hierarchical_ahead']['subgoal']} / {a['flat_ahead']['subgoal']}")
        rows.append(cells)
    header = [
        "setting", "flat: subgoal", "hierarchical: subgoal", "Δ subgoal", "flat: subtask", "hierarchical: subtask",
        "Δ subtask", "trials hierarchical ahead / flat ahead (subgoal)",
    ]
    return markdown_table(header, rows)


def _per_size(metrics: Mapping[str, Any], cell: Callable[[Mapping[str, Any], str], str]) -> list[str]:
    """A table of one row per task size and one column per setting, each cell ``cell(size row, setting)``."""
    settings = metrics["settings"]
    rows = [
        [str(row["subgoals"]), str(row["trials"]), *(cell(row, s["key"]) for s in settings)] for row in metrics["sizes"]
    ]
    return markdown_table(["subgoals", "trials", *(setting_label(s) for s in settings)], rows)


def _size_table(metrics: Mapping[str, Any]) -> list[str]:
    def cell(row: Mapping[str, Any], key: str) -> str:
        a = row["accuracy"][key]
        return f"{a['flat']['subgoal']:.3f} / {a['hierarchical']['subgoal']:.3f}"

    return _per_size(metrics, cell)


def _progress_table(metrics: Mapping[str, Any]) -> list[str]:
    """Subgoal accuracy of the progress-aware tracker beside the hierarchical HMM, per size and setting."""

    def cell(row: Mapping[str, Any], key: str) -> str:
        a = row["accuracy"][key]
        delta = format_ci(row["progress_difference"][key], signed=True)
        return f"{a['hierarchical']['subgoal']:.3f} → {a['progress']['subgoal']:.3f} ({delta})"

    return _per_size(metrics, cell)


def _work_table(metrics: Mapping[str, Any]) -> list[str]:
    rows = []
    for row in metrics["sizes"]:
        nz, entries = row["transition_nonzeros"], row["operator_entries"]
        rows.append(
            [
                str(row["subgoals"]),
                str(row["trials"]),
                f"{row['subtasks']:.1f}",
                f"{row['depth']:.2f}",
                f"{row['steps']:.0f}",
                f"{nz['flat']:.0f} / {nz['hierarchical']:.0f}",
                f"{entries['flat']:.0f} / {entries['hierarchical']:.0f}",
                f"{entries['flat'] / entries['hierarchical']:.1f}",
            ]
        )
    header = [
        "subgoals", "trials", "subtasks", "depth", "steps per stream", "non-zero transitions flat / hierarchical",
        "entries per update flat / hierarchical", "flat ÷ hierarchical",
    ]
    return markdown_table(header, rows)


def report(metrics: Mapping[str, Any]) -> str:
    """The markdown report of a goal-inference run (deterministic: from the metrics alone; its prose:
    ``templates/report.md``)."""
    thesis = metrics["thesis"]
    design = metrics["design"]
    return render(
        __package__,
        "report.md",
        metrics,
        sizes=_sizes_line(metrics),
        thesis_tasks=thesis["tasks"],
        thesis_subgoals=f"{thesis['subgoals']['min']}–{thesis['subgoals']['max']}",
        mean_duration=f"{MEAN_DURATION:g}",
        events_per_action=design["events_per_action"],
        steps=f"{steps_for(200):,} steps up to 200 subgoals, {steps_for(500):,} up to 500 and {steps_for(1000):,} beyond",
        timed_setting=design["timed_setting"],
        figure_2_4=thesis["figure_2_4"],
        computational_claim=thesis["computational_claim"],
        accuracy_statement=thesis["accuracy_statement"],
        cpu=thesis["cpu"],
        accuracy_table=_accuracy_table(metrics),
        verdicts=[f"* {paragraph}" for paragraph in accuracy_verdict(metrics)],
        size_table=_size_table(metrics),
        progress_table=_progress_table(metrics),
        work_table=_work_table(metrics),
        timing_report=TIMING_REPORT,
        timing_file=TIMING_FILE,
        timing_plot=TIMING_PLOT,
    )


def _rows_by_size(document: Mapping[str, Any]) -> dict[int, Sequence[Mapping[str, Any]]]:
    trials: dict[int, list[Mapping[str, Any]]] = {}
    for trial in document["trials"]:
        trials.setdefault(int(trial["subgoals"]), []).append(trial)
    return dict(trials)


def _range(times: Mapping[str, Any]) -> str:
    return f"{times['median_us']:.1f} ({times['least_median_us']:.1f}–{times['greatest_median_us']:.1f})"


def _same_cost(sizes: Sequence[Mapping[str, Any]]) -> str:
    same = [str(row["subgoals"]) for row in sizes if row["ratio"] is not None and 0.9 <= row["ratio"] <= 1.1]
    if not same:
        return ""
    return f" Both cost about the same (flat ÷ hierarchical within 0.9–1.1) at {', '.join(same)} subgoals."


def timing_markdown(document: Mapping[str, Any]) -> str:
    """``timing.md``: the per-size per-update times of a run (its timing ``document``, see
    :func:`~.timing.timing_summary`) beside Figure 2.4 (its prose: ``templates/timing.md``). Not
    deterministic."""
    bound_us = THESIS["update_seconds_bound"] * 1e6
    sizes, trials = document["sizes"], document["trials"]
    worst = max(sizes, key=lambda row: row["hierarchical"]["median_us"])
    under = sum(t["hierarchical"]["max_us"] < bound_us for t in trials)
    largest, smallest = sizes[-1], sizes[0]
    grows = (largest["ratio"] or 0) > (smallest["ratio"] or 0) and (largest["ratio"] or 0) > 1
    return render(
        __package__,
        "timing.md",
        trials=len(trials),
        cpus=", ".join(document["cpus"]),
        python=document["python"],
        settings=" / ".join(sorted({str(t.get("setting")) for t in trials})),
        table=_timing_table(document),
        figure_2_4=THESIS["figure_2_4"],
        worst_subgoals=worst["subgoals"],
        worst_us=f"{worst['hierarchical']['median_us']:.1f}",
        margin=f"{bound_us / worst['hierarchical']['median_us']:,.0f}",
        slowest_us=f"{max(t['hierarchical']['max_us'] for t in trials):.1f}",
        slowest_flat_us=f"{max(t['flat']['max_us'] for t in trials):.1f}",
        under=under,
        holds="the claim holds, for every trial." if under == len(trials) else "not in every trial.",
        smallest_ratio=_ratio(smallest),
        smallest=smallest["subgoals"],
        largest_ratio=_ratio(largest),
        largest=largest["subgoals"],
        grows=(
            "The hierarchical filter's advantage grows with task size."
            if grows
            else "No advantage that grows with task size in this run."
        ),
        same_cost=_same_cost(sizes),
    )


def _ratio(row: Mapping[str, Any]) -> str:
    return shown(row["ratio"], ".2f")


def _timing_table(document: Mapping[str, Any]) -> list[str]:
    """One row per task size: median and mean update times of both models."""
    by_size = _rows_by_size(document)
    rows = []
    for row in document["sizes"]:
        f, h = row["flat"], row["hierarchical"]
        steps = sum(t["steps"] for t in by_size[row["subgoals"]]) / row["trials"]
        rows.append(
            [
                str(row["subgoals"]),
                str(row["trials"]),
                f"{steps:.0f}",
                _range(f),
                _range(h),
                _ratio(row),
                f"{f['mean_us']:.1f}",
                f"{h['mean_us']:.1f}",
                f"{1e6 / h['median_us']:,.0f}",
            ]
        )
    header = [
        "subgoals", "trials", "steps", "flat: median µs (range)", "hierarchical: median µs (range)",
        "flat ÷ hierarchical", "flat: mean µs", "hierarchical: mean µs", "hierarchical updates per second",
    ]
    return markdown_table(header, rows)


def headline(metrics: Mapping[str, Any]) -> list[HeadlineRow]:
    """A few (quantity, this run, the thesis) rows for the terminal (from the metrics alone, so the per-update
    times are only pointed to)."""
    thesis = metrics["thesis"]
    hardest = metrics["settings"][-1]
    accuracy = metrics["accuracy"][hardest["key"]]
    largest = metrics["sizes"][-1]
    no_numbers = "no numbers; benefit depends on overlap"
    rows: list[HeadlineRow] = [
        (
            "trials, subgoals",
            f"{metrics['trials']}, {metrics['sizes'][0]['subgoals']}–{largest['subgoals']}",
            f"{thesis['tasks']}, {thesis['subgoals']['min']}–{thesis['subgoals']['max']}",
        )
    ]
    for level in LEVELS:
        rows.append(
            (
                f"{level} accuracy flat / hierarchical, {setting_label(hardest)}",
                f"{accuracy['flat'][level]['mean']:.3f} / {accuracy['hierarchical'][level]['mean']:.3f}",
                no_numbers,
            )
        )
    entries = largest["operator_entries"]
    rows.append(
        (
            f"entries per update flat / hierarchical, {largest['subgoals']} subgoals",
            f"{entries['flat']:,.0f} / {entries['hierarchical']:,.0f}",
            "–",
        )
    )
    rows.append(
        (
            "time per update flat / hierarchical (median), by size",
            f"see {TIMING_REPORT}",
            "CC-HTN under 1 s (1 Hz) in most cases; i7-3930K, 1 thread",
        )
    )
    return rows
