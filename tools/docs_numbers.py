"""Write the numbers the docs quote from the commands and experiments that produce them.

A generated passage sits between ``<!-- numbers:NAME -->`` and ``<!-- /numbers:NAME -->`` in docs/*.md or
README.md; :data:`BLOCKS` says how each one is made: from a file of recorded results in ``docs/results/``
(the output of a run too long for ``make test``; ``make docs-results`` runs them again and rewrites the files),
from ``benchmarks/results/`` (``make bench``) or by running a quick command.

    python tools/docs_numbers.py            # rewrite every block (make docs-numbers)
    python tools/docs_numbers.py --check    # exit 1 naming every block that would change (the tests run this)

Numbers quoted outside a block are checked against a fresh small run by a test instead (the ``small-runs``
table of docs/experiments.md: tests/experiments/test_docs_numbers.py; the others: tests/test_docs_numbers.py).
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import subprocess
import sys
import tempfile
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from statistics import mean
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "docs" / "results"
BENCHMARKS = ROOT / "benchmarks" / "results"
_BLOCK = re.compile(r"<!-- numbers:(?P<name>[a-z0-9-]+) -->(?P<body>.*?)<!-- /numbers:(?P=name) -->", re.S)
_OPEN = re.compile(r"<!-- /?numbers:(?P<name>[^ ]*) -->")


@dataclass(frozen=True)
class Block:
    """How one generated passage is made.

    Attributes:
        source: Where its numbers come from, in words (a results file and the command that writes it).
        make: The passage's markdown: lines ending with a newline, or a phrase for an inline block.
        runs_command: Whether ``make`` runs a command (seconds) rather than reading a file.
        inline: Whether the block sits inside a line (``… <!-- numbers:x -->0.9<!-- /numbers:x --> …``)
            rather than on lines of its own.
    """

    source: str
    make: Callable[[], str]
    runs_command: bool = False
    inline: bool = False

    def body(self) -> str:
        """What goes between the markers."""
        return self.make() if self.inline else "\n" + self.make()


def documents() -> list[Path]:
    """The files that may hold generated blocks: README.md and docs/*.md."""
    return [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def block_names(text: str) -> list[str]:
    """The names of the blocks in ``text``, in order.

    Raises:
        ValueError: for a marker without its partner or a name used twice.
    """
    names = [m.group("name") for m in _BLOCK.finditer(text)]
    markers = [m.group("name") for m in _OPEN.finditer(text)]
    if len(markers) != 2 * len(names):
        raise ValueError(f"unmatched numbers markers: {sorted(set(markers) - set(names)) or markers}")
    if len(set(names)) != len(names):
        raise ValueError(f"a block name used twice: {names}")
    return names


def render(text: str, made: Mapping[str, str]) -> str:
    """``text`` with every block's body replaced by ``made[name]``."""
    return _BLOCK.sub(
        lambda m: f"<!-- numbers:{m['name']} -->{made[m['name']]}<!-- /numbers:{m['name']} -->", text
    )


def where() -> dict[str, Path]:
    """Each block's name and the document it is in.

    Raises:
        ValueError: for a block :data:`BLOCKS` does not know, one in two documents, or one in none.
    """
    found: dict[str, Path] = {}
    for path in documents():
        for name in block_names(path.read_text(encoding="utf-8")):
            if name not in BLOCKS:
                raise ValueError(f"{path.relative_to(ROOT)}: unknown numbers block {name!r}")
            if name in found:
                raise ValueError(f"numbers block {name!r} in {found[name].name} and {path.name}")
            found[name] = path
    missing = sorted(set(BLOCKS) - set(found))
    if missing:
        raise ValueError(f"numbers blocks in no document: {missing}")
    return found


def stale(names: list[str] | None = None) -> list[str]:
    """The blocks (all, or ``names``) whose text differs from what they would be made from now."""
    located = where()
    chosen = sorted(located) if names is None else names
    return [n for n in chosen if _current(located[n], n) != BLOCKS[n].body()]


def write_all() -> list[Path]:
    """Rewrite every block; the documents that changed."""
    located = where()
    made = {name: block.body() for name, block in BLOCKS.items()}
    changed = []
    for path in sorted(set(located.values())):
        text = path.read_text(encoding="utf-8")
        new = render(text, made)
        if new != text:
            path.write_text(new, encoding="utf-8")
            changed.append(path)
    return changed


def _current(path: Path, name: str) -> str:
    for match in _BLOCK.finditer(path.read_text(encoding="utf-8")):
        if match["name"] == name:
            return match["body"]
    raise ValueError(f"{path.name}: no block {name!r}")


# --- sources ---------------------------------------------------------------------------------------------


def _json(path: Path) -> Any:
    return json.loads(path.read_text(encoding="utf-8"))


def _command(*args: str) -> str:
    """The standard output of ``supportive ARGS`` (200 columns, so no line wraps), run from the repository."""
    env = {**os.environ, "COLUMNS": "200", "NO_COLOR": "1", "TERM": "dumb"}
    done = subprocess.run(
        [sys.executable, "-m", "supportive.cli", *args],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        check=False,
    )
    if done.returncode:
        raise RuntimeError(f"supportive {' '.join(args)} failed ({done.returncode}): {done.stderr.strip()}")
    return done.stdout


def _f(value: float, digits: int = 3) -> str:
    return f"{value:.{digits}f}"


_FIELD = re.compile(r"\{(?P<path>[\w./-]+)(?:\|(?P<unit>ms|us|k|pct))?(?::(?P<format>[^}]*))?\}")
_SCALE = {"ms": 1e3, "us": 1e6, "k": 1e-3, "pct": 100.0}


def filled(template: str, data: Mapping[str, Any]) -> str:
    """``template`` with each ``{a.b.c|unit:format}`` replaced by ``data["a"]["b"]["c"]``, scaled by the unit
    (``ms``, ``us``: seconds to milli-/microseconds; ``k``: thousands; ``pct``: a share in per cent) and formatted.

    >>> filled("{x.y|ms:.1f} ms, {n:,}", {"x": {"y": 0.01234}, "n": 1904})
    '12.3 ms, 1,904'
    """

    def value(match: re.Match[str]) -> str:
        item: Any = data
        for key in match["path"].split("."):
            item = item[key]
        if match["unit"]:
            item = item * _SCALE[match["unit"]]
        return format(item, match["format"] or "")

    return _FIELD.sub(value, template)


def from_benchmark(name: str, template: str) -> Block:
    """An inline block: ``template`` filled from ``benchmarks/results/NAME.json``."""
    return Block(
        f"benchmarks/results/{name}.json (make bench)",
        lambda: filled(template, _json(BENCHMARKS / f"{name}.json")),
        inline=True,
    )


# --- CaptainCook4D: `supportive captaincook --json` > docs/results/captaincook.json ---------------------------


def _captaincook() -> list[dict[str, Any]]:
    recipes: list[dict[str, Any]] = _json(RESULTS / "captaincook.json")
    return recipes


def captaincook_precedence() -> str:
    """docs/exports.md: the means over the recipes, where recall falls below 1 and the lowest precision."""
    recipes = _captaincook()
    below = [r for r in recipes if r["recall"] < 1]
    lowest = min(recipes, key=lambda r: r["precision"])
    misses = ", ".join(f"`{r['recipe']}` ({_f(r['recall'])})" for r in below) or "none"
    admitted = sum(r["admits_demonstrations"] for r in recipes)
    return (
        f"Measured: mean precision {_f(mean(r['precision'] for r in recipes))}, "
        f"recall {_f(mean(r['recall'] for r in recipes))}, F1 {_f(mean(r['f1'] for r in recipes))} over the "
        f"{len(recipes)} recipes; {admitted} of {len(recipes)} learned models admit all their recordings. Recall is "
        f"below 1 in {len(below)} recipes: {misses}. Precision is lowest in `{lowest['recipe']}` "
        f"({_f(lowest['precision'])}).\n"
    )


def captaincook_edges() -> str:
    """docs/learning.md: task-graph edge F1, full and 5-shot, the means over the recipes."""
    recipes = _captaincook()
    full = mean(r["edges"]["f1"] for r in recipes)
    few = mean(r["edges_5_shot"]["f1"] for r in recipes)
    return f"{_f(full)} full, {_f(few)} 5-shot\n"


# --- the learning benchmark: `make bench` > benchmarks/results/learn.json ---------------------------------


def _seconds(value: float) -> str:
    if value >= 10:
        return f"{value:.0f} s"
    if value >= 1:
        return f"{value:.2f} s"
    milliseconds = value * 1000
    return f"{milliseconds:.3g} ms" if milliseconds < 100 else f"{milliseconds:.0f} ms"


def learn_benchmark() -> str:
    """docs/exports.md: each case's median time beside the strict learner's and its goal, if it has one."""
    cases = _json(BENCHMARKS / "learn.json")["cases"]
    rows = ["| case | actions | default learner | strict | ratio | goal |", "|---|---:|---:|---:|---:|---|"]
    ratios = []
    for name, case in cases.items():
        strict, ratio = case["strict"]["median_seconds"], case["general_over_strict"]
        comparable = ratio <= _COMPARABLE
        ratios += [ratio] if comparable else []
        goal = case["goal_seconds"]
        met = "–" if goal is None else f"{_seconds(goal)}: {'met' if case['meets_goal'] else '**not met**'}"
        rows.append(
            f"| `{name}` | {case['actions']:,} | {_seconds(case['median_seconds'])} | {_seconds(strict)} | "
            f"{f'{ratio:.1f}×' if comparable else '—'} | {met} |"
        )
    return "\n".join(rows) + (
        f"\n\nWhere the two are comparable (a ratio under {_COMPARABLE}×), the default learner takes "
        f"{min(ratios):.1f}–{max(ratios):.1f}× the strict one's time.\n"
    )


_COMPARABLE = 100  # a larger ratio means the learners did different work (the slip search), shown as "—"


# --- `supportive reproduce all`: docs/results/summary.json ---------------------------------------------------


def _summary() -> dict[str, Any]:
    summary: dict[str, Any] = _json(RESULTS / "summary.json")
    return summary


def reproduce_all_trials() -> str:
    """docs/experiments.md: the seed and each experiment's trials in the recorded run."""
    summary = _summary()
    counts = ", ".join(f"{name} {count}" for name, count in sorted(summary["trials"].items()))
    return f"(seed {summary['seed']}, each experiment's default trials: {counts})\n"


def reproduce_all_summary() -> str:
    """docs/experiments.md: the summary table, as ``summary.md`` renders it."""
    from supportive.experiments import findings_table

    rows = [
        (e["experiment"], e["reference"], e["findings"]) for e in _summary()["experiments"] if e["findings"]
    ]
    return findings_table(rows) + "\n"


# --- one experiment's full run: its metrics.json > docs/results/FILE, its report.md made from them --------


def _report(experiment: str, file: str) -> str:
    """The experiment's ``report.md`` made from the recorded ``metrics.json``."""
    from supportive.experiments import get

    return get(experiment).report(_json(RESULTS / file))


def _nth_table(experiment: str, file: str, header: str, n: int = 0) -> str:
    """The ``n``-th table of ``experiment``'s report (from ``docs/results/FILE``) whose header starts with
    ``header``."""
    tables = re.findall(r"(?:^\|.*\|\n)+", _report(experiment, file) + "\n", re.M)
    matching = [str(t) for t in tables if t.startswith(header)]
    if len(matching) <= n:
        raise ValueError(f"{experiment}'s report has no table {n} starting {header!r}")
    return matching[n]


def report_table(experiment: str, file: str, header: str) -> Block:
    """The first table of ``experiment``'s report (from ``docs/results/FILE``) whose header starts with
    ``header``."""
    return Block(
        f"docs/results/{file} (supportive reproduce {experiment})",
        lambda: _nth_table(experiment, file, header),
    )


def report_part(experiment: str, file: str, first: str, stop: str) -> Block:
    """The lines of ``experiment``'s report from the heading ``first`` up to the heading ``stop``, its
    headings two levels down (they sit under a section of the docs)."""

    def make() -> str:
        text = _report(experiment, file)
        part = text[text.index(f"\n{first}") + 1 : text.index(f"\n{stop}") + 1]
        return re.sub(r"^## ", "#### ", part, flags=re.M)

    return Block(f"docs/results/{file} (supportive reproduce {experiment})", make)


def timing_part(experiment: str, file: str, first: str, stop: str | None = None) -> Block:
    """The lines of the ``timing.md`` that ``experiment``'s ``timing_report`` writes from the recorded
    ``timing.json`` (``docs/results/FILE``): from the line starting ``first`` up to the one starting ``stop``
    (or the end), headings two levels down."""

    def make() -> str:
        from supportive.experiments import get

        report = get(experiment).timing_report
        if report is None:
            raise ValueError(f"{experiment} has no timing report")
        with tempfile.TemporaryDirectory() as folder:
            report(_json(RESULTS / file)["trials"], Path(folder))
            text = (Path(folder) / "timing.md").read_text(encoding="utf-8")
        start = text.index(f"\n{first}") + 1
        end = len(text) if stop is None else text.index(f"\n{stop}", start) + 1
        return re.sub(r"^## ", "#### ", text[start:end].rstrip("\n") + "\n", flags=re.M)

    return Block(f"docs/results/{file} (supportive reproduce {experiment}: timing.json)", make)


def digest(file: str) -> Block:
    """An inline block: the recorded file's sha256, shortened as the docs quote it (``922beaf9…9856cb71``)."""

    def make() -> str:
        full = hashlib.sha256((RESULTS / file).read_bytes()).hexdigest()
        return f"`{full[:8]}…{full[-8:]}`"

    return Block(f"docs/results/{file}", make, inline=True)


def edge_reduction_counts() -> str:
    """docs/experiments.md: how many learned hierarchies are complete, and inside the thesis's depth range."""
    metrics = _json(RESULTS / "edge-reduction.json")
    tasks = metrics["tasks"]
    low, high = metrics["thesis"]["mean_action_depth"]["min"], metrics["thesis"]["mean_action_depth"]["max"]
    learned = metrics["models"]["learned"]
    inside = sum(low <= t["learned"]["depth"] <= high for t in tasks)
    orderings = metrics["all_orderings"]
    sizes = [t["subgoals"] for t in tasks if t.get("all_orderings")]
    return (
        f"Learned from 4 paths, {learned['complete']} of {len(tasks)} hierarchies are complete and {inside} of "
        f"{len(tasks)} tasks have a depth inside {low}–{high}. From all orderings ({orderings['qualified']} tasks, "
        f"with {min(sizes)}–{max(sizes)} subgoals; the larger ones admit more than {orderings['limit']:,} orderings) "
        f"the learner recovered **{orderings['recovered']} of {orderings['qualified']}** structures exactly.\n"
    )


def edge_reduction_learned() -> str:
    """docs/learning.md: complete hierarchies and mean depth, learned from 4 paths, beside the truth's."""
    metrics = _json(RESULTS / "edge-reduction.json")
    learned, truth = metrics["models"]["learned"], metrics["models"]["ground_truth"]
    return (
        f"complete hierarchies {learned['complete']} of {learned['tasks']}, mean action depth "
        f"{learned['depth']['mean']:.2f} (ground truth {truth['depth']['mean']:.2f}; the thesis reports "
        f"{metrics['thesis']['mean_action_depth']['mean']} for its CC-HTNs).\n"
    )


def _signed(value: float) -> str:
    return f"{value:+.3f}".replace("-", "−")


def goal_inference_tracker() -> str:
    """docs/inference.md: the progress-aware tracker beside the hierarchical HMM at overlap 0.8, per task size."""
    sizes = _json(RESULTS / "goal-inference.json")["sizes"]

    def ahead(setting: str) -> int:
        return sum(
            s["accuracy"][setting]["progress"]["subgoal"] > s["accuracy"][setting]["hierarchical"]["subgoal"]
            for s in sizes
        )

    parts, excluding = [], []
    for size in sizes:
        accuracy, difference = (
            size["accuracy"]["overlap-0.8-noisy"],
            size["progress_difference"]["overlap-0.8-noisy"],
        )
        parts.append(
            f"{size['subgoals']:,}: {accuracy['hierarchical']['subgoal']:.3f} → {accuracy['progress']['subgoal']:.3f} "
            f"({_signed(difference['mean'])} [{_signed(difference['low'])}, {_signed(difference['high'])}])"
        )
        excluding += [f"{size['subgoals']:,}"] if difference["low"] > 0 else []
    return (
        f"at overlap 0.8 the tracker's mean subgoal accuracy is above the hierarchical HMM's in "
        f"{ahead('overlap-0.8-clean')} of {len(sizes)} task sizes clean and {ahead('overlap-0.8-noisy')} of "
        f"{len(sizes)} noisy. Noisy, hierarchical → tracker (paired difference, 95% CI), by subgoals: "
        f"{', '.join(parts)}; the interval excludes zero at {', '.join(excluding) or 'no size'} subgoals ("
        f"{sizes[0]['trials']} trials per size).\n"
    )


def caregiver_collisions() -> str:
    """docs/caregiver.md: the largest damage of one episode, and what the caregiver did to the random-motion
    novice's stairwell falls and candle bumps."""
    metrics = _json(RESULTS / "caregiver.json")
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


# --- quick commands -------------------------------------------------------------------------------------------


def support_two_cells_led() -> str:
    """docs/support.md: `supportive support two-cells-led --simulate`, its first lines (a few favoured plans)."""
    lines = _command("support", "two-cells-led", "--simulate").splitlines()
    favoured = [i for i, line in enumerate(lines) if line.startswith("  favours")]
    kept = [*lines[: favoured[0] + 1], "  ...", *lines[favoured[-1] + 1 :]] if len(favoured) > 1 else lines
    return "```console\n$ supportive support two-cells-led --simulate\n" + "\n".join(kept) + "\n```\n"


_CAPTAINCOOK = "docs/results/captaincook.json (supportive captaincook --json)"
_SUMMARY = "docs/results/summary.json (supportive reproduce all)"
_EDGES = "docs/results/edge-reduction.json (supportive reproduce edge-reduction)"
BLOCKS: dict[str, Block] = {
    "captaincook-precedence": Block(_CAPTAINCOOK, captaincook_precedence),
    "captaincook-edges": Block(_CAPTAINCOOK, captaincook_edges),
    "learn-benchmark": Block("benchmarks/results/learn.json (make bench)", learn_benchmark),
    "reproduce-all-trials": Block(_SUMMARY, reproduce_all_trials),
    "reproduce-all-summary": Block(_SUMMARY, reproduce_all_summary),
    "edge-reduction-depth": report_table("edge-reduction", "edge-reduction.json", "| model | tasks | mean |"),
    "edge-reduction-counts": Block(_EDGES, edge_reduction_counts),
    "edge-reduction-bins": report_table("edge-reduction", "edge-reduction.json", "| subgoals |"),
    "edge-reduction-totals": report_table(
        "edge-reduction", "edge-reduction.json", "| model | tasks | complete |"
    ),
    "captaincook-curves-f1": report_table("captaincook", "captaincook-curves.json", "| k | recipes |"),
    "captaincook-curves-own-k": report_table("captaincook", "captaincook-curves.json", "| condition |"),
    "captaincook-curves-queries": report_table(
        "captaincook", "captaincook-curves.json", "| strategy | asked |"
    ),
    "active-learning-blocks-tasks": report_part(
        "active-learning-blocks", "active-learning-blocks.json", "## Task 1", "## Verdict"
    ),
    "active-learning-blocks-sha": digest("active-learning-blocks.json"),
    "goal-inference-sha": digest("goal-inference.json"),
    "transfer-sha": digest("transfer.json"),
    "caregiver-sha": digest("caregiver.json"),
    "caregiver-reduction": report_table("caregiver", "caregiver.json", "| novice | reduction,"),
    "caregiver-damage": report_table("caregiver", "caregiver.json", "| novice | no caregiver |"),
    "caregiver-steps": Block(
        "docs/results/caregiver.json (supportive reproduce caregiver)",
        lambda: _nth_table("caregiver", "caregiver.json", "| novice | no caregiver |", 1),
    ),
    "caregiver-collisions": Block(
        "docs/results/caregiver.json (supportive reproduce caregiver)", caregiver_collisions
    ),
    "transfer-episodes": report_table("transfer", "transfer.json", "| condition | episodes"),
    "transfer-comparisons": report_table("transfer", "transfer.json", "| comparison |"),
    "goal-inference-accuracy": report_table(
        "goal-inference", "goal-inference.json", "| setting | flat: subgoal |"
    ),
    "goal-inference-work": report_table(
        "goal-inference", "goal-inference.json", "| subgoals | trials | subtasks |"
    ),
    "goal-inference-timing": timing_part(
        "goal-inference", "goal-inference-timing.json", "| subgoals |", "## "
    ),
    "goal-inference-accuracy-summary": report_table(
        "goal-inference", "goal-inference.json", "| setting | flat: subgoal |"
    ),
    "goal-inference-tracker": Block(
        "docs/results/goal-inference.json (supportive reproduce goal-inference)", goal_inference_tracker
    ),
    "goal-inference-figure": timing_part(
        "goal-inference", "goal-inference-timing.json", "## Beside Figure 2.4"
    ),
    "edge-reduction-learned": Block(_EDGES, edge_reduction_learned),
    "captaincook-prediction-models": report_table(
        "captaincook-prediction", "captaincook-prediction.json", "| model | top-1 |"
    ),
    "captaincook-prediction-reliability": report_table(
        "captaincook-prediction", "captaincook-prediction.json", "| top-1 probability |"
    ),
    "mistake-detection-thresholds": report_table("mistake-detection", "mistake-detection.json", "| threshold |"),
    "mistake-detection-captaincook": report_table(
        "mistake-detection", "mistake-detection.json", "| method | precision |"
    ),
    "mistake-detection-kinds": report_table("mistake-detection", "mistake-detection.json", "| method | kind |"),
    "bench-service": from_benchmark(
        "service",
        "**{claim_release.ops_per_second:,.0f} operations/s, p50 {claim_release.p50_ms:.1f} ms, p90 {claim_release.p90_ms:.1f} ms, p99 {claim_release.p99_ms:.1f} ms** (targets ≥ {targets.ops_per_second:.0f} ops/s and p99 < {targets.p99_ms:.0f} ms)",
    ),
    "bench-social-update": from_benchmark(
        "social",
        "{update_plus_ellipse.median_seconds|us:.1f} µs median, {update_plus_ellipse.p99_seconds|us:.1f} µs p99 (target {target_seconds|us:.0f} µs)",
    ),
    "bench-social": from_benchmark(
        "social",
        "| `update` + `ellipse()`, {samples_in_window} samples in the window (target {target_seconds|us:.0f} µs) | {update_plus_ellipse.median_seconds|us:.1f} µs | {update_plus_ellipse.p99_seconds|us:.1f} µs |\n| peer, measured in the same run: deque → `numpy.array`, `numpy.cov`, `numpy.linalg.eigh` per update | {peer_update_plus_ellipse.median_seconds|us:.1f} µs | {peer_update_plus_ellipse.p99_seconds|us:.1f} µs |\n| `field` at {field.points:,} points, one agent | {field.one_agent.median_seconds|ms:.2f} ms | |\n| `field` at {field.points:,} points, three agents combined | {field.three_agents.median_seconds|ms:.2f} ms | |\n| `PeerPolicy.decide` over the example's six subtasks | {peer_role_decision.median_seconds|us:.0f} µs | |",
    ),
    "bench-rosbag": from_benchmark(
        "rosbag",
        "| `read_contact_frames` (what `infer --bag` consumes) | **{ours.seconds:.2f}** ({ours.frames_per_second|k:,.0f},000 frames/s) | **{rss_above_baseline_mb.ours:.0f} MB** ({ours.peak_rss_mb:.0f} MB in all, = the baseline) | **{ours.tracemalloc_peak_mb:.1f} MB** |\n| a naive peer: deserialize every message into a list first | {naive_peer.seconds:.2f} | {rss_above_baseline_mb.naive_peer:.0f} MB | {naive_peer.tracemalloc_peak_mb:.0f} MB |",
    ),
    "bench-rosbag-bag": from_benchmark(
        "rosbag",
        "({bag.frames:,}\n`ContactFrame`s, a {bag.size_mb:.0f} MB MCAP bag)",
    ),
    "bench-caregiver": from_benchmark(
        "caregiver",
        "20 episodes, default reading, one core: {experiment.seconds_one_process:.1f} s (target {experiment.target_seconds:.0f} s);\n                # the full default run on 2 workers: {full_run.seconds_two_workers:.1f} s at load ≈ 3–4 (target {full_run.target_seconds:.0f} s);\n                # one decision on the {decision.map} map: median {decision.median_seconds|ms:.2f} ms, p99 {decision.p99_seconds|ms:.2f} ms (target {decision.target_seconds|ms:.0f} ms)",
    ),
    "bench-active-learning": from_benchmark(
        "experiments",
        "{active_learning.trials} trials: {active_learning.in_process_seconds:.1f} s in one\nprocess and {active_learning.workers_2_seconds:.1f} s with 2 workers",
    ),
    "bench-progress": from_benchmark(
        "inference",
        "one contact-event update {cases.ikea-100-subgoals.update_seconds.progress|us:.0f} µs at 100 subgoals ({cases.ikea-100-subgoals.progress_states} states),\n{cases.ikea-1000-subgoals.update_seconds.progress|us:.0f} µs at 1,000 ({cases.ikea-1000-subgoals.progress_states:,} states); the hierarchical HMM {cases.ikea-100-subgoals.update_seconds.hierarchical|us:.0f} µs and {cases.ikea-1000-subgoals.update_seconds.hierarchical|us:.0f} µs in the same run",
    ),
    "bench-hmm": from_benchmark(
        "inference",
        "10 subgoals {cases.ikea-10-subgoals.update_seconds.hierarchical|us:.1f} µs\n(flat {cases.ikea-10-subgoals.update_seconds.flat|us:.1f} µs); 100 subgoals {cases.ikea-100-subgoals.update_seconds.hierarchical|us:.1f} µs (flat {cases.ikea-100-subgoals.update_seconds.flat|us:.1f} µs; goal < {cases.ikea-100-subgoals.goal_update_seconds|us:.0f} µs); 1,000 subgoals {cases.ikea-1000-subgoals.update_seconds.hierarchical|us:.1f} µs (flat {cases.ikea-1000-subgoals.update_seconds.flat|us:.1f} µs; goal\n< {cases.ikea-1000-subgoals.goal_update_seconds|ms:.0f} ms)",
    ),
    "bench-language": from_benchmark(
        "language",
        "target {target_seconds|ms:.0f} ms; {per_utterance.gc_as_is.samples} timings, one other process busy on one of the two\n  cores) takes a median {per_utterance.gc_as_is.median_seconds|ms:.2f} ms with a p99 of {per_utterance.gc_as_is.p99_seconds|ms:.1f} ms and a maximum of {per_utterance.gc_as_is.max_seconds|ms:.0f} ms; with the start-up objects frozen\n  (`gc.freeze()`) a median {per_utterance.gc_frozen.median_seconds|ms:.2f} ms, p99 {per_utterance.gc_frozen.p99_seconds|ms:.1f} ms, maximum {per_utterance.gc_frozen.max_seconds|ms:.1f} ms",
    ),
    "bench-language-accuracy": from_benchmark(
        "language",
        "On {utterances} held-out chair\n  utterances written by hand (`{held_out}`): **top-1 {accuracy.top1:.2f}, top-3 {accuracy.top3:.2f}**",
    ),
    "bench-language-table": from_benchmark(
        "language",
        "| bag of words, naive Bayes (the thesis's) | {accuracy.top1:.3f} | {accuracy.top3:.3f} | {per_utterance.gc_as_is.median_seconds|ms:.2f} ms |\n| sentence embeddings | {embeddings_peer.top1:.3f} | {embeddings_peer.top3:.3f} | {embeddings_peer.per_utterance.median_seconds|ms:.1f} ms |",
    ),
    "bench-cover": from_benchmark(
        "cover",
        "an exact cover takes a median {runs.exact/ilp.median_seconds|ms:.0f} ms (max {runs.exact/ilp.max_seconds|ms:.0f} ms), the thesis's full coverage with\nirrelevant states allowed {runs.exact/ilp_full_allow_irrelevant.median_seconds|ms:.0f} ms (max {runs.exact/ilp_full_allow_irrelevant.max_seconds:.2f} s), a partial cover {runs.exact/ilp_partial.median_seconds|ms:.0f} ms, ESPRESSO {runs.exact/espresso.median_seconds|ms:.0f} ms; with {setup.noise|pct:.0f} % of the labels\nflipped (no exact cover) a partial cover takes a median {runs.noisy/ilp_partial.median_seconds|ms:.0f} ms (max {runs.noisy/ilp_partial.max_seconds:.2f} s), all under the {target_seconds:.0f} s target, and\nis more faithful than ESPRESSO's (precision {runs.noisy/ilp_partial.mean_precision:.2f} / recall {runs.noisy/ilp_partial.mean_recall:.2f} in {runs.noisy/ilp_partial.mean_formula_literals:.0f} literals against {runs.noisy/espresso_partial.mean_precision:.2f} / {runs.noisy/espresso_partial.mean_recall:.2f} in {runs.noisy/espresso_partial.mean_formula_literals:.0f})",
    ),
    "bench-support": from_benchmark(
        "support",
        "200 environments {environments.200.one_process.median_seconds:.2f} s median, {environments.200.one_process.max_seconds:.2f} s max on one core (target {target_seconds_200:.0f} s); with 2 workers {environments.200.two_workers.median_seconds:.2f} s, a {environments.200.speedup_two_workers}×\nspeed-up; 400 environments {environments.400.one_process.median_seconds:.2f} s → {environments.400.two_workers.median_seconds:.2f} s ({environments.400.speedup_two_workers}×); 800: {environments.800.one_process.median_seconds:.2f} s → {environments.800.two_workers.median_seconds:.2f} s ({environments.800.speedup_two_workers}×",
    ),
    "bench-hmm-speedup": from_benchmark(
        "inference", "{cases.ikea-1000-subgoals.hierarchical_speedup_over_flat:.1f}"
    ),
    "bench-hmmlearn": from_benchmark(
        "inference", "{cases.ikea-100-subgoals.hmmlearn.rescore_prefix_10000_seconds:.1f}"
    ),
    "support-two-cells-led": Block(
        "supportive support two-cells-led --simulate", support_two_cells_led, True
    ),
}


def main(argv: list[str]) -> int:
    """``--check``: 1 and the stale blocks' names when any would change, else 0; no argument: rewrite them."""
    if argv == ["--check"]:
        names = stale()
        for name in names:
            print(f"docs numbers out of date: {name} ({BLOCKS[name].source}); run `make docs-numbers`")
        return 1 if names else 0
    if argv:
        print("usage: python tools/docs_numbers.py [--check]", file=sys.stderr)
        return 2
    for path in write_all():
        print(f"rewrote {path.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
