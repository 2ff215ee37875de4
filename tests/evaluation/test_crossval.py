"""Cross-validation and the baselines: folds, the scores' arithmetic, and the CLI."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

import pytest

from supportive import examples
from supportive.evaluation import Bigram, MaskedBigram, MostFrequentNotDone, StepScores, evaluate_task, folds

CliRunner = Callable[[list[str]], tuple[int, str, str]]

DEMOS = [list("abcd"), list("acbd"), list("abcd"), list("acbd"), list("abcd")]


def test_folds_cover_every_demonstration_once() -> None:
    for k in (None, 2, 3, 10):
        parts = folds(7, k, seed=3)
        assert sorted(i for part in parts for i in part) == list(range(7))
    assert folds(7, 3, seed=3) == folds(7, 3, seed=3)  # same seed, same folds


def test_bigram_is_add_one_smoothed() -> None:
    model = Bigram().fit(DEMOS)
    after_a = model.next_step(["a"])
    assert after_a["b"] == pytest.approx((3 + 1) / (5 + 5)) and after_a["<end>"] == pytest.approx(1 / 10)
    assert sum(after_a.values()) == pytest.approx(1.0)


def test_masked_bigram_never_repeats_a_done_step_and_backs_off() -> None:
    model = MaskedBigram().fit(DEMOS)
    assert model.next_step(["a", "b"])["b"] == 0.0
    backed_off = model.next_step(["a", "d"])  # d -> <end> only, but b and c are still open
    assert backed_off["<end>"] == pytest.approx(1.0)
    assert MostFrequentNotDone().fit(DEMOS).next_step(list("abcd")) == {"a": 0, "b": 0, "c": 0, "d": 0, "<end>": 1.0}


def test_scores_add_up() -> None:
    scores = StepScores()
    scores.add({"a": 0.7, "b": 0.3}, "a", set())
    scores.add({"a": 0.7, "b": 0.3}, "b", {"a"})
    scores.add({"a": 1.0}, "c", set())
    rates = scores.as_dict()  # rounded to four places
    assert rates["top1"] == rates["zero"] == rates["done_top1"] == 0.3333 and rates["top3"] == 0.6667
    assert rates["log2"] == pytest.approx((-0.5146 - 1.737) / 2, abs=1e-3)


def test_the_progress_aware_predictor_beats_the_baselines_on_the_chair(cli: CliRunner) -> None:
    """`evaluate --json` (leave one out: the default for 6 demonstrations) and its other fold choices."""
    code, out, _ = cli(["evaluate", str(examples.path("ikea-chair")), "--json"])
    assert code == 0
    data = json.loads(out)
    assert data["folds"] == data["held_out"] == 6 and set(data["prediction"]) == {
        "progress-aware",
        "bigram",
        "masked bigram",
        "most frequent not done",
    }
    ours, masked, bigram = (data["prediction"][name] for name in ("progress-aware", "masked bigram", "bigram"))
    assert None not in (ours["top1"], ours["log2"], masked["top1"], bigram["top1"], bigram["log2"])
    assert ours["zero"] == 0.0 and ours["done_top1"] == 0.0
    assert _number(ours["top1"]) > _number(masked["top1"]) > _number(bigram["top1"])
    assert _number(ours["log2"]) > _number(bigram["log2"])
    assert data["recall"] is not None and data["precision"] == 1.0
    code, out, _ = cli(["evaluate", "ikea-chair", "--folds", "3"])
    assert code == 0 and "progress-aware" in out and "held-out demonstrations admitted" in out
    code, out, _ = cli(["evaluate", "ikea-chair", "--folds", "loo"])
    assert code == 0 and "leave one out, 6 folds" in out
    code, _, err = cli(["evaluate", "ikea-chair", "--folds", "one"])
    assert code == 2 and "--folds" in err and len(err.strip().splitlines()) == 1


def _number(value: object) -> float:
    assert isinstance(value, int | float)
    return float(value)


def test_evaluate_names_the_demonstrations_not_admitted() -> None:
    """Issue 26: `evaluate` said "3 of 4 admitted" without saying which one was not. Oracle: learn from the
    others, ask whether the held-out one is admitted."""
    from supportive.inference.predictor import StepPredictor

    spec = examples.load("blocks-tower")
    result = evaluate_task(spec)
    expected = []
    for i, held in enumerate(spec.demonstrations):
        rest = [d for j, d in enumerate(spec.demonstrations) if j != i]
        if not StepPredictor().fit(spec.with_demonstrations(rest)).learner_.htn_.admits(held.actions):
            expected.append(held.id)
    assert result.not_admitted == expected and len(expected) == result.held_out - result.admitted
    assert result.as_dict()["not_admitted"] == expected


def test_evaluate_cli_says_which_were_not_admitted(cli: CliRunner) -> None:
    code, out, _ = cli(["evaluate", "blocks-tower"])
    assert code == 0 and "3 of 4 held-out demonstrations admitted" in out
    assert "  not admitted when held out: d3\n" in out


@pytest.mark.parametrize(("copies", "said"), [(25, "leave one out, 50 folds"), (26, "10 folds, 10 folds")])
def test_evaluate_leaves_one_out_up_to_fifty_demonstrations_and_uses_ten_folds_above(
    cli: CliRunner, tmp_path: Path, copies: int, said: str
) -> None:
    """Issue 28: leave one out fits once per demonstration, so `evaluate` grew with their square (3,000: about
    17 minutes); above 50 demonstrations the default is ten folds (`--folds loo` still leaves one out)."""
    from dataclasses import replace

    from supportive.io.taskfile import dump_task

    spec = examples.load("knife-carrots-celery")
    assert len(spec.demonstrations) == 2
    demos = [replace(d, id=f"{d.id}-{i}") for i in range(copies) for d in spec.demonstrations]
    file = tmp_path / "many.yaml"
    file.write_text(dump_task(spec.with_demonstrations(demos), "yaml"))
    code, out, _ = cli(["evaluate", str(file)])
    assert code == 0 and f"{spec.name}: {said}" in out
