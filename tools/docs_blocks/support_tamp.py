"""support-tamp: docs/results/support-tamp.json."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from .common import RESULTS, Block, filled, read_json
from .prose import of, pct, span, words
from .runs import digest, run_time

_ST = "docs/results/support-tamp.json (supportive reproduce support-tamp)"


def _st() -> dict[str, Any]:
    metrics: dict[str, Any] = read_json(RESULTS / "support-tamp.json")
    return metrics


def _st_pairings() -> list[str]:
    from supportive.experiments.support_tamp.measure import PAIRINGS

    return list(PAIRINGS)


def support_tamp_makespans() -> str:
    """docs/support.md: makespans alone and supported, both readings of the gain, per scenario and pairing."""
    metrics = _st()
    readings = list(metrics["readings"])
    default, other = readings[0], readings[1]
    thesis = metrics["thesis"]["makespan_gain_percent"]
    rows = [
        f"| scenario | pairing | alone (s) | supported, `{default}` (s) | reduction / speed-up | `{other}` (s) | "
        "reduction / speed-up | thesis | ceiling: reduction / speed-up |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for scenario in ("unpredictable", "heuristic"):
        for pairing in _st_pairings():
            entry = metrics["scenarios"][scenario][pairing]
            main, second = entry["supported"][default], entry["supported"][other]
            if scenario == "unpredictable":
                extra = "(same run) |"
            else:
                extra = (
                    f"{second['makespan']['mean']:.1f} | {pct(second['gain']['reduction'])} / "
                    f"{pct(second['gain']['speed-up'])}"
                )
            rows.append(
                f"| {scenario} | {pairing} | {entry['alone']['makespan']['mean']:.1f} | {main['makespan']['mean']:.1f} | "
                f"**{pct(main['gain']['reduction'])}** / {pct(main['gain']['speed-up'])} | {extra} | "
                f"{thesis[pairing]:g} % | {pct(entry['ceiling']['reduction'])} / {pct(entry['ceiling']['speed-up'])} |"
            )
    return "\n".join(rows) + "\n"


def _nodes(metrics: Mapping[str, Any], pairing: str, reading: str | None) -> tuple[int, int]:
    """The greedy lead's search nodes, median and mean, alone (``reading`` None) or supported, rounded as shown."""
    entry = metrics["scenarios"]["heuristic"][pairing]
    side = entry["alone"] if reading is None else entry["supported"][reading]
    return round(side["lead_nodes_median"]), round(side["lead_nodes"]["mean"])


def support_tamp_search() -> str:
    """docs/support.md: Figure 3.6, the greedy lead's search nodes alone and under each objective."""
    metrics = _st()
    readings = list(metrics["readings"])
    rows = [
        "| the greedy lead's search nodes, median (mean) | alone | "
        + " | ".join(f"`{r}`" for r in readings)
        + " |",
        "|---|---:|" + "---:|" * len(readings),
    ]
    for pairing in _st_pairings():
        alone = _nodes(metrics, pairing, None)
        cells = []
        for r in readings:
            median, average = _nodes(metrics, pairing, r)
            best = median < alone[0] and median == min(_nodes(metrics, pairing, s)[0] for s in readings)
            cells.append(f"**{median:.0f}** ({average:.0f})" if best else f"{median:.0f} ({average:.0f})")
        rows.append(f"| {pairing} | {alone[0]:.0f} ({alone[1]:.0f}) | " + " | ".join(cells) + " |")
    return "\n".join(rows) + "\n"


