"""Speed of goal inference (``make bench``): writes benchmarks/results/inference.json.

For generated IKEA-like tasks of 10, 100 and 1,000 subgoals and a 10,000-step synthetic contact-event stream:

* our online update (one observation in, a belief out) for the flat and the hierarchical HMM and the
  progress-aware tracker (issue #14: goals 50 us at 100 subgoals, 1 ms at 1,000; exact, over its enumerated
  states, when it has at most ``max_states``; the beam's agreement with exact is measured on a task whose
  states are enumerable);
* the peer, hmmlearn's CategoricalHMM on the same flat model (its observations are the distinct event sets of
  the stream, each a symbol). hmmlearn has no online filter, so a user who wants a belief at every step
  re-scores the prefix: we time that at several prefix lengths, and its full-sequence ``score`` and
  ``predict_proba`` against ours on the whole stream.
"""

from __future__ import annotations

import argparse
import json
import platform
import time
from pathlib import Path

import numpy as np
from hmmlearn.hmm import CategoricalHMM

from supportive.generate import generate_task
from supportive.inference import FlatHMM, HierarchicalHMM, ProgressHMM
from supportive.inference.synthetic import synthetic_model, synthetic_stream
from supportive.tasks.htn import HTN

GOALS_SECONDS = {100: 50e-6, 1000: 1e-3}
DETECTION_GOAL_SECONDS = 20e-6
"""Issue #24: online mistake detection adds at most this per update at 100 subgoals."""
PROGRESS_GOALS = {100: 50e-6, 1000: 1e-3}
STEPS = 10_000


def per_update(model: FlatHMM | HierarchicalHMM | ProgressHMM, observations: list[frozenset[str]]) -> float:
    running = model.filter()
    running.update(observations[0])  # build what the first update builds (the tracker's matrices)
    started = time.perf_counter()
    for observation in observations:
        running.update(observation)
    return (time.perf_counter() - started) / len(observations)


def peer(model: FlatHMM, observations: list[frozenset[str]], prefixes: list[int]) -> dict[str, float]:
    symbols = {o: i for i, o in enumerate(dict.fromkeys(observations))}
    emissions = np.exp(np.array([model.observations_.log_likelihood(o) for o in symbols]).T)  # type: ignore[union-attr]
    emissions = emissions[[model.observations_.action_index[a] for a, _ in model.layout_.leaves]]  # type: ignore[union-attr]
    emissions /= emissions.sum(axis=1, keepdims=True)
    n = model.layout_.n_leaves
    hmm = CategoricalHMM(n_components=n, n_features=len(symbols), init_params="", params="")
    hmm.startprob_ = model.transitions_.start
    hmm.transmat_ = model.stay_ * np.eye(n) + (1 - model.stay_) * model.transitions_.matrix  # type: ignore[union-attr]
    hmm.emissionprob_ = emissions
    coded = np.array([symbols[o] for o in observations]).reshape(-1, 1)
    out: dict[str, float] = {}
    for length in prefixes:
        started = time.perf_counter()
        hmm.score(coded[:length])
        out[f"rescore_prefix_{length}_seconds"] = time.perf_counter() - started
    started = time.perf_counter()
    hmm.score(coded)
    out["score_full_seconds"] = time.perf_counter() - started
    started = time.perf_counter()
    hmm.predict_proba(coded)
    out["predict_proba_full_seconds"] = time.perf_counter() - started
    out["steps"] = len(coded)
    return out


def detection_overhead(seed: int, size: int = 100, executions: int = 30) -> dict[str, object]:
    """Per known action, the progress-aware tracker alone and with the mistake detector on it, alternating in
    one run over the same executions (a tenth with a step moved early, so mistakes are judged too)."""
    from supportive.generate.mistakes import inject
    from supportive.inference.mistakes import MistakeDetector
    from supportive.tasks.htn import admits, sample_ordering, to_leaves

    spec = generate_task(size, seed)
    assert spec.structure is not None
    structure = spec.structure
    rng = np.random.default_rng(seed)
    demos = [[a for a, _ in sample_ordering(structure, rng)] for _ in range(executions)]
    demos, _ = inject(demos, "early", 0.1, lambda d: admits(structure, to_leaves(d)), rng)
    hmm = ProgressHMM(HTN(spec.name, (structure,))).fit()
    detector = MistakeDetector(hmm)
    alone: list[float] = []
    judged: list[float] = []
    flagged = 0
    for demo in demos:
        running = hmm.filter()
        started = time.perf_counter()
        for action in demo:
            running.observe(action)
        alone.append((time.perf_counter() - started) / len(demo))
        detector.reset()
        started = time.perf_counter()
        for action in demo:
            flagged += detector.observe(action).mistake
        judged.append((time.perf_counter() - started) / len(demo))
    tracker, with_detector = float(np.median(alone)), float(np.median(judged))
    return {
        "subgoals": size,
        "executions": len(demos),
        "steps_flagged": flagged,
        "tracker_update_seconds": tracker,
        "with_detector_update_seconds": with_detector,
        "detection_added_seconds": with_detector - tracker,
        "goal_added_seconds": DETECTION_GOAL_SECONDS,
        "meets_goal": with_detector - tracker <= DETECTION_GOAL_SECONDS,
    }


