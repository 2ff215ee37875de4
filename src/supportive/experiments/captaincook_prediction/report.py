"""The captaincook-prediction report: one table of every model's scores, each recipe's admission."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from supportive.experiments.captaincook_prediction.measure import MODELS
from supportive.experiments.readings import Finding
from supportive.experiments.registry import HeadlineRow
from supportive.experiments.tables import markdown_table

__all__ = ["findings", "headline", "plots", "report"]


def report(metrics: Mapping[str, Any]) -> str:
    """Markdown: what was measured, the models side by side, the verdict, per-recipe admission."""
    models = metrics["models"]
    rows = [
        [
            name, f"{m['top1']:.3f}", f"{m['top3']:.3f}", f"{m['zero']:.3f}", f"{m['log2']:.3f}", f"{m['done_top1']:.3f}",
            f"{m['ece']:.3f}",
        ]
        for name, m in models.items()
    ]
    ours, masked = models[MODELS[0]], models["masked bigram"]
    admission = metrics["admission"]
    lines = [
        "# CaptainCook4D: next-step prediction (leave one out)",
        "",
        "Every recording of every recipe, errors included, is held out in turn; the hierarchy and its frequencies",
        "are learned from the others (the default learner), and at each step of the held-out recording (and after its",
        "last, where the truth is `<end>`) each model gives the probability of what is done next. Not in the thesis.",
        "",
        *markdown_table(
            ["model", "top-1", "top-3", "P = 0", "log2 P per step", "top-1 already done", "calibration error"], rows
        ),
        "",
        "`log2 P per step` is the mean over the steps a model gave a probability above 0 (the share it gave 0 is",
        "`P = 0`); `top-1 already done` counts a top-1 action already done as often as any training recording does it;",
        "`calibration error` is the expected calibration error of the top-1 probability (ten equal bins: the mean",
        "over steps of |share right − mean probability| of their bin). The progress-aware predictor mixes in an",
        "add-one bigram and smooths its choices with the weight and pseudo-counts that cross-validation over the",
        "training recordings picks (docs/inference.md).",
        "",
        "Reliability of the progress-aware predictor's top-1 probability (`reliability.png` draws every model's):",
        "",
        *markdown_table(
            ["top-1 probability", "steps", "mean probability", "right"],
            [
                [f"{r['from']:.1f}–{r['to']:.1f}", str(r["predictions"]), f"{r['confidence']:.3f}", f"{r['accuracy']:.3f}"]
                for r in ours["reliability"]
            ],
        ),
        "",
        f"* The progress-aware predictor's top-1 is {ours['top1'] - masked['top1']:+.3f} against the masked bigram's,",
        f"  with probability 0 on {ours['zero']:.1%} of steps (masked bigram {masked['zero']:.1%}).",
        f"* The hierarchy learned from the other recordings admits {admission['admitted']} of {admission['held_out']}",
        f"  held-out recordings ({admission['share']:.1%}); recordings with errors are often off-script by design.",
        "",
        "## Per recipe",
        "",
        *markdown_table(
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
    ]
    return "\n".join(lines) + "\n"


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
