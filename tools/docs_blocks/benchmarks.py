"""Benchmark numbers: ``make bench`` > ``benchmarks/results/NAME.json``."""

from __future__ import annotations

from .common import BENCHMARKS, Block, filled, read_json


def from_benchmark(name: str, template: str) -> Block:
    """An inline block: ``template`` filled from ``benchmarks/results/NAME.json``."""
    return Block(
        f"benchmarks/results/{name}.json (make bench)",
        lambda: filled(template, read_json(BENCHMARKS / f"{name}.json")),
        inline=True,
    )


def _seconds(value: float) -> str:
    if value >= 10:
        return f"{value:.0f} s"
    if value >= 1:
        return f"{value:.2f} s"
    milliseconds = value * 1000
    return f"{milliseconds:.3g} ms" if milliseconds < 100 else f"{milliseconds:.0f} ms"


def learn_benchmark() -> str:
    """docs/exports.md: each case's median time beside the strict learner's and its goal, if it has one."""
    cases = read_json(BENCHMARKS / "learn.json")["cases"]
    rows = ["| case | actions | default learner | strict | ratio | goal |", "|---|---:|---:|---:|---:|---|"]
    ratios = []
    for name, case in cases.items():
        strict, ratio = case["strict"]["median_seconds"], case["general_over_strict"]
        comparable = "slips" not in case  # with slips put in, only the default learner searches for them
        ratios += [ratio] if comparable else []
        goal = case["goal_seconds"]
        met = "–" if goal is None else f"{_seconds(goal)}: {'met' if case['meets_goal'] else '**not met**'}"
        rows.append(
            f"| `{name}` | {case['actions']:,} | {_seconds(case['median_seconds'])} | {_seconds(strict)} | "
            f"{f'{ratio:.1f}×' if comparable else '—'} | {met} |"
        )
    return "\n".join(rows) + (
        "\n\nOn the demonstrations without slips (the strict learner searches for none, so the last case has no "
        f"ratio), the default learner takes {min(ratios):.1f}–{max(ratios):.1f}× the strict one's time.\n"
    )


def admission_benchmark() -> str:
    """docs/learning.md: the share of valid executions admitted as clean demonstrations grow, per profile."""
    result = read_json(BENCHMARKS / "admission.json")
    compared = result["compared_threshold"]
    sizes = list(result["mean_share_of_valid_executions_admitted"])
    tasks = sum(result["tasks"].values())

    def row(label: str, values: dict[str, float], form: str = "{:.3f}") -> str:
        return f"| {label} | " + " | ".join(form.format(values[n]) for n in sizes) + " |"

    rows = [
        "| demonstrations | " + " | ".join(sizes) + " |",
        "|---|" + "---:|" * len(sizes),
        row(f"**valid executions admitted**, mean of {tasks} tasks", result["mean_share_of_valid_executions_admitted"]),
        *(row(f"… {profile} ({count})", result["by_profile"][profile]) for profile, count in result["tasks"].items()),
        row("steps set aside as slips (all tasks)", result["steps_set_aside"], "{}"),
        row("own demonstrations admitted", result["own_demonstrations_admitted"]),
        row(
            f"valid executions admitted, subtasks from {compared['subtask_demonstrations']} demonstrations",
            compared["mean_share_of_valid_executions_admitted"],
        ),
    ]
    return "\n".join(rows) + (
        f"\n\nOn average over the tasks the default learner's share is {_verdict(result['drops'])}; with "
        f"subtasks from {compared['subtask_demonstrations']} demonstrations it is {_verdict(compared['drops'])}.\n"
    )


def detector_demos_benchmark() -> str:
    """docs/inference.md: the mistake detector's false alarms and recall by the demonstrations it learned from."""
    result = read_json(BENCHMARKS / "detector-demos.json")
    sizes = list(result["false_alarms_per_step"])

    def row(label: str, values: dict[str, float]) -> str:
        return f"| {label} | " + " | ".join(f"{values[n]:.3f}" for n in sizes) + " |"

    rows = [
        "| demonstrations | " + " | ".join(sizes) + " |",
        "|---|" + "---:|" * len(sizes),
        row(f"**steps of valid executions flagged**, {result['tasks']} tasks", result["false_alarms_per_step"]),
        row("tasks with a flagged valid step", result["tasks_with_a_false_alarm"]),
        *(row(f"recall: {kind}", values) for kind, values in result["recall"].items()),
    ]
    rates = result["false_alarms_per_step"]
    said = ", ".join(f"1 in {1 / rates[n]:,.0f} from {n}" for n in sizes if rates[n] > 0)
    return "\n".join(rows) + f"\n\nSteps of a correct execution flagged: {said} demonstrations.\n"


