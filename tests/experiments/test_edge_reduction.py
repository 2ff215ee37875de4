from __future__ import annotations

import json
from pathlib import Path

import pytest

from supportive.errors import ExperimentError
from supportive.experiments import get, run_experiment
from supportive.experiments.edge_reduction.measure import make_trials, measure_task, model_sizes, run_trial
from supportive.experiments.edge_reduction.report import verdict
from supportive.experiments.edge_reduction.summary import bin_of, summarize
from supportive.experiments.plotting import PNG_SIGNATURE
from supportive.generate import THESIS_DEPTH_RANGE, as_demonstrations, sample_orderings
from supportive.tasks.htn import HTN, ActionNode, ChainNode, CliqueNode, Node
from supportive.tasks.spec import TaskSpec


def _leaves(names: str) -> tuple[ActionNode, ...]:
    return tuple(ActionNode(name) for name in names)


def _spec(name: str, structure: Node, demonstrations: int = 4, seed: int = 0) -> TaskSpec:
    demos = as_demonstrations(sample_orderings(structure, demonstrations, seed))
    return TaskSpec(name, (), structure, demos)


# Structures whose order-free parts are cliques of primitives (the case §2.1.7.3 argues about).
CLIQUE_TASKS: list[Node] = [
    ChainNode((ActionNode("a"), CliqueNode(_leaves("bcde")), ActionNode("f"), CliqueNode(_leaves("ghi")))),
    CliqueNode(_leaves("abcdef")),
    ChainNode((CliqueNode(_leaves("abc")), CliqueNode(_leaves("defgh")), ActionNode("i"))),
    CliqueNode((ChainNode(_leaves("ab")), *_leaves("cdef"))),
    ChainNode((CliqueNode(_leaves("abc")), CliqueNode(_leaves("def")), CliqueNode(_leaves("ghi")))),
]


def test_clique_and_chain_edge_counts() -> None:
    for k in (2, 3, 6):
        clique = model_sizes(HTN("c", (CliqueNode(_leaves("abcdefgh"[:k])),)))
        assert (clique["flat_edges"], clique["htn_edges"], clique["depth"]) == (k * (k - 1), k, 1.0)
        chain = model_sizes(HTN("c", (ChainNode(_leaves("abcdefgh"[:k])),)))
        assert (chain["flat_edges"], chain["htn_edges"]) == (k - 1, k - 1)
        assert set(chain) == {"flat_edges", "htn_edges", "depth", "roots", "complete"}
    # transitions into and out of a clique: one CC-HTN edge each instead of one per member
    sizes = model_sizes(
        HTN("c", (ChainNode((ActionNode("a"), CliqueNode(_leaves("bcd")), ActionNode("e"))),))
    )
    assert (sizes["flat_edges"], sizes["htn_edges"]) == (3 + 6 + 3, 2 + 3)


def test_summary_of_clique_tasks() -> None:
    results = [
        {"index": i, **measure_task(_spec(f"t{i}", structure, seed=i))}
        for i, structure in enumerate(CLIQUE_TASKS)
    ]
    metrics = summarize(results)
    truth = [r["ground_truth"] for r in results]
    # every task has a clique of >= 3 children: strictly fewer CC-HTN edges
    assert [(t["flat_edges"], t["htn_edges"]) for t in truth] == [
        (4 + 12 + 4 + 3 + 6, 3 + 4 + 3),  # chain[a, {bcde}, f, {ghi}]
        (30, 6),
        (6 + 15 + 20 + 5, 2 + 3 + 5),  # chain[{abc}, {defgh}, i]
        (1 + 4 * 3 + 1 * 4 + 4 * 1, 1 + 5),  # clique{[ab], c, d, e, f}
        (6 + 9 + 6 + 9 + 6, 2 + 3 * 3),
    ]
    summary = metrics["models"]["ground_truth"]
    assert (summary["fewer_edges"], summary["more_edges"]) == (5, 0)
    assert summary["flat_per_htn"] == round(
        sum(t["flat_edges"] for t in truth) / sum(t["htn_edges"] for t in truth), 4
    )
    assert all(b["ground_truth"]["flat_edges"] > b["ground_truth"]["htn_edges"] for b in metrics["bins"])
    for model in ("learned", "ground_truth", "all_orderings"):
        depth = metrics["models"][model]["depth"]
        assert 0 <= depth["min"] <= depth["mean"] <= depth["max"] <= 3
    # few orderings: every task is learned from all of them, which recovers the structure (invariant 3)
    assert metrics["all_orderings"] == {"limit": 5000, "qualified": 5, "recovered": 5}
    assert [r["all_orderings"]["flat_edges"] for r in results] == [t["flat_edges"] for t in truth]
    # the learned models admit the demonstrations, so they have some transitions; from four sampled paths
    # the general learner may nest chance runs deeper than the truth, never deeper than a binary tree
    for r in results:
        assert r["learned"]["flat_edges"] > 0 and r["learned"]["depth"] < r["subgoals"]


