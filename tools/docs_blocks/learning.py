"""generalisation, learner-settings and selection-settings (docs/learning.md): docs/results/generalisation.json,
learner-settings.json and selection-settings.json."""

from __future__ import annotations

from collections.abc import Mapping
from statistics import mean
from typing import Any

from .captaincook import CAPTAINCOOK, captaincook_recipes
from .common import RESULTS, Block, read_json
from .prose import span
from .reports import report_table
from .runs import run_time

_GEN = "docs/results/generalisation.json (supportive reproduce generalisation)"
_LS = "docs/results/learner-settings.json (supportive reproduce learner-settings)"
_SS = "docs/results/selection-settings.json (supportive reproduce selection-settings)"


def _gen() -> dict[str, Any]:
    metrics: dict[str, Any] = read_json(RESULTS / "generalisation.json")
    return metrics


def generalisation_table() -> str:
    """docs/learning.md: the default learner, the general reading and the strict learner on generated tasks and
    CaptainCook4D, beside what the issues asked."""
    from supportive.learning.graph_edges import PEERS

    metrics = _gen()
    learners = ("auto", "general", "strict")
    synthetic, captaincook, slips = metrics["synthetic"], metrics["captaincook"], metrics["slips"]

    def orderings(profile: str) -> list[str]:
        return [
            f"{synthetic[profile][m]['recall']:.3f} / {synthetic[profile][m]['precision']:.3f}"
            for m in learners
        ]

    def admitted(m: str) -> str:
        c = captaincook[m]
        return f"{c['admitted']} / {c['held_out']} ({c['admission']:.1%})".replace("%", " %")

    def pr(m: str, data: str) -> str:
        return f"{captaincook[m][f'{data}_precision']:.3f} / {captaincook[m][f'{data}_recall']:.3f}"

    def f1(m: str) -> str:
        text = f"{captaincook[m]['edges']['full']['f1']:.3f} / {captaincook[m]['edges']['5-shot']['f1']:.3f}"
        return f"**{text}**" if m == learners[0] else text

    def slipped(data: str) -> str:
        return " · ".join(
            f"{slips[p][data]['recall']:.3f} / {slips[p][data]['precision']:.3f}" for p in ("ikea", "uniform")
        )

    peer = PEERS["DO (Seminara et al. 2024)"]
    rows = [
        "| | auto (default) | general | strict | asked |",
        "|---|---:|---:|---:|---|",
        f"| generated `uniform` tasks, 4–12 actions, 4 demonstrations: recall / precision of orderings "
        f"({synthetic['uniform']['auto']['tasks']} tasks) | "
        + " | ".join(orderings("uniform"))
        + " | ≥ 0.7 / ≥ 0.95 |",
        f"| generated `ikea` tasks, same ({synthetic['ikea']['auto']['tasks']} tasks) | "
        + " | ".join(orderings("ikea"))
        + " | |",
        "| CaptainCook4D, learned from the first half of each recipe's error-free recordings: other half admitted | "
        + " | ".join(admitted(m) for m in learners)
        + " | ≥ 60 % |",
        "| … the held-out recordings' mean log-likelihood, nats (every execution a hierarchy admits equally "
        "likely, a refused one explained as noise; mean over the recipes) | "
        + " | ".join(f"{captaincook[m]['held_out_log_likelihood']['mean']:.2f}" for m in learners)
        + " | |",
        "| CaptainCook4D precedence P / R among the graph's steps, all error-free recordings | "
        + " | ".join(pr(m, "error_free") for m in learners)
        + " | |",
        "| … all recordings, errors included | "
        + " | ".join(pr(m, "with_errors") for m in learners)
        + " | |",
        "| CaptainCook4D task graphs, DTGL protocol, F1 full / 5-shot (P / R in the report) | "
        + " | ".join(f1(m) for m in learners)
        + f" | ≥ 0.90 / ≥ 0.86; DO {peer['full']:.3f} / {peer['5-shot']:.3f} |",
        "| generated tasks, 16 clean demonstrations (general): recall / precision, ikea · uniform | | "
        + slipped("clean")
        + " | | |",
        "| … and 4 more with one step moved to a random place | | "
        + slipped("with_slips")
        + " | | must not flatten |",
        "| … the same, nothing set aside (`slips=False`) | | "
        + slipped("with_slips_none_set_aside")
        + " | | |",
    ]
    return "\n".join(rows) + "\n"