def support_tamp_gaps() -> str:
    """docs/support.md: the share of the gap to a fast lead alone that a fast helper closes, and the plan-following
    lead's effort."""
    metrics = _st()
    default, other = list(metrics["readings"])[:2]
    gap = {
        s: metrics["scenarios"][s]["slow lead helped vs fast lead alone"]
        for s in ("unpredictable", "heuristic")
    }
    plain = metrics["scenarios"]["unpredictable"]
    efforts = [plain[p]["alone"]["lead_nodes"]["mean"] for p in _st_pairings()] + [
        plain[p]["supported"][default]["lead_nodes"]["mean"] for p in _st_pairings()
    ]
    same = max(efforts) - min(efforts) < 0.5
    return (
        f"(95 % confidence intervals, tables faster / slower and the gap to a fast lead alone are in `report.md`: the "
        f"slow lead with a fast helper closes {gap['unpredictable'][default]['gap_closed_percent']:.1f} % (unpredictable) "
        f"and {gap['heuristic'][default]['gap_closed_percent']:.1f} % (heuristic; "
        f"{gap['heuristic'][other]['gap_closed_percent']:.1f} % {other}) of the gap to a fast lead alone. "
        f"The unpredictable lead's effort is the plan steps it estimates, "
        + (
            f"{efforts[0]:.0f} on average with and without support: it never had to choose again.)\n"
            if same
            else f"{span(efforts, 0)} on average across the pairings, alone and supported.)\n"
        )
    )


def _gains(metrics: Mapping[str, Any], scenario: str, reading: str) -> dict[str, dict[str, float]]:
    return {p: metrics["scenarios"][scenario][p]["supported"][reading]["gain"] for p in _st_pairings()}


def support_tamp_reproduces() -> str:
    """docs/support.md: what reproduces — where support shortens the makespan, the order of the gains, the
    search-aware objective's search nodes."""
    metrics = _st()
    default, other = list(metrics["readings"])[:2]
    pairings = _st_pairings()
    lowered = {
        s: [p for p, g in _gains(metrics, s, default).items() if g["reduction"] > 0]
        for s in ("unpredictable", "heuristic")
    }
    total = sum(len(v) for v in lowered.values())
    if total == 2 * len(pairings):
        where = "in every pairing"
    else:
        missed = [f"{p} ({s})" for s in lowered for p in pairings if p not in lowered[s]]
        where = (
            f"in every pairing but {words(missed)}"
            if len(missed) < 3
            else f"in {total} of {2 * len(pairings)} pairings"
        )
    ordered = all(
        g["slow lead, fast support"]["reduction"]
        > g["slow lead, slow support"]["reduction"]
        > g["fast lead, slow support"]["reduction"]
        and g["fast lead, fast support"]["reduction"] > g["fast lead, slow support"]["reduction"]
        for g in (_gains(metrics, s, default) for s in ("unpredictable", "heuristic"))
    )
    equal = [
        abs(g["fast lead, fast support"]["reduction"] - g["slow lead, slow support"]["reduction"])
        for g in (_gains(metrics, s, default) for s in ("unpredictable", "heuristic"))
    ]
    medians = {r: [_nodes(metrics, p, r)[0] for p in pairings] for r in (None, default, other)}
    alone = medians[None][0]
    aware_falls = [p for p, m in zip(pairings, medians[other], strict=True) if m < alone]
    duration_rises = [p for p, m in zip(pairings, medians[default], strict=True) if m > alone]
    slow_fast = (
        _gains(metrics, "heuristic", other)["slow lead, fast support"]["reduction"],
        _gains(metrics, "heuristic", default)["slow lead, fast support"]["reduction"],
    )
    others = [
        abs(
            _gains(metrics, "heuristic", other)[p]["reduction"]
            - _gains(metrics, "heuristic", default)[p]["reduction"]
        )
        for p in pairings[1:]
    ]
    text = (
        f"**What reproduces.** Support lowers the mean makespan {where}"
        + (
            "; the gain grows with the helper's speed relative to the lead's (faster helper > equal > slower), as in the thesis"
            if ordered
            else "; the gain does not always grow with the helper's speed relative to the lead's (the table above), as in the thesis it does"
        )
        + (
            "; a slow lead with a fast helper closes part of the gap to a fast lead alone. "
            if all(
                metrics["scenarios"][s]["slow lead helped vs fast lead alone"][default]["gap_closed_percent"]
                > 0
                for s in ("unpredictable", "heuristic")
            )
            else "; a slow lead with a fast helper does not always close part of the gap to a fast lead alone. "
        )
        + (
            f"The equal-speed pairings (fast/fast, slow/slow) give about the same gain (within {max(equal):.1f} points), "
            "as they should: the same motions at a third of the speed. "
            if max(equal) <= 1.0
            else f"The equal-speed pairings (fast/fast, slow/slow) differ by up to {max(equal):.1f} points, though they "
            "are the same motions at a third of the speed. "
        )
    )
    falls = [f"{m:.0f}" for p, m in zip(pairings, medians[other], strict=True) if p in aware_falls]
    text += (
        f"A support agent that also minimises the greedy lead's next search cuts its median search to "
        f"{' / '.join(falls)} nodes from {alone:.0f} in {of(len(aware_falls), len(pairings))} pairings "
        f'(Figure 3.6\'s "the search space or planning burden" reduced), '
        + ("at about the same makespans" if max(others) <= 1.0 else "with makespans of its own")
        + f" ({pct(slow_fast[0])} against {pct(slow_fast[1])} for the slow lead, within {max(others):.1f} points in "
        "the other pairings)"
    )
    if duration_rises:
        rises = [m for p, m in zip(pairings, medians[default], strict=True) if p in duration_rises]
        text += f" — where the duration-only objective *raised* the median in {of(len(rises), len(pairings))} pairings, to {span(rises, 0)}"
    return text + ".\n"


