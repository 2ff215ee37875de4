"""The generalisation report: the default learner (the reading held-out likelihood chooses) and the general
reading beside the strict one."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from supportive.experiments.captaincook.recipes import FEW_SHOT
from supportive.experiments.generalisation.measure import DEMONSTRATIONS, LEARNERS, SIZES, SLIP_CLEAN, SLIPPED
from supportive.experiments.readings import Finding
from supportive.experiments.registry import HeadlineRow
from supportive.experiments.tables import markdown_table
from supportive.learning.graph_edges import PEERS

__all__ = ["findings", "headline", "plots", "report"]

DEFAULT, STRICT = LEARNERS[0], LEARNERS[-1]
"""The learners the headline and findings compare: the default (``auto``) and the thesis's ``strict``."""


def report(metrics: Mapping[str, Any]) -> str:
    """Markdown tables: generated tasks per profile; CaptainCook4D admission and precedence scores."""
    lines = [
        "# Generalisation: the default learner and the general reading beside the strict one",
        "",
        f"Generated chain/clique tasks of {SIZES[0]}–{SIZES[1]} actions, {DEMONSTRATIONS} sampled demonstrations each:",
        "recall is the share of the valid orderings the learned hierarchy admits, precision the share of its",
        "orderings that are valid (issue #13 asks recall ≥ 0.6 with precision ≥ 0.95).",
        "",
        *markdown_table(
            ["profile", "learner", "tasks", "recall", "precision", "complete"],
            [
                [profile, mode, str(m["tasks"]), f"{m['recall']:.3f}", f"{m['precision']:.3f}", str(m["complete"])]
                for profile, by_mode in metrics["synthetic"].items()
                for mode, m in by_mode.items()
            ],
        ),
    ]
    if metrics.get("slips"):
        lines += [
            "",
            f"Slips on the same tasks (general learner): {SLIP_CLEAN} sampled demonstrations, then those and {SLIPPED}",
            "more with one step moved to a random place; the last column sets nothing aside (`slips=False`). A",
            "moved step that lands inside another subtask breaks its contiguity rather than an order, which the",
            "slip search does not look for (docs/learning.md).",
            "",
            *markdown_table(
                ["profile", "clean: recall / precision", "with slips", "with slips, none set aside"],
                [
                    [profile]
                    + [f"{m[data]['recall']:.3f} / {m[data]['precision']:.3f}" for data in ("clean", "with_slips", "with_slips_none_set_aside")]
                    for profile, m in metrics["slips"].items()
                ],
            ),
        ]
    if metrics["captaincook"]:
        lines += [
            "",
            "CaptainCook4D: learned from the first half of each recipe's error-free recordings, the share of the other",
            "half admitted (issue #13 asks ≥ 0.60); learned from every error-free recording, and from every recording",
            "errors included, the precision and recall of the implied \"must come before\" pairs among the graph's steps",
            "against the published graphs (asked: with errors within 0.03 of without). Recordings with errors add",
            "performances the graph lacks (a step done twice, an off-graph step); \"P (all pairs)\" counts their orders",
            "as wrong too.",
            "",
            *markdown_table(
                [
                    "learner", "admitted", "P (error-free)", "R (error-free)", "P (with errors)", "R (with errors)",
                    "P (with errors, all pairs)",
                ],
                [
                    [
                        mode,
                        f"{m['admitted']}/{m['held_out']} ({m['admission']:.1%})",
                        f"{m['error_free_precision']:.3f}",
                        f"{m['error_free_recall']:.3f}",
                        f"{m['with_errors_precision']:.3f}",
                        f"{m['with_errors_recall']:.3f}",
                        f"{m['with_errors_all_precision']:.3f}",
                    ]
                    for mode, m in metrics["captaincook"].items()
                ],
            ),
        ]
        lines += [
            "",
            "CaptainCook4D task graphs with the protocol of *Differentiable Task Graph Learning* (Seminara et al.,",
            "NeurIPS 2024): the learned \"before\" relation transitively reduced, START and END added, its edges",
            "against the published graph's, precision / recall / F1 per recipe and their means; learned from every",
            f"error-free recording (full) and from each recipe's first {FEW_SHOT} (5-shot). Their published F1s:",
            ", ".join(f"{name} {', '.join(f'{k} {v:.3f}' for k, v in f1.items())}" for name, f1 in PEERS.items()) + ".",
            "",
            *markdown_table(
                ["learner", "full: P / R / F1", "5-shot: P / R / F1"],
                [
                    [mode]
                    + [
                        f"{m['edges'][setting]['precision']:.3f} / {m['edges'][setting]['recall']:.3f} / "
                        f"**{m['edges'][setting]['f1']:.3f}**"
                        for setting in ("full", "5-shot")
                    ]
                    for mode, m in metrics["captaincook"].items()
                ],
            ),
        ]
    return "\n".join(lines) + "\n"


def plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    """No plots: the tables say it."""
    return []


def headline(metrics: Mapping[str, Any]) -> list[HeadlineRow]:
    """Recall/precision per profile, CaptainCook admission, for the default learner (strict beside)."""
    rows: list[HeadlineRow] = []
    for profile, by_mode in metrics["synthetic"].items():
        g, s = by_mode[DEFAULT], by_mode[STRICT]
        rows.append((f"{profile}: recall / precision", f"{g['recall']:.3f} / {g['precision']:.3f}", f"strict {s['recall']:.3f} / {s['precision']:.3f}"))
    if metrics["captaincook"]:
        g, s = metrics["captaincook"][DEFAULT], metrics["captaincook"][STRICT]
        rows.append(("CaptainCook held-out admitted", f"{g['admission']:.3f}", f"strict {s['admission']:.3f}"))
    return rows


def findings(metrics: Mapping[str, Any]) -> list[Finding]:
    """Recall / precision of orderings per profile, CaptainCook held-out admission and task-graph F1, the default
    learner vs strict."""
    rows = []
    for profile, by_mode in metrics["synthetic"].items():
        g, s = by_mode[DEFAULT], by_mode[STRICT]
        rows.append(
            Finding(
                f"{profile} tasks, 4 demonstrations: recall / precision of orderings, default · strict",
                "– (not in the thesis)",
                (("", f"{g['recall']:.3f} / {g['precision']:.3f} · {s['recall']:.3f} / {s['precision']:.3f}"),),
                "the default generalises further" if g["recall"] > s["recall"] else "no gain",
            )
        )
    if metrics["captaincook"]:
        g, s = metrics["captaincook"][DEFAULT], metrics["captaincook"][STRICT]
        rows.append(
            Finding(
                "CaptainCook4D, learned from half the recordings: the other half admitted, default · strict",
                "– (not in the thesis)",
                (("", f"{g['admission']:.3f} · {s['admission']:.3f}"),),
                "the default admits more" if g["admission"] > s["admission"] else "no gain",
            )
        )
        gaps = [g[f"error_free_{m}"] - g[f"with_errors_{m}"] for m in ("precision", "recall")]
        rows.append(
            Finding(
                "CaptainCook4D, precedence P / R: error-free recordings · all recordings, errors included (default)",
                "– (not in the thesis)",
                (
                    (
                        "",
                        f"{g['error_free_precision']:.3f} / {g['error_free_recall']:.3f} · "
                        f"{g['with_errors_precision']:.3f} / {g['with_errors_recall']:.3f}",
                    ),
                ),
                "errors barely change it (within 0.03)" if max(gaps) <= 0.03 else "errors cost more than 0.03",
            )
        )
        for setting in ("full", "5-shot"):
            peer = PEERS["DO (Seminara et al. 2024)"][setting]
            ours, strict = g["edges"][setting]["f1"], s["edges"][setting]["f1"]
            rows.append(
                Finding(
                    f"CaptainCook4D task-graph F1 ({setting}, DTGL protocol): default · strict",
                    f"– (DO, Seminara et al. 2024: {peer:.3f})",
                    (("", f"{ours:.3f} · {strict:.3f}"),),
                    "above DO and strict" if ours > max(peer, strict) else "not above both DO and strict",
                )
            )
    return rows