_ISSUE_23_F1 = {"full": 0.90, "5-shot": 0.86}
_ISSUE_13_ADMISSION = 0.60


def generalisation_verdicts() -> str:
    """docs/learning.md: the default learner's task-graph F1 (from captaincook.json, the block above) beside the
    published model, the pinned readings and issue #23's target; its held-out admission beside issue #13's."""
    from supportive.learning.graph_edges import PEERS

    recipes = captaincook_recipes()
    ours = {
        s: mean(r["edges" if s == "full" else "edges_5_shot"]["f1"] for r in recipes)
        for s in ("full", "5-shot")
    }
    captaincook = _gen()["captaincook"]
    peer = PEERS["DO (Seminara et al. 2024)"]
    general = captaincook["general"]["edges"]["5-shot"]["f1"]
    strict = {s: captaincook["strict"]["edges"][s]["f1"] for s in ("full", "5-shot")}

    def side(theirs: Mapping[str, float]) -> str:
        """Above, below or level with ``theirs`` as the tables show the figures (three decimals), in both
        settings or each."""
        said = ["above" if a > b else "below" if a < b else "level with"
                for a, b in ((round(ours[s], 3), round(theirs[s], 3)) for s in ("full", "5-shot"))]
        return said[0] if said[0] == said[1] else f"{said[0]} (all recordings) and {said[1]} (5-shot)"

    met = all(round(ours[s], 3) >= _ISSUE_23_F1[s] for s in ours)
    admission, kept = captaincook["auto"]["admission"], captaincook["general"]["admission"]
    interval = captaincook["auto"]["admission_interval"]
    synthetic = _gen()["synthetic"]["uniform"]["auto"]
    return (
        f"— {side(peer)} the published Direct Optimization model's ({peer['full']:.3f} / {peer['5-shot']:.3f}) and "
        f"{'above' if ours['5-shot'] > general else 'below'} the pinned general reading's 5-shot {general:.3f}, "
        f"{'but ' if 'below' in side(strict) else ''}{side(strict)} our strict learner's ({strict['full']:.3f} / {strict['5-shot']:.3f}) and "
        f"{'at or above' if met else 'below'} the issue's {_ISSUE_23_F1['full']:.2f} / {_ISSUE_23_F1['5-shot']:.2f} — "
        f"**{'met' if met else 'not met'}**. Its held-out half admission, {admission:.1%}, is "
        f"{'at or above' if admission >= _ISSUE_13_ADMISSION else 'below'} the {_ISSUE_13_ADMISSION:.0%} issue #13 "
        f"asked to keep (the general reading keeps {kept:.1%}"
        + (
            "; where held-out likelihood prefers a tighter reading than the general one, fewer unseen recordings are admitted"
            if kept > admission
            else ""
        )
        + f"; 95% interval over the recipes {interval['low']:.1%}–{interval['high']:.1%}"
        + f") — **{'met' if admission >= _ISSUE_13_ADMISSION else 'not met'}**"
        + (
            ""
            if admission >= _ISSUE_13_ADMISSION
            else "; the held-out recordings' log-likelihood, which the settings are chosen by, is in the table "
            "above and *Where subtasks begin* below weighs the two"
        )
        + ". Generated tasks from 4 demonstrations: "
        f"recall {synthetic['recall']:.3f} at precision {synthetic['precision']:.3f} — "
        + (
            "kept"
            if synthetic["recall"] >= 0.7 and synthetic["precision"] >= 0.95
            else "**not kept** (≥ 0.7 / ≥ 0.95 asked)"
        )
        + ".\n"
    ).replace("%", " %")


def generalisation_subtasks() -> str:
    """docs/learning.md (inline): the default learner on generated ``uniform`` tasks from 4 demonstrations."""
    synthetic = _gen()["synthetic"]["uniform"]["auto"]
    return f"recall {synthetic['recall']:.2f} / precision {synthetic['precision']:.3f}"


