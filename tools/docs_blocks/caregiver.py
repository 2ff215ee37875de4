"""caregiver: docs/results/caregiver.json."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from .common import RESULTS, Block, read_json
from .prose import number, span, words
from .reports import report_table
from .runs import digest

_CG = "docs/results/caregiver.json (supportive reproduce caregiver)"


def reductions(metrics: Mapping[str, Any], novice: str) -> dict[str, float]:
    return {r: metrics["damage_reduction_percent"][novice][r]["percent"] for r in metrics["readings"]}


def novice_groups(metrics: Mapping[str, Any]) -> tuple[list[str], list[str]]:
    """The most random novices, for whom the reading changes the reduction by at most 5 points, and the rest."""
    novices = sorted(metrics["novice_types"], key=lambda n: -metrics["novice_types"][n])
    alike = 0
    for novice in novices:
        values = reductions(metrics, novice).values()
        if max(values) - min(values) > 5:
            break
        alike += 1
    return novices[:alike], novices[alike:]


def _thesis_reductions(metrics: Mapping[str, Any]) -> dict[str, float]:
    from supportive.experiments.caregiver.report import thesis_reduction

    return {novice: thesis_reduction(novice) for novice in metrics["novice_types"]}


def _short(novice: str) -> str:
    """``50 %-random``, ``random-motion``: a novice type as an adjective."""
    return novice.replace("% random", " %-random").replace(" motion", "-motion")


def caregiver_collisions() -> str:
    """docs/caregiver.md: the largest damage of one episode, and what the caregiver did to the random-motion
    novice's stairwell falls and candle bumps."""
    metrics = read_json(RESULTS / "caregiver.json")
    counts = metrics["collisions"]["random motion"]

    def change(hazard: str) -> str:
        with_ = [counts["with"][r][hazard] for r in metrics["readings"]]
        low, high = min(with_), max(with_)
        return f"{counts['without'][hazard]} to {low}" + ("" if low == high else f"–{high}")

    return (
        f"(Maximum damage in one episode: {metrics['max_damage']}. Over the {metrics['episodes']} random-motion "
        f"episodes the caregiver cut stairwell falls from {change('stairs')} and candle bumps from "
        f"{change('candle')}, by reading.)\n"
    )


def _beside() -> tuple[dict[str, Any], str, str, dict[str, float], list[str], list[str], list[float]]:
    """What the two beside-the-thesis passages start from: the recorded run, its default and last readings,
    the thesis's reductions, the novices alike and apart under the readings, and the alike ones' reductions."""
    metrics = read_json(RESULTS / "caregiver.json")
    default, *_, last = metrics["readings"]
    alike, differ = novice_groups(metrics)
    first = [v for n in alike for v in reductions(metrics, n).values()]
    return metrics, default, last, _thesis_reductions(metrics), alike, differ, first


