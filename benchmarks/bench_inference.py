"""Speed of goal inference (``make bench``): writes benchmarks/results/inference.json.

For generated IKEA-like tasks of 10, 100 and 1,000 subgoals and a 10,000-step synthetic contact-event stream:

* our online update (one observation in, a belief out) for the flat and the hierarchical HMM;
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
from supportive.inference import FlatHMM, HierarchicalHMM
from supportive.inference.synthetic import synthetic_model, synthetic_stream
from supportive.tasks.htn import HTN

GOALS_SECONDS = {100: 50e-6, 1000: 1e-3}
STEPS = 10_000


def per_update(model: FlatHMM | HierarchicalHMM, observations: list[frozenset[str]]) -> float:
    running = model.filter()
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
        flat, hierarchical = FlatHMM(htn, model), HierarchicalHMM(htn, model)
        ours = {"flat": per_update(flat, observations), "hierarchical": per_update(hierarchical, observations)}
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
            f"{size:5d} subgoals: update flat {ours['flat'] * 1e6:8.1f} us, hierarchical "
            f"{ours['hierarchical'] * 1e6:8.1f} us (goal {goal}); hmmlearn re-score of the prefix "
            f"{theirs[f'rescore_prefix_{max(p for p in (100, 1000, 10_000) if p <= len(peer_steps))}_seconds'] * 1e3:8.2f} ms"
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
