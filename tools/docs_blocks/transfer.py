"""transfer: docs/results/transfer.json."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from .common import RESULTS, Block, read_json
from .prose import minus, span, words
from .reports import report_table
from .runs import digest

_TR = "docs/results/transfer.json (supportive reproduce transfer)"


def _pair(metrics: Mapping[str, Any], first: str, second: str) -> dict[str, Any]:
    return next(p for p in metrics["pairs"] if p["first"] == first and p["second"] == second)


def transfer_beside() -> str:
    """docs/experiments.md: the transfer section's verdict, from the paired comparisons."""
    metrics = read_json(RESULTS / "transfer.json")
    default, other = metrics["readings"][:2]
    conditions = metrics["conditions"]
    macros = f"cchtn:{default}"
    versus = {base: _pair(metrics, macros, base) for base in ("q", "none")}
    faster = all(p["difference"]["high"] < 0 for p in versus.values())
    saved = [-p["difference"]["mean"] for p in versus.values()]
    fewer_steps = conditions[macros]["steps"] < conditions["none"]["steps"]
    wins = [p["wins"] for p in versus.values()]
    losses = [p["losses"] for p in versus.values()]
    trials = versus["q"]["trials"]
    fixed = {base: _pair(metrics, f"cchtn:{other}", base) for base in ("q", "none")}
    level = all(p["difference"]["low"] < 0 < p["difference"]["high"] for p in fixed.values())
    every = all(p["wins"] == p["trials"] for p in versus.values())
    return (
        f"**Beside the thesis: {'reproduced' if every else 'partly reproduced' if faster else 'not reproduced'}.** With "
        f"macros that perform any order of their clique, CC-HTN transfer "
        + (
            f"is faster than both exploring from scratch and flat Q-function transfer *on average* "
            f"({span(saved)} fewer episodes, the paired 95% CIs below zero)"
            if faster
            else "is not faster than both exploring from scratch and flat Q-function transfer on average (a paired 95% CI "
            "reaches zero)"
        )
        + (", with fewer primitive attempts than (a)" if fewer_steps else "")
        + ". It is "
        + ("" if every else "not ")
        + f'faster "in every trial": it wins {words([f"{w} of {trials}" for w in wins])} trials against (b) and '
        f"(a), and loses {words([str(v) for v in losses])}. With one fixed order per macro (`{other}`) the macros "
        + (
            f"do not help on average (wins {fixed['q']['wins']} and {fixed['none']['wins']}, losses "
            f"{fixed['q']['losses']} and {fixed['none']['losses']} against (b) and (a); both paired CIs include zero)"
            if level
            else "make a difference on average (the paired CIs above)"
        )
        + ":\n"
    )


def transfer_summary_limits() -> str:
    """docs/experiments.md (inline, the summary's list): the average saving and the wins against Q transfer."""
    metrics = read_json(RESULTS / "transfer.json")
    default = metrics["readings"][0]
    pair = _pair(metrics, f"cchtn:{default}", "q")
    where = "below" if pair["difference"]["high"] < 0 else "including"
    return (
        f"({minus(format(pair['difference']['mean'], '.0f'))} episodes, paired CI {where} 0) but not in every trial "
        f"({pair['wins']} of {pair['trials']} against Q transfer)"
    )


BLOCKS: dict[str, Block] = {
    "transfer-sha": digest("transfer.json"),
    "transfer-episodes": report_table("transfer", "transfer.json", "| condition | episodes"),
    "transfer-comparisons": report_table("transfer", "transfer.json", "| comparison |"),
    "transfer-beside": Block(_TR, transfer_beside),
    "transfer-summary-limits": Block(_TR, transfer_summary_limits, inline=True),
    "transfer-macros": Block(
        _TR,
        lambda: f"{read_json(RESULTS / 'transfer.json')['conditions']['cchtn:any-order']['macros']:g}",
        inline=True,
    ),
}