def _ls() -> dict[str, Any]:
    metrics: dict[str, Any] = read_json(RESULTS / "learner-settings.json")
    return metrics


_KINDS = {"moved": " to a random place", "repeated": " later"}
_COUNT = {1: "one", 2: "two"}


def learner_settings_chosen() -> str:
    """docs/learning.md: the chosen setting against issue #23's precision and recall, cell by cell, on
    demonstrations drawn uniformly (the issue's case), and its precision and recall where people have habits."""
    metrics = _ls()
    chosen = metrics["chosen"]
    by_people = metrics["settings"][chosen]["kinds_by_people"]
    cells = {name: cell for name, cell in by_people["uniform"].items() if cell["mistakes"]}
    precisions = [c["precision"] for c in cells.values()]
    short = [name for name, c in cells.items() if c["recall"] < 0.7]

    def by_kind(name: str) -> str:
        kind, n = name.rsplit(" ", 1)
        others = [(m, c["recall"]) for m, c in cells.items() if m.startswith(kind + " ") and m != name]
        return (
            f"a step **{kind}**{_KINDS.get(kind, '')}, {n} demonstrations, recall {cells[name]['recall']:.2f} ("
            + ", ".join(f"{r:.2f} at {m.rsplit(' ', 1)[1]}" for m, r in others)
            + ")"
        )

    recall = (
        "in every cell"
        if not short
        else f"in every cell but {_COUNT[len(short)]}: " + "; ".join(by_kind(name) for name in short)
        if len(short) < 3
        else f"in {len(cells) - len(short)} of {len(cells)} cells"
    )
    habits = [c for c in by_people["habits"].values() if c["mistakes"]]
    return (
        f"The chosen setting (`{chosen}`), on demonstrations drawn uniformly (issue #23's case), "
        + ("meets" if min(precisions) >= 0.9 else "misses")
        + f" the issue's precision (≥ 0.9 in every cell: {span(precisions, 2)}) and "
        + ("meets" if not short else "misses")
        + f" its recall (≥ 0.7) {recall}. Where the demonstrations are by people with habits, its precision is "
        f"{span([c['precision'] for c in habits], 2)} and its recall {span([c['recall'] for c in habits], 2)}: "
        "a wrong report there can be a rare valid order read as a slip.\n"
    )


def generalisation_intervals() -> str:
    """docs/learning.md: how sure the default learner's task-graph F1 is — its 95 % interval over the recipes,
    and the paired difference from the strict learner — and whether DO's published mean or a zero difference
    lies inside."""
    from supportive.experiments.statistics import format_ci
    from supportive.learning.graph_edges import PEERS

    edges = _gen()["captaincook"]["auto"]["edges"]
    peer = PEERS["DO (Seminara et al. 2024)"]
    shown, inside, differs = [], [], []
    for setting in ("full", "5-shot"):
        f1, interval, paired = edges[setting]["f1"], edges[setting]["f1_interval"], edges[setting]["f1_minus_strict"]
        shown.append(
            f"{setting} {format_ci({'mean': f1, **interval})} (minus strict, per recipe: "
            f"{format_ci(paired, signed=True)})"
        )
        inside.append(interval["low"] <= peer[setting] <= interval["high"])
        differs.append(not paired["low"] <= 0.0 <= paired["high"])
    peer_words = (
        "DO's published means lie inside both intervals"
        if all(inside)
        else "DO's published mean lies outside " + ("both intervals" if not any(inside) else "one interval")
    )
    strict_words = (
        "the interval of the paired difference from our strict learner holds zero in both settings"
        if not any(differs)
        else "the interval of the paired difference from our strict learner leaves out zero in "
        + ("both settings" if all(differs) else "one setting")
    )
    undecided = all(inside) and not any(differs)
    return (
        "How sure these means are (95 % intervals, Student's t over the 24 recipes, from the recorded run): "
        f"{'; '.join(shown)}. {peer_words[0].upper()}{peer_words[1:]}, and {strict_words}"
        + (": these recipes show the default neither better nor worse than either." if undecided else ".")
        + "\n"
    )