def test_summary_of_generated_tasks() -> None:
    results = [run_trial(trial) for trial in make_trials(5, 1)]
    assert [r["subgoals"] for r in results] == [10, 32, 55, 78, 100]
    assert [r["index"] for r in results] == list(range(5))
    assert all(r["demonstrations"] == 4 for r in results)
    metrics = summarize(results)
    assert sum(b["ground_truth"]["tasks"] for b in metrics["bins"]) == 5
    assert [b["label"] for b in metrics["bins"]] == ["10–19", "30–39", "50–59", "70–79", "90–100"]
    for model in ("ground_truth", "all_orderings"):  # complete hierarchies never need more edges
        summary = metrics["models"][model]
        assert summary["more_edges"] == 0 and summary["flat_per_htn"] >= 1
    for r in results:
        assert r["ground_truth"]["htn_edges"] <= r["ground_truth"]["flat_edges"]
        low, high = THESIS_DEPTH_RANGE  # the generator redraws tasks outside the thesis's range
        assert low <= r["ground_truth"]["depth"] <= high
        assert 0 <= r["learned"]["depth"] <= high
        assert r["ground_truth"]["roots"] == 1 and r["learned"]["roots"] >= 1
        if r["all_orderings"] is not None:
            assert r["all_orderings"]["recovered"]
            assert r["orderings"] <= 5000
    assert json.loads(json.dumps(metrics)) == metrics


def test_trial_is_reproducible_and_named_after_its_task() -> None:
    trial = make_trials(3, 9)[1]
    first, second = run_trial(trial), run_trial(trial)
    assert first == second
    assert first["task"].startswith("ikea-002-n55-s")


def test_measure_needs_structure_and_demonstrations() -> None:
    with pytest.raises(ExperimentError, match="ground-truth structure"):
        measure_task(TaskSpec("x", (), None, as_demonstrations([(("a", 1),)])))
    with pytest.raises(ExperimentError, match="demonstrations"):
        measure_task(TaskSpec("x", (), ActionNode("a"), ()))
    with pytest.raises(ExperimentError, match="no trial results"):
        summarize([])


def test_bins() -> None:
    assert bin_of(10, 100) == (10, 19) and bin_of(99, 100) == (90, 100) and bin_of(100, 100) == (90, 100)
    assert bin_of(5, 7) == (0, 9)


def test_report_and_plots(tmp_path: Path) -> None:
    result = run_experiment("edge-reduction", trials=3, seed=2, output=tmp_path, progress=False)
    report = (tmp_path / "report.md").read_text()
    for number in ("1.99", "3.61", "2.84", "76 tasks", "Figure 2.5", "dramatic reduction"):
        assert number in report
    # the counting rule, with the thesis's words
    for phrase in ("|E| = |V|^2 - |V|", "(|E| = 1)", "k − 1", "k² − k flat edges against k", "2 + 3 = 5"):
        assert phrase in report
    assert "order edges" not in report
    for label in (
        "(a) learned from the demonstrations",
        "(b) ground-truth structure",
        "(c) learned from all",
    ):
        assert label in report
    pngs = [path for path in result.files if path.suffix == ".png"]
    assert {p.name for p in pngs} == {"edges.png", "depth.png"}
    for png in pngs:
        assert png.read_bytes()[:8] == PNG_SIGNATURE and png.stat().st_size > 1000
    metrics = json.loads((tmp_path / "metrics.json").read_text())
    assert metrics["thesis"] == json.loads(json.dumps(get("edge-reduction").thesis))
    assert metrics["trials"] == 3 and len(metrics["tasks"]) == 3
    assert ("tasks, subgoals", "3, 10–100", "76, 10–100") in result.headline
    truth = metrics["models"]["ground_truth"]
    assert (
        "flat ÷ CC-HTN edges, (b) ground truth",
        f"{truth['flat_per_htn']:.2f}",
        "dramatic reduction (Fig. 2.5)",
    ) in (result.headline)
    assert "tree_links" not in truth and "order_edges" not in truth


def _metrics(bins: list[tuple[float, float]]) -> dict[str, object]:
    def sizes(flat: float, htn: float) -> dict[str, object]:
        return {
            "tasks": 1,
            "flat_edges": flat,
            "htn_edges": htn,
            "flat_per_htn": flat / htn,
            "fewer_edges": int(htn < flat),
            "more_edges": int(htn > flat),
        }

    entries = [
        {
            "label": f"{10 * i}–{10 * i + 9}",
            "learned": sizes(*b),
            "ground_truth": sizes(*b),
            "all_orderings": None,
        }
        for i, b in enumerate(bins, start=1)
    ]
    total = sizes(sum(f for f, _ in bins), sum(h for _, h in bins))
    total["tasks"] = len(bins)
    return {"models": {"learned": total, "ground_truth": total, "all_orderings": None}, "bins": entries}


def test_verdict_is_worded_from_the_numbers() -> None:
    growing = verdict(_metrics([(20, 10), (100, 20)]), "ground_truth")
    assert "as claimed" in growing and "not as claimed" not in growing and "constant factor" not in growing
    assert "from +10.0 (10–19 subgoals) to +80.0 (20–29)" in growing and "from 2.00 to 5.00" in growing
    constant = verdict(_metrics([(20, 10), (100, 50)]), "ground_truth")
    assert "as claimed — but by a roughly constant factor" in constant
    more = verdict(_metrics([(20, 25), (100, 50)]), "learned")
    assert "not as claimed (the CC-HTN needs more edges in 1 size bins)" in more
    flat_gap = verdict(_metrics([(20, 10), (15, 5)]), "ground_truth")
    assert flat_gap.endswith("the gap does not grow with size, so not as claimed.")
    assert verdict(_metrics([(20, 10)]), "all_orderings") == "(c) learned from all valid orderings: no task."