def support_tamp_falls_short() -> str:
    """docs/support.md: what does not reproduce — the gains beside the thesis's and the motion model's ceiling."""
    metrics = _st()
    default, other = list(metrics["readings"])[:2]
    thesis = metrics["thesis"]["makespan_gain_percent"]
    plain = metrics["scenarios"]["unpredictable"]["slow lead, fast support"]
    greedy = metrics["scenarios"]["heuristic"]["slow lead, fast support"]
    speedups = [
        plain["supported"][default]["gain"]["speed-up"],
        greedy["supported"][other]["gain"]["speed-up"],
    ]
    ceilings = plain["ceiling"]["reduction"], greedy["ceiling"]["reduction"]
    shares = [
        100 * metrics["scenarios"][s][p]["supported"][r]["gain"][g] / thesis[p]
        for s in ("unpredictable", "heuristic")
        for p in ("slow lead, fast support", "fast lead, fast support", "slow lead, slow support")
        for r in ((default,) if s == "unpredictable" else (default, other))
        for g in ("reduction", "speed-up")
    ]
    top = thesis["slow lead, fast support"]
    below = (
        "lies below that cap, so the cap alone does not explain the gap"
        if top < min(ceilings)
        else "is beyond that cap"
    )
    return (
        f"**What does not, and what limits it.** Our gains are {span(shares, 0, ' %')} of the thesis's "
        f"({' / '.join(f'{v:g}' for v in dict.fromkeys(thesis[p] for p in _st_pairings()))} %) where the helper is as fast as the lead or "
        f"faster, under either objective and either reading of the percentage: read as a speed-up the "
        f"slow-lead/fast-helper gain is {pct(speedups[0])} ({pct(speedups[1])} heuristic, {other}), "
        + ("still far from" if max(speedups) < top else "reaching")
        + f" {top:g} %. The motion model caps what staging can do: for the plan the lead follows, perfect free "
        f"staging would cut at most {pct(ceilings[0])} (unpredictable lead) or {pct(ceilings[1])} (greedy lead) of its "
        f"makespan, since every piece still costs a grasp and a release; the thesis's {top:g} % {below}.\n"
    )


def support_tamp_steps() -> str:
    """docs/support.md (inline): how many steps the plan-following lead takes alone."""
    steps = _st()["scenarios"]["unpredictable"]["slow lead, fast support"]["alone"]["lead_steps"]["mean"]
    return f"the plans the unpredictable lead follows take {steps:.1f} steps on average"