def learner_settings_clean() -> str:
    """docs/learning.md (inline): what the chosen setting reported on clean data, by people without habits and
    with them."""
    row = _ls()["settings"][_ls()["chosen"]]
    tasks, flagged = row["clean_tasks"], row["clean_tasks_flagged"]
    habits, habit_flagged = row["habits_tasks"], row["habits_tasks_flagged"]
    return (
        f"reported a slip in {flagged} of the {tasks:,} clean tasks by people without habits ({flagged / tasks:.2%} "
        f"of them; {row['clean_flagged']:.4%} of their steps) and in {habit_flagged} of the {habits:,} by people "
        f"with habits ({habit_flagged / habits:.2%}; {row['habits_flagged']:.4%} of their steps)"
    )


def learner_settings_spread() -> str:
    """docs/learning.md: how sure the recorded run's choice is, from its bootstrap spread: how often the chosen
    setting is best, which settings are within one and two standard errors of it, and that the rest are not."""
    from supportive.experiments.learner_settings.spread import RESAMPLES

    metrics = _ls()
    chosen, spread = metrics["chosen"], metrics["spread"]
    others = sorted((name for name in spread if name != chosen), key=lambda name: spread[name]["gap"])

    def behind(name: str) -> str:
        s = spread[name]
        return f"`{name}` {s['gap']:.4f} behind (standard error {s['error']:.4f}, {s['gap'] / s['error']:.1f} of them)"

    within = [n for n in others if spread[n]["gap"] <= spread[n]["error"]]
    near = [n for n in others if spread[n]["error"] < spread[n]["gap"] <= 2 * spread[n]["error"]]
    rest = len(others) - len(within) - len(near)
    return (
        f"Resampling the tasks with mistakes {RESAMPLES:,} times within their cells, the chosen setting has the "
        f"best worst F1 in {spread[chosen]['best_share']:.1%} of the resamples. Within one standard error of it, "
        "which this run does not tell from it: "
        + ("; ".join(behind(n) for n in within) if within else "none")
        + ". Within two: "
        + ("; ".join(behind(n) for n in near) if near else "none")
        + f". The other {rest} qualified settings are more than two standard errors behind.\n"
    )


CLEAN_BANDS = ((1, 9), (10, 19), (20, 49), (50, 99), (100, 200))
"""Bands of the number of clean demonstrations :func:`learner_settings_clean_by_n` reports apart (the clean
tasks draw it uniformly from 1–200, so an overall rate is mostly that of many demonstrations)."""


def learner_settings_clean_by_n() -> str:
    """docs/learning.md (inline): the chosen setting's clean tasks with a slip reported, by number of
    demonstrations and by people without habits / with them, from the recorded trials."""
    chosen = _ls()["chosen"]
    clean = [t for t in _ls()["tasks"] if t["case"] == "none"]
    parts = []
    for low, high in CLEAN_BANDS:
        counts = []
        for people in ("uniform", "habits"):
            band = [t for t in clean if low <= t["demonstrations"] <= high and t["people"] == people]
            flagged = sum(t["settings"][chosen]["wrong_tasks"] for t in band)
            counts.append(f"{flagged} of {len(band):,}")
        parts.append(f"{low}–{high} demonstrations: {' / '.join(counts)}")
    return "; ".join(parts)


