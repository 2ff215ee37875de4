"""The captaincook-prediction report: one table of every model's scores, each recipe's admission."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from supportive.experiments.captaincook_prediction.measure import MODELS
from supportive.experiments.readings import Finding
from supportive.experiments.registry import HeadlineRow
from supportive.experiments.tables import markdown_table
from supportive.experiments.templates import render

__all__ = ["findings", "headline", "plots", "report"]


def report(metrics: Mapping[str, Any]) -> str:
    """Markdown: what was measured, the models side by side, the verdict, per-recipe admission (its prose:
    ``templates/report.md``)."""
    models = metrics["models"]
    ours, masked = models[MODELS[0]], models["masked bigram"]
    admission = metrics["admission"]
    keys = ("top1", "top3", "zero", "log2", "done_top1", "ece")
    return render(
        __package__,
        "report.md",
        models_table=markdown_table(
            ["model", "top-1", "top-3", "P = 0", "log2 P per step", "top-1 already done", "calibration error"],
            [[name, *(f"{m[k]:.3f}" for k in keys)] for name, m in models.items()],
        ),
        reliability_table=markdown_table(
            ["top-1 probability", "steps", "mean probability", "right"],
            [
                [f"{r['from']:.1f}–{r['to']:.1f}", str(r["predictions"]), f"{r['confidence']:.3f}", f"{r['accuracy']:.3f}"]
                for r in ours["reliability"]
            ],
        ),
        top1_gain=f"{ours['top1'] - masked['top1']:+.3f}",
        zero=f"{ours['zero']:.1%}",
        masked_zero=f"{masked['zero']:.1%}",
        admitted=admission["admitted"],
        held_out=admission["held_out"],
        share=f"{admission['share']:.1%}",
        recipes_table=markdown_table(
            ["recipe", "held out", "admitted", "top-1 (ours)", "top-1 (masked bigram)"],
            [
                [
                    r["task"],
                    str(r["held_out"]),
                    str(r["admitted"]),
                    f"{r['prediction'][MODELS[0]]['top1']:.3f}",
                    f"{r['prediction']['masked bigram']['top1']:.3f}",
                ]
                for r in metrics["recipes"]
            ],
        ),
    )


def plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    """``reliability.png``: every model's reliability diagram."""
    from supportive.render.reliability import write_reliability

    tables = {name: m["reliability"] for name, m in metrics["models"].items()}
    return [write_reliability(tables, directory / "reliability.png", "CaptainCook4D: next-step reliability")]


def headline(metrics: Mapping[str, Any]) -> list[HeadlineRow]:
    """Top-1 of each model, and held-out admission."""
    rows: list[HeadlineRow] = [
        (f"next-step top-1, {name}", f"{m['top1']:.3f}", "–") for name, m in metrics["models"].items()
    ]
    rows.append(("held-out recordings admitted", f"{metrics['admission']['share']:.3f}", "–"))
    return rows


def findings(metrics: Mapping[str, Any]) -> list[Finding]:
    """Next-step top-1, progress-aware vs the strongest baseline; the share of steps given probability 0."""
    models = metrics["models"]
    ours, masked, bigram = models[MODELS[0]], models["masked bigram"], models["bigram"]
    return [
        Finding(
            "next-step top-1, progress-aware / masked bigram (P = 0)",
            "– (not in the thesis)",
            (("", f"{ours['top1']:.3f} ({ours['zero']:.1%}) / {masked['top1']:.3f} ({masked['zero']:.1%})"),),
            "progress-aware ahead" if ours["top1"] > masked["top1"] else "not ahead of the masked bigram",
        ),
        Finding(
            "next-step log2 P per step, progress-aware / add-one bigram (calibration error)",
            "– (not in the thesis)",
            (("", f"{ours['log2']:.3f} ({ours['ece']:.3f}) / {bigram['log2']:.3f} ({bigram['ece']:.3f})"),),
            "at least the bigram's" if ours["log2"] >= bigram["log2"] else "below the bigram's",
        ),
    ]