def clean_slips_benchmark() -> str:
    """docs/learning.md: how often the default learner sets a step aside in clean uniform demonstrations of the
    property tests' distribution, with 95 % upper bounds, and the draws where it did."""
    result = read_json(BENCHMARKS / "clean-slips.json")
    rows = ["| tasks | drawn | a step set aside or a demonstration refused | share | 95 % upper bound |", "|---|---:|---:|---:|---:|"]
    for key, rate in result["rates"].items():
        label = f"{key.removeprefix('n ').replace('-', '–')} demonstrations" if key.startswith("n ") else key
        rows.append(f"| {label} | {rate['tasks']:,} | {rate['failed']} | {rate['share']:.2%} | {rate['upper_95']:.2%} |")
    failures = result["failures"]
    said = "; ".join(
        f"{f['kind']}, {f['size']} steps" + (f" in {f['chains']} chains" if "chains" in f else "") + f", {f['n']} demonstrations: "
        f"{f['set_aside']} set aside, {f['refused']} refused"
        for f in failures
    )
    return "\n".join(rows) + ("\n\nThe draws that failed: " + said + ".\n" if failures else "\n\nNo draw failed.\n")


def order_penalty_benchmark() -> str:
    """docs/learning.md: the default learner's task-graph F1 on generated tasks and its learning time with the
    top level's orders weighed at each penalty, against the coin test (the default)."""
    result = read_json(BENCHMARKS / "order-penalty.json")
    rows = [
        "| top level's orders | edge F1 (95 % interval) | minus the coin test's (± s.e.) | uniform people | people with habits | learning time |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for name, row in result["settings"].items():
        f1 = row["f1"]
        rows.append(
            f"| {name} | {f1['mean']:.3f} [{f1['low']:.3f}, {f1['high']:.3f}] | {row['minus_coin_test']:+.3f} ± "
            f"{row['standard_error']:.3f} | {row['by_people']['uniform']:.3f} | {row['by_people']['habits']:.3f} | "
            f"{row['time_ratio_to_coin_test']:.2f}× |"
        )
    candidate = result["candidate"]
    picked = "none" if candidate is None else f"order_penalty={candidate:g}"
    return "\n".join(rows) + (
        f"\n\n{result['tasks']:,} generated tasks ({result['tasks_per_cell']} per profile, kind of people and number "
        f"of demonstrations). The procedure's candidate ({result['procedure']}): {picked}.\n"
    )


def habits_benchmark() -> str:
    """docs/learning.md: fits that set a step aside, and the share of steps set aside, in clean
    demonstrations by people with habits, per learner, habit strength and number of demonstrations."""
    result = read_json(BENCHMARKS / "habits.json")
    learners = result["by_learner"]
    sizes = list(next(iter(next(iter(learners.values())).values())))
    tasks = result["tasks_per_strength"]
    lines = [
        "| learner | habit strength | " + " | ".join(f"{n} demonstrations" for n in sizes) + " |",
        "|---|---|" + "---:|" * len(sizes),
        *(
            f"| {name} | {strength} | "
            + " | ".join(
                f"{row[n]['fits_with_a_step_set_aside']} of {tasks} ({row[n]['share_of_steps_set_aside']:.2%} of steps)"
                for n in sizes
            )
            + " |"
            for name, rows in learners.items()
            for strength, row in rows.items()
        ),
    ]
    return "\n".join(lines) + "\n"


def _verdict(drops: list[dict[str, float]]) -> str:
    """Whether a curve never falls, or where it does."""
    if not drops:
        return "non-decreasing in the number of demonstrations"
    falls = ", ".join(
        f"from {d['start']} to {d['end']} demonstrations by {-d['by']:.3f} (paired standard error "
        f"{d['standard_error']:.3f})"
        for d in drops
    )
    return f"**not** non-decreasing: it falls {falls}"


def backoff_benchmark() -> str:
    """docs/inference.md: next-step prediction on generated tasks with mistakes, one back-off weight against a
    second one after an off-script step."""
    result = read_json(BENCHMARKS / "backoff.json")
    rows = [
        "| demonstrations with a mistake | held-out steps | one weight: top-1 · log2 P | off-script back-off: top-1 · log2 P | fitted weights (mean): on · off script |",
        "|---:|---:|---:|---:|---:|",
    ]
    for row in result["rows"]:
        one, two = row["one weight"], row["off-script back-off"]
        rows.append(
            f"| {row['share_mistaken']:.0%} | {row['held_out_steps']:,} | {one['top1']:.3f} · {one['log2']:.3f} | "
            f"{two['top1']:.3f} · {two['log2']:.3f} | {row['mean_backoff']:.2f} · {row['mean_off_script_backoff']:.2f} |"
        )
    tasks = result["rows"][0]["tasks"]
    return "\n".join(rows) + f"\n\n{tasks} tasks per row (seed {result['seed']}).\n"


def active_learning_benchmark() -> str:
    """docs/experiments.md: the active-learning experiment's default reading timed in one process and on 2
    workers, the load average around it, and the earlier issue's 60 s target for 2 workers met or not."""
    timed = read_json(BENCHMARKS / "experiments.json")["active_learning"]
    verdict = "meets" if timed["meets_target"] else "misses"
    return (
        f"{timed['trials']} trials: {timed['in_process_seconds']:.1f} s in one\nprocess and "
        f"{timed['workers_2_seconds']:.1f} s with 2 workers ({timed['dask_speedup']:.2f}× as fast), cluster start-up "
        f"included, at a load average of {timed['load_before'][0]:.1f} before and {timed['load_after'][0]:.1f} after "
        f"(2 cores): that {verdict} the earlier issue's target of {timed['target_seconds']:.0f} s with 2 workers"
    )


BLOCKS: dict[str, Block] = {
    "learn-benchmark": Block("benchmarks/results/learn.json (make bench)", learn_benchmark),
    "bench-admission": Block("benchmarks/results/admission.json (make bench)", admission_benchmark),
    "bench-clean-slips": Block("benchmarks/results/clean-slips.json (make bench)", clean_slips_benchmark),
    "bench-habits": Block("benchmarks/results/habits.json (make bench)", habits_benchmark),
    "bench-order-penalty": Block("benchmarks/results/order-penalty.json (make bench)", order_penalty_benchmark),
    "bench-detector-demos": Block("benchmarks/results/detector-demos.json (make bench)", detector_demos_benchmark),
    "bench-backoff": Block("benchmarks/results/backoff.json (make bench)", backoff_benchmark),
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
        "20 episodes, default reading, one core: {experiment.seconds_one_process:.1f} s (target {experiment.target_seconds:.0f} s);\n                # the full default run on 2 workers: {full_run.seconds_two_workers:.1f} s at load {full_run.load_average.0:.1f} (target {full_run.target_seconds:.0f} s);\n                # one decision on the {decision.map} map: median {decision.median_seconds|ms:.2f} ms, p99 {decision.p99_seconds|ms:.2f} ms (target {decision.target_seconds|ms:.0f} ms)",
    ),
    "bench-active-learning": Block("benchmarks/results/experiments.json (make bench)", active_learning_benchmark, inline=True),
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
        "target {target_seconds|ms:.0f} ms; {per_utterance.gc_as_is.samples} timings on the 2-core machine)\n  takes a median {per_utterance.gc_as_is.median_seconds|ms:.2f} ms with a p99 of {per_utterance.gc_as_is.p99_seconds|ms:.1f} ms and a maximum of {per_utterance.gc_as_is.max_seconds|ms:.0f} ms; with the start-up objects frozen\n  (`gc.freeze()`) a median {per_utterance.gc_frozen.median_seconds|ms:.2f} ms, p99 {per_utterance.gc_frozen.p99_seconds|ms:.1f} ms, maximum {per_utterance.gc_frozen.max_seconds|ms:.1f} ms",
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
}