def selection_settings_chosen() -> str:
    """docs/learning.md: the best policy, how far the conventional one and never comparing are behind it (and
    whether within one standard error), which was kept, and what likelihood alone would pick at what cost in
    recall."""
    from supportive.experiments.selection_settings.measure import (
        CONVENTIONAL,
        RECALL_DEMONSTRATIONS,
        best_policy,
        policy_name,
        within_one_error,
    )

    metrics: dict[str, Any] = read_json(RESULTS / "selection-settings.json")
    policies, best, chosen, recall = metrics["policies"], metrics["best"], metrics["chosen"], metrics["recall"]

    def behind(name: str) -> str:
        row = policies[name]
        within = "within" if within_one_error(row) else "beyond"
        return f"{row['gap']:.4f} nats behind it, {within} one standard error ({row['error']:.4f})"

    conventional, never = policy_name(*CONVENTIONAL), policy_name(CONVENTIONAL[0], None)
    against = (
        "it is the conventional policy" if best == conventional
        else f"the conventional `{conventional}` is {behind(conventional)}"
    )
    text = (
        f"The best policy that keeps the recall is `{best}` ({policies[best]['gain']:+.3f} nats per fresh "
        f"execution over keeping `general`, the mean over the rows); {against}, and not comparing at all is "
        f"{behind(never)}. Kept: `{chosen}`."
    )
    likelihood = best_policy({name: {**row, "qualifies": True} for name, row in policies.items()})
    assert likelihood is not None
    if not policies[likelihood]["qualifies"]:
        text += (
            f" On likelihood alone `{likelihood}` would win ({policies[likelihood]['gain']:+.3f}), at the cost of "
            f"issue #13's recall: from {RECALL_DEMONSTRATIONS} demonstrations of `uniform` tasks it admits "
            f"{policies[likelihood]['recall']:.3f} of the fresh executions, `general` {recall['general']:.3f}."
        )
    return text + "\n"


def selection_settings_subtasks_chosen() -> str:
    """docs/learning.md: the ``subtask_demonstrations`` the procedure picks, how far issue #13's 4 is behind
    the best, and what the learner defaults to."""
    from supportive.experiments.selection_settings.gains import within_one_error
    from supportive.experiments.selection_settings.measure import RECALL_DEMONSTRATIONS
    from supportive.learning import HTNLearner

    subtasks: dict[str, Any] = read_json(RESULTS / "selection-settings.json")["subtasks"]
    rows, best, chosen = subtasks["thresholds"], subtasks["best"], subtasks["chosen"]
    issue = rows[str(RECALL_DEMONSTRATIONS)]
    within = "within" if within_one_error(issue) else "beyond"
    return (
        f"The best threshold is {best} ({rows[str(best)]['gain']:+.3f} nats per fresh execution over never making "
        f"subtasks, the mean over the rows); issue #13's {RECALL_DEMONSTRATIONS} is {issue['gap']:.4f} nats "
        f"behind it, {within} one standard error ({issue['error']:.4f}). Chosen: {chosen}; `HTNLearner` "
        f"defaults to {HTNLearner().subtask_demonstrations}.\n"
    )


def selection_settings_evidence_chosen() -> str:
    """docs/learning.md: the ``evidence`` level the procedure picks, what the levels it passed over gain and
    cost, and what the learner defaults to."""
    from supportive.experiments.selection_settings.evidence import CONVENTIONAL_EVIDENCE, LEVELS
    from supportive.experiments.selection_settings.gains import within_one_error
    from supportive.learning import HTNLearner

    evidence: dict[str, Any] = read_json(RESULTS / "selection-settings.json")["evidence"]
    rows, best, chosen = evidence["levels"], evidence["best"], evidence["chosen"]
    conventional = rows[str(CONVENTIONAL_EVIDENCE)]
    parts = []
    if best != CONVENTIONAL_EVIDENCE:
        within = "within" if within_one_error(conventional) else "beyond"
        parts.append(
            f"The best qualifying level is {best} ({rows[str(best)]['gain']:+.3f} nats per fresh execution over "
            f"{CONVENTIONAL_EVIDENCE}); {CONVENTIONAL_EVIDENCE} is {within} one standard error of it "
            f"({conventional['gap']:.4f} behind, error {conventional['error']:.4f})."
        )
    else:
        parts.append(f"No qualifying level predicts the fresh executions better than {CONVENTIONAL_EVIDENCE}.")
    costly = [level for level in LEVELS if not rows[str(level)]["qualifies"]]
    if costly:
        parts.append(
            "Costing issue #13's recall: "
            + "; ".join(
                f"{level} ({rows[str(level)]['gain']:+.3f} nats, admits {rows[str(level)]['recall']:.3f} of the "
                f"fresh executions against {conventional['recall']:.3f})"
                for level in costly
            )
            + "."
        )
    behind = [level for level in LEVELS if rows[str(level)]["qualifies"] and level != best]
    if behind:
        parts.append(
            "Behind the best: "
            + "; ".join(
                f"{level} by {rows[str(level)]['gap']:.3f} nats ("
                f"{'within' if within_one_error(rows[str(level)]) else 'beyond'} one standard error, "
                f"{rows[str(level)]['error']:.3f})"
                for level in behind
            )
            + "."
        )
    parts.append(f"Chosen: {chosen}; `HTNLearner` defaults to {HTNLearner().evidence}.")
    return " ".join(parts) + "\n"