def caregiver_beside() -> str:
    """docs/caregiver.md: the reductions beside the thesis's, by novice and reading."""
    metrics, default, last, theirs, alike, differ, first = _beside()
    inside = [
        n
        for n in differ
        if metrics["damage_reduction_percent"][n][last]["low"]
        <= theirs[n]
        <= metrics["damage_reduction_percent"][n][last]["high"]
    ]
    over = [n for n in metrics["novice_types"] if reductions(metrics, n)[last] > 66]
    hardest = min(metrics["novice_types"], key=lambda n: metrics["novice_types"][n])
    reached = max(reductions(metrics, hardest).values()) >= theirs[hardest]
    damage = metrics["measures"]["damage_normalized"][hardest]["without"]["mean"] * metrics["max_damage"]
    return (
        f"**Beside the thesis.** For the {number(len(alike))} most random novice{'s' if len(alike) > 1 else ''} the caregiver "
        f"cuts damage by {span(first, 0, ' %')} under every reading (thesis "
        f"{' / '.join(f'{theirs[n]:.0f}' for n in alike)} %). For the more goal-directed novices the reading decides: "
        f"with P(safe) over the whole trajectory (the default, Eq. 3.2 as printed) the estimate saturates — a novice "
        f"whose moves are mostly expert-like is judged safe almost for good — and damage falls by only "
        f"{' / '.join(f'{reductions(metrics, n)[default]:.0f}' for n in differ)} % (thesis "
        f"{' / '.join(f'{theirs[n]:.0f}' for n in differ)} %); with the `{last}` reading it falls by "
        f"{' / '.join(f'{reductions(metrics, n)[last]:.0f}' for n in differ)} %"
        + (
            f", the thesis's value inside the CI for the {words([_short(n) for n in inside])} novice"
            + ("s" if len(inside) > 1 else "")
            if inside
            else ""
        )
        + f", and damage falls by more than 66 % for {number(len(over))} of the {number(len(metrics['novice_types']))} types "
        f'("generally … by over 66%"). '
        + ("No reading reaches" if not reached else "A reading reaches")
        + f" the {_short(hardest)} novice's {theirs[hardest]:.0f} %: it takes about {damage:.1f} damage an "
        f"episode without the caregiver (a table or candle bump or two; tables cannot be mitigated), so even "
        f"{metrics['episodes']} episodes leave a wide interval (95% CIs: "
        + ", ".join(
            f"{r} {span([metrics['damage_reduction_percent'][hardest][r][k] for k in ('low', 'high')], 0, ' %')}"
            for r in metrics["readings"]
        )
        + ").\n"
    )


def caregiver_summary() -> str:
    """docs/experiments.md: the caregiver section's sentence of numbers."""
    metrics, default, last, theirs, alike, differ, first = _beside()
    return (
        f"damage falls by {span(first, 0, ' %')} for the {number(len(alike))} most random novices under every reading (thesis "
        f"{' / '.join(f'{theirs[n]:.0f}' for n in alike)} %); for the more goal-directed ones the reading decides — "
        f"{' / '.join(f'{reductions(metrics, n)[default]:.0f}' for n in differ)} % for the "
        f"{words([_short(n) for n in differ])} novices with Eq. 3.2 over the whole trajectory, "
        f"{' / '.join(f'{reductions(metrics, n)[last]:.0f}' for n in differ)} % with the `{last}` reading (thesis "
        f"{' / '.join(f'{theirs[n]:.0f}' for n in differ)} %).\n"
    )


def caregiver_memory() -> str:
    """docs/caregiver.md (inline): what the reading does to the goal-directed novices in the recorded run."""
    metrics = read_json(RESULTS / "caregiver.json")
    _, differ = novice_groups(metrics)
    novice = differ[0]
    values = reductions(metrics, novice)
    return (
        f"in the recorded run, {metrics['episodes']} episodes on the {metrics['map']} map, the "
        f"{_short(novice)} novice's damage fell by {values['trajectory']:.0f} % with Eq. 3.2 over the whole "
        f"trajectory against {values['memory']:.0f} % with γ = {metrics['memory']['memory']:g} and "
        f"{values['per-step']:.0f} % with γ = {metrics['memory']['per-step']:g}"
    )


BLOCKS: dict[str, Block] = {
    "caregiver-sha": digest("caregiver.json"),
    "caregiver-reduction": report_table("caregiver", "caregiver.json", "| novice | reduction,"),
    "caregiver-damage": report_table("caregiver", "caregiver.json", "| novice | no caregiver |"),
    "caregiver-steps": report_table("caregiver", "caregiver.json", "| novice | no caregiver |", 1),
    "caregiver-collisions": Block(
        "docs/results/caregiver.json (supportive reproduce caregiver)", caregiver_collisions
    ),
    "caregiver-beside": Block(_CG, caregiver_beside),
    "caregiver-summary": Block(_CG, caregiver_summary),
    "caregiver-memory": Block(_CG, caregiver_memory, inline=True),
}
