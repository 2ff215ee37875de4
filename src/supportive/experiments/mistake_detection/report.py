"""The mistake-detection report: the threshold chosen on generated tasks, then CaptainCook4D beside the two
baselines, with a precision-recall plot."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from supportive.evaluation.mistakes import DETECTOR, KIND_HEADERS, kind_rows
from supportive.experiments.mistake_detection.measure import KINDS, POSITIVES, SIZES, TEST, TRAIN
from supportive.experiments.plotting import new_figure, save_png
from supportive.experiments.readings import Finding
from supportive.experiments.registry import HeadlineRow
from supportive.experiments.tables import markdown_table
from supportive.experiments.templates import render, section

__all__ = ["findings", "headline", "plots", "report"]


def report(metrics: Mapping[str, Any]) -> str:
    """Markdown: generated tasks per threshold, the choice, CaptainCook4D per method and kind (the prose:
    ``templates/report.md``, ``captaincook.md``)."""
    chosen = metrics["chosen"]
    cc = metrics["captaincook"]
    return render(
        __package__,
        "report.md",
        sizes=f"{SIZES[0]}–{SIZES[1]}",
        train=TRAIN,
        test=TEST,
        chosen=chosen,
        generated_table=markdown_table(
            ["threshold", "false alarms (clean steps)", *(f"recall: {k}" for k in KINDS), "skip caught after (steps)"],
            [
                [
                    f"**{t}**" if chosen is not None and float(t) == chosen else t,
                    f"{row['false_alarms']:.4f}",
                    *(f"{row['recall'][k]:.3f}" for k in KINDS),
                    "–" if row["skip_delay"] is None else f"{row['skip_delay']:.2f}",
                ]
                for t, row in metrics["generated"].items()
            ],
        ),
        captaincook=_captaincook(cc) if cc else "",
    )


def _captaincook(cc: Mapping[str, Any]) -> str:
    """The CaptainCook4D part: every method's scores, per kind, and how late missing steps are caught."""
    delay = cc["methods"][DETECTOR]["missing_delay"]
    return section(
        __package__,
        "captaincook.md",
        recipes=cc["recipes"],
        held_out=cc["held_out"],
        positives=" and ".join(POSITIVES),
        threshold=cc["threshold"],
        methods_table=markdown_table(
            ["method", "precision", "recall", "F1", "flagged on error-free recordings", "not-visible labels flagged"],
            [
                [
                    name,
                    f"{m['precision']:.3f}",
                    f"{m['recall']:.3f}",
                    f"**{m['f1']:.3f}**",
                    f"{m['clean_flagged']:.4f}",
                    f"{m['not_visible']['flagged']}/{m['not_visible']['labels']}",
                ]
                for name, m in cc["methods"].items()
            ],
        ),
        kinds_table=markdown_table(list(KIND_HEADERS), kind_rows(cc["methods"])),
        found=delay["found"],
        mean=delay["mean"],
    )


def plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    """``precision-recall.png``: the detector's curve over the thresholds on CaptainCook4D, the baselines' points."""
    cc = metrics["captaincook"]
    if not cc:
        return []
    figure = new_figure(5.5, 4.5)
    axes = figure.add_subplot(1, 1, 1)
    curve = sorted(cc["curve"].items(), key=lambda kv: float(kv[0]))
    axes.plot([m["recall"] for _, m in curve], [m["precision"] for _, m in curve], marker="o", label=DETECTOR)
    for threshold, m in curve:
        axes.annotate(threshold, (m["recall"], m["precision"]), fontsize=7, xytext=(3, 3), textcoords="offset points")
    for name, m in cc["methods"].items():
        if name != DETECTOR:
            axes.plot([m["recall"]], [m["precision"]], marker="s", linestyle="none", label=name)
    axes.set_xlim(0, 1)
    axes.set_ylim(0, 1)
    axes.set_xlabel("recall (order errors and missing steps)")
    axes.set_ylabel("precision")
    axes.set_title("CaptainCook4D: online mistake detection", fontsize=9)
    axes.legend(fontsize=7)
    return [save_png(figure, directory / "precision-recall.png")]


def headline(metrics: Mapping[str, Any]) -> list[HeadlineRow]:
    """The chosen threshold; CaptainCook4D F1 of the detector and the baselines."""
    rows: list[HeadlineRow] = [("threshold chosen on generated tasks", str(metrics["chosen"]), "–")]
    for name, m in metrics["captaincook"].get("methods", {}).items():
        rows.append((f"CaptainCook4D mistake F1, {name}", f"{m['f1']:.3f}", "–"))
    return rows


def findings(metrics: Mapping[str, Any]) -> list[Finding]:
    """Generated recall and false alarms at the chosen threshold; CaptainCook4D F1 against the baselines."""
    rows = []
    chosen = metrics["chosen"]
    if chosen is not None:
        row = metrics["generated"][str(chosen)]
        rows.append(
            Finding(
                "generated tasks: worst recall over kinds / false alarms on clean steps",
                "– (not in the thesis)",
                (("", f"{row['worst_recall']:.3f} / {row['false_alarms']:.4f}"),),
                "meets recall ≥ 0.9 at ≤ 1 %" if row["worst_recall"] >= 0.9 and row["false_alarms"] <= 0.01 else "below the asked",
            )
        )
    cc = metrics["captaincook"]
    if cc:
        ours = cc["methods"][DETECTOR]
        baselines = [m["f1"] for name, m in cc["methods"].items() if name != DETECTOR]
        rows.append(
            Finding(
                "CaptainCook4D mistake F1 (order + missing), detector / best baseline (precision)",
                "– (not in the thesis)",
                (("", f"{ours['f1']:.3f} / {max(baselines):.3f} ({ours['precision']:.3f})"),),
                "ahead by ≥ 0.05 at precision ≥ 0.6"
                if ours["f1"] >= max(baselines) + 0.05 and ours["precision"] >= 0.6
                else "not ahead by 0.05 at precision ≥ 0.6",
            )
        )
    return rows