def support_tamp_search_costs() -> str:
    """docs/support.md: what the search-aware objective costs in search nodes: the mean, a slower helper's median."""
    metrics = _st()
    other = list(metrics["readings"])[1]
    pairings = _st_pairings()
    raised = [p for p in pairings if _nodes(metrics, p, other)[1] > _nodes(metrics, p, None)[1]]
    slow_helper, alone = (
        _nodes(metrics, "fast lead, slow support", other)[0],
        _nodes(metrics, "fast lead, slow support", None)[0],
    )
    text = f"The {other} objective "
    if raised:
        text += (
            f"raises the greedy lead's *mean* nodes in {of(len(raised), len(pairings))} pairings (outlier tables where a "
            "staged piece sends the greedy search down a long branch)"
        )
    else:
        text += "raises the greedy lead's mean nodes in no pairing"
    if slow_helper > alone:
        text += (
            f" and, with a slower helper, even the median ({slow_helper:.0f} against {alone:.0f} alone) — likely because "
            "a slow helper's changes land only after the lead has searched, and then mid-plan"
        )
    else:
        text += f"; with a slower helper the median is {slow_helper:.0f} against {alone:.0f} alone"
    return text + ".\n"


def _support_tamp_limits() -> dict[str, str]:
    """The summary list's support-tamp numbers: the gains beside the thesis's, the ceilings, the search nodes."""
    metrics = _st()
    default, other = list(metrics["readings"])[:2]
    thesis = metrics["thesis"]["makespan_gain_percent"]
    ratios = [
        metrics["scenarios"][s][p]["supported"][r]["gain"][g] / thesis[p]
        for s in ("unpredictable", "heuristic")
        for p in ("slow lead, fast support", "fast lead, fast support")
        for r in (default, other)
        for g in ("reduction", "speed-up")
    ]
    ceilings = [
        metrics["scenarios"][s][p]["ceiling"]["reduction"]
        for s in metrics["scenarios"]
        for p in _st_pairings()
    ]
    alone, aware = (_nodes(metrics, "slow lead, fast support", r)[0] for r in (None, other))
    return {
        "share": f"{span([100 * r for r in ratios], 0)} % of the thesis's under either objective and either reading of the percentage (faster and equal helpers)",
        "ceilings": span(ceilings, 0, " %"),
        "verb": "reduces" if aware < alone else "does not reduce",
        "alone": f"{alone:.0f}",
        "aware": f"{aware:.0f}",
    }


def support_tamp_summary() -> str:
    """docs/experiments.md: the support-tamp section's two sentences of numbers."""
    metrics = _st()
    default, other = list(metrics["readings"])[:2]
    entry = metrics["scenarios"]["unpredictable"]["slow lead, fast support"]
    gain = entry["supported"][default]["gain"]
    thesis = metrics["thesis"]["makespan_gain_percent"]["slow lead, fast support"]
    alone, duration, aware = (
        _nodes(metrics, "slow lead, fast support", r)[0] for r in (None, default, other)
    )
    change = "raised" if duration > alone else "lowered" if duration < alone else "left"
    return (
        f"A slow lead with a fast helper gains {pct(gain['reduction'])} (speed-up {pct(gain['speed-up'])}; thesis "
        f"{thesis:g} %) though perfect, free staging could give {pct(entry['ceiling']['reduction'])}; the {other} helper "
        + ("cuts" if aware < alone else "takes")
        + f" the greedy lead's median search from {alone:.0f} to {aware:.0f} nodes where the duration-only one "
        f"{change} it {'at' if change == 'left' else 'to'} {duration:.0f}.\n"
    )


BLOCKS: dict[str, Block] = {
    "support-tamp-makespans": Block(_ST, support_tamp_makespans),
    "support-tamp-search": Block(_ST, support_tamp_search),
    "support-tamp-gaps": Block(_ST, support_tamp_gaps),
    "support-tamp-reproduces": Block(_ST, support_tamp_reproduces),
    "support-tamp-falls-short": Block(_ST, support_tamp_falls_short),
    "support-tamp-steps": Block(_ST, support_tamp_steps, inline=True),
    "support-tamp-search-costs": Block(_ST, support_tamp_search_costs),
    "support-tamp-sha": digest("support-tamp.json"),
    "support-tamp-time": run_time("support-tamp"),
    "support-tamp-summary": Block(_ST, support_tamp_summary),
    "support-tamp-summary-limits": Block(
        _ST,
        lambda: filled(
            "gains {share}, below the motion model's ceiling ({ceilings}); the search-aware objective "
            "{verb} the greedy lead's search (median {alone} → {aware} nodes)",
            _support_tamp_limits(),
        ),
        inline=True,
    ),
}