def selection_settings_losses() -> str:
    """docs/learning.md: where comparing loses from 6 demonstrations on, under the kept policy's folds: which
    readings it keeps instead of ``general`` on how many tasks, and what each then gains or loses."""
    metrics: dict[str, Any] = read_json(RESULTS / "selection-settings.json")
    kept_folds = metrics["policies"][metrics["chosen"]]["folds"]
    if kept_folds is None:
        return "The policy kept never compares the readings.\n"
    folds = str(kept_folds)
    rows = [r for r in metrics["tasks"] if r["demonstrations"] >= 6]
    gains: dict[str, list[float]] = {}
    for r in rows:
        chosen = r["folds"][folds]["chosen"]
        if chosen != "general":
            gains.setdefault(chosen, []).append(r["folds"][folds]["log_likelihood"] - r["general"]["log_likelihood"])
    kept = sorted(gains.items(), key=lambda item: -len(item[1]))
    return (
        f"From 6 demonstrations on, with {folds} folds, the comparison keeps another reading than `general` on "
        f"{sum(len(g) for g in gains.values())} of the {len(rows):,} tasks: "
        + "; ".join(f"`{name}` on {len(g)}, {mean(g):+.2f} nats per fresh execution" for name, g in kept)
        + ".\n"
    )


BLOCKS: dict[str, Block] = {
    "generalisation-table": Block(_GEN, generalisation_table),
    "generalisation-verdicts": Block(f"{_GEN}; {CAPTAINCOOK}", generalisation_verdicts),
    "generalisation-intervals": Block(_GEN, generalisation_intervals),
    "generalisation-subtasks": Block(_GEN, generalisation_subtasks, inline=True),
    "generalisation-time": run_time("generalisation"),
    "generalisation-slip-sizes": report_table("generalisation", "generalisation.json", "| steps | people |"),
    "learner-settings-table": report_table("learner-settings", "learner-settings.json", "| setting |"),
    "learner-settings-chosen": Block(_LS, learner_settings_chosen),
    "learner-settings-clean": Block(_LS, learner_settings_clean, inline=True),
    "learner-settings-clean-by-n": Block(_LS, learner_settings_clean_by_n, inline=True),
    "learner-settings-time": run_time("learner-settings"),
    "learner-settings-spread": Block(_LS, learner_settings_spread),
    "learner-settings-spread-table": report_table("learner-settings", "learner-settings.json", "| setting | worst F1 |"),
    "selection-settings-gains": report_table("selection-settings", "selection-settings.json", "| demonstrations | 2 folds"),
    "selection-settings-admitted": report_table(
        "selection-settings", "selection-settings.json", "| demonstrations | general"
    ),
    "selection-settings-policies": report_table("selection-settings", "selection-settings.json", "| compare from"),
    "selection-settings-chosen": Block(_SS, selection_settings_chosen),
    "selection-settings-subtask-gains": report_table(
        "selection-settings", "selection-settings.json", "| demonstrations | gain of making subtasks"
    ),
    "selection-settings-thresholds": report_table(
        "selection-settings", "selection-settings.json", "| subtask_demonstrations |"
    ),
    "selection-settings-subtasks-chosen": Block(_SS, selection_settings_subtasks_chosen),
    "selection-settings-evidence-gains": report_table(
        "selection-settings", "selection-settings.json", "| demonstrations | evidence="
    ),
    "selection-settings-evidence-levels": report_table("selection-settings", "selection-settings.json", "| evidence |"),
    "selection-settings-evidence-chosen": Block(_SS, selection_settings_evidence_chosen),
    "selection-settings-losses": Block(_SS, selection_settings_losses),
    "selection-settings-time": run_time("selection-settings"),
}