def beam_agreement(seed: int, size: int = 30, steps: int = 2000) -> dict[str, object]:
    """Mean total-variation distance between the beam's and the exact tracker's current-subgoal beliefs
    and next-step predictions, per beam width, on one stream."""
    spec = generate_task(size, seed)
    assert spec.structure is not None
    htn = HTN(spec.name, (spec.structure,))
    model = synthetic_model([a.id for a in spec.actions], overlap=0.5, spurious=1.0, seed=seed)
    stream = synthetic_stream(spec.structure, model, executions=steps // (5 * size) + 1, seed=seed)
    observations = list(stream.observations[:steps])
    exact = ProgressHMM(htn, model, restart=True).fit()
    reference = [b.subgoals.copy() for b in map(exact.filter().update, observations)]
    widths: dict[str, object] = {"states": len(exact.states_ or ()), "steps": len(observations)}
    for beam in (8, 32, 128):
        approximate = ProgressHMM(htn, model, restart=True, max_states=1, beam=beam).fit().filter()
        distances = [
            0.5 * float(np.abs(approximate.update(o).subgoals - r).sum()) for o, r in zip(observations, reference, strict=True)
        ]
        widths[f"beam_{beam}_mean_tv"] = float(np.mean(distances))
        widths[f"beam_{beam}_max_tv"] = float(np.max(distances))
    return widths


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "inference.json")
    parser.add_argument("--seed", type=int, default=3)
    args = parser.parse_args()
    cases = {}
    for size in (10, 100, 1000):
        spec = generate_task(size, args.seed)
        assert spec.structure is not None
        htn = HTN(spec.name, (spec.structure,))
        model = synthetic_model([a.id for a in spec.actions], overlap=0.5, spurious=1.0, seed=args.seed)
        executions = max(1, STEPS // (5 * size) + 1)
        stream = synthetic_stream(spec.structure, model, executions=executions, seed=args.seed)
        observations = list(stream.observations[:STEPS])
        flat, hierarchical = FlatHMM(htn, model).fit(), HierarchicalHMM(htn, model).fit()
        progress = ProgressHMM(htn, model, restart=True).fit()  # the stream chains executions
        ours = {
            "flat": per_update(flat, observations),
            "hierarchical": per_update(hierarchical, observations),
            "progress": per_update(progress, observations),
        }
        started = time.perf_counter()
        hierarchical.predict_proba(observations)
        ours_full = time.perf_counter() - started
        peer_steps = observations if size <= 100 else observations[:1000]
        theirs = peer(flat, peer_steps, [p for p in (100, 1000, 10_000) if p <= len(peer_steps)])
        goal = GOALS_SECONDS.get(size)
        cases[f"ikea-{size}-subgoals"] = {
            "subgoals": size,
            "stream_steps": len(observations),
            "update_seconds": ours,
            "goal_update_seconds": goal,
            "meets_goal": None if goal is None else ours["hierarchical"] <= goal,
            "progress_goal_update_seconds": PROGRESS_GOALS.get(size),
            "progress_meets_goal": None if size not in PROGRESS_GOALS else ours["progress"] <= PROGRESS_GOALS[size],
            "progress_states": None if progress.states_ is None else len(progress.states_),
            "progress_over_hierarchical": ours["progress"] / ours["hierarchical"],
            "hierarchical_speedup_over_flat": ours["flat"] / ours["hierarchical"],
            "transition_nonzeros": {
                "flat": int(flat.transitions_.nonzeros),
                "hierarchical": int(hierarchical.transitions_.nonzeros),
            },
            "ours_predict_proba_full_seconds": ours_full,
            "hmmlearn": theirs,
            "ratios": {
                "hmmlearn_rescore_last_prefix_over_our_update": theirs[f"rescore_prefix_{max(p for p in (100, 1000, 10_000) if p <= len(peer_steps))}_seconds"]
                / ours["hierarchical"],
                "hmmlearn_predict_proba_over_ours_full": theirs["predict_proba_full_seconds"]
                * (len(observations) / theirs["steps"])
                / ours_full,
            },
        }
        print(
            f"{size:5d} subgoals: progress {ours['progress'] * 1e6:8.1f} us "
            f"({cases[f'ikea-{size}-subgoals']['progress_states']} states), "
            f"update flat {ours['flat'] * 1e6:8.1f} us, hierarchical "
            f"{ours['hierarchical'] * 1e6:8.1f} us (goal {goal}); hmmlearn re-score of the prefix "
            f"{theirs[f'rescore_prefix_{max(p for p in (100, 1000, 10_000) if p <= len(peer_steps))}_seconds'] * 1e3:8.2f} ms"
        )
    cases["beam-vs-exact"] = beam_agreement(args.seed)
    cases["mistake-detection-100-subgoals"] = detection = detection_overhead(args.seed)
    print(
        f"mistake detection at 100 subgoals: tracker {detection['tracker_update_seconds'] * 1e6:.1f} us, with the "
        f"detector {detection['with_detector_update_seconds'] * 1e6:.1f} us per action "
        f"(added {detection['detection_added_seconds'] * 1e6:.1f} us; goal {DETECTION_GOAL_SECONDS * 1e6:.0f} us)"
    )
    result = {
        "benchmark": "inference",
        "machine": {"python": platform.python_version(), "processor": platform.machine()},
        "seed": args.seed,
        "peer": "hmmlearn CategoricalHMM on the flat model (same transitions and emissions)",
        "cases": cases,
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")


if __name__ == "__main__":
    main()
