"""The numbers the docs quote are the ones their commands and experiments give.

Every ``<!-- numbers:NAME -->`` block of README.md and docs/*.md must be what ``tools/docs_numbers.py`` (``make
docs-numbers``) writes now; the recorded results it reads (``docs/results/``) must be what their commands give
on a fresh run (those of seconds marked slow, those of a minute or more only under ``make docs-verify``;
CaptainCook4D where the dataset is, as in CI: ``../shared``).
"""

from __future__ import annotations

import importlib.util
import json
import os
import sys
from pathlib import Path
from types import ModuleType

import pytest

from docs_blocks import caregiver, runs
from docs_blocks.common import RESULTS, filled
from supportive.experiments import get, run_experiment
from supportive.experiments.output import dump_json

ROOT = Path(__file__).resolve().parents[1]


def _tool() -> ModuleType:
    spec = importlib.util.spec_from_file_location("docs_numbers", ROOT / "tools" / "docs_numbers.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


tool = _tool()
QUICK = sorted(n for n, b in tool.BLOCKS.items() if not b.runs_command)
COMMANDS = sorted(n for n, b in tool.BLOCKS.items() if b.runs_command)


def test_every_block_is_in_one_document() -> None:
    located = tool.where()
    assert sorted(located) == sorted(tool.BLOCKS)
    assert {p.name for p in located.values()} >= {"experiments.md", "exports.md", "learning.md", "support.md"}


@pytest.mark.parametrize("name", QUICK)
def test_a_block_from_recorded_results_is_up_to_date(name: str) -> None:
    assert tool.stale([name]) == [], f"{name}: run `make docs-numbers` ({tool.BLOCKS[name].source})"


@pytest.mark.slow
@pytest.mark.parametrize("name", COMMANDS)
def test_a_block_from_a_command_is_up_to_date(name: str) -> None:
    assert tool.stale([name]) == [], f"{name}: run `make docs-numbers` ({tool.BLOCKS[name].source})"


def test_a_changed_number_is_found_and_written_back(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    doc = tmp_path / "docs" / "x.md"
    doc.parent.mkdir()
    (tmp_path / "README.md").write_text("# r\n", encoding="utf-8")
    doc.write_text("a\n<!-- numbers:n -->\n0.939\n<!-- /numbers:n -->\nb\n", encoding="utf-8")
    monkeypatch.setattr(tool, "ROOT", tmp_path)
    monkeypatch.setattr(tool, "BLOCKS", {"n": tool.Block("test", lambda: "0.938\n")})
    assert tool.stale() == ["n"]
    assert tool.main(["--check"]) == 1
    assert tool.main([]) == 0
    assert doc.read_text(encoding="utf-8") == "a\n<!-- numbers:n -->\n0.938\n<!-- /numbers:n -->\nb\n"
    assert tool.stale() == []


@pytest.mark.parametrize(
    ("text", "problem"),
    [
        ("<!-- numbers:a -->\nx\n", "unmatched"),
        ("<!-- numbers:a -->\n<!-- /numbers:a -->\n<!-- numbers:a -->\n<!-- /numbers:a -->\n", "twice"),
    ],
)
def test_broken_markers_are_refused(text: str, problem: str) -> None:
    with pytest.raises(ValueError, match=problem):
        tool.block_names(text)


def test_a_block_no_generator_knows_is_refused(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "docs").mkdir()
    (tmp_path / "README.md").write_text("<!-- numbers:ghost -->\n<!-- /numbers:ghost -->\n", encoding="utf-8")
    monkeypatch.setattr(tool, "ROOT", tmp_path)
    with pytest.raises(ValueError, match="unknown numbers block 'ghost'"):
        tool.where()


def _recorded(name: str) -> object:
    return json.loads((RESULTS / name).read_text(encoding="utf-8"))


RECORDED = {
    "edge-reduction": "edge-reduction.json",
    "active-learning-blocks": "active-learning-blocks.json",
    "captaincook": "captaincook-curves.json",
    "goal-inference": "goal-inference.json",
    "transfer": "transfer.json",
    "caregiver": "caregiver.json",
    "captaincook-prediction": "captaincook-prediction.json",
    "active-learning": "active-learning.json",
    "support-tamp": "support-tamp.json",
    "generalisation": "generalisation.json",
    "learner-settings": "learner-settings.json",
    "mistake-detection": "mistake-detection.json",
    "selection-settings": "selection-settings.json",
}


@pytest.mark.parametrize(("experiment", "file"), sorted(RECORDED.items()))
def test_the_recorded_summary_holds_the_recorded_runs(experiment: str, file: str) -> None:
    """summary.json's findings of an experiment whose metrics.json is recorded are what the experiment finds in
    them (a cheap consistency check: the full run is compared by the slow tests below)."""
    metrics = _recorded(file)
    assert isinstance(metrics, dict)
    summary = _recorded("summary.json")
    assert isinstance(summary, dict)
    entry = next(e for e in summary["experiments"] if e["experiment"] == experiment)
    findings = get(experiment).findings
    assert findings is not None
    assert entry["findings"] == [f.as_json() for f in findings(metrics)]
    assert summary["trials"][experiment] == metrics["trials"] and summary["seed"] == metrics["seed"]


def test_the_recorded_summary_covers_every_experiment_from_its_recording() -> None:
    """summary.json has an entry for every experiment `reproduce all` runs, in its order, each one recorded."""
    from supportive.experiments import names

    summary = _recorded("summary.json")
    assert isinstance(summary, dict)
    assert [e["experiment"] for e in summary["experiments"]] == list(names()) == sorted(RECORDED)
    assert sorted(summary["trials"]) == sorted(RECORDED)


def test_the_recorded_run_times_belong_to_the_recorded_runs() -> None:
    """Each ``NAME-run.json`` the docs quote a wall time from is the ``run.json`` of the run recorded beside it."""
    for name in runs.TIMED:
        run, metrics = _recorded(f"{name}-run.json"), _recorded(RECORDED[name])
        assert isinstance(run, dict) and isinstance(metrics, dict)
        assert (run["experiment"], run["trials"], run["seed"]) == (name, metrics["trials"], metrics["seed"])
        assert run["seconds"] > 0


def test_the_learner_defaults_are_the_setting_the_recorded_run_chose() -> None:
    """docs/learning.md says the slip search's defaults were chosen by `reproduce learner-settings`: the recorded
    run's choice is what ``HTNLearner`` defaults to."""
    import inspect

    from supportive.learning import HTNLearner

    chosen = _recorded("learner-settings.json")
    assert isinstance(chosen, dict) and chosen["chosen"]
    parameters = inspect.signature(HTNLearner.__init__).parameters
    for part in chosen["chosen"].split():
        name, value = part.split("=")
        assert parameters[name].default == float(value), name


def test_the_selection_defaults_are_the_policy_the_recorded_run_chose() -> None:
    """docs/learning.md says when and with how many folds the default learner compares its readings, from how
    many demonstrations it makes subtasks, and its evidence level were chosen by `reproduce selection-settings`:
    the recorded run's choices are what ``HTNLearner`` defaults to."""
    import inspect

    from supportive.learning import HTNLearner

    metrics = _recorded("selection-settings.json")
    assert isinstance(metrics, dict) and metrics["chosen"]
    policy = metrics["policies"][metrics["chosen"]]
    parameters = inspect.signature(HTNLearner.__init__).parameters
    assert parameters["selection_folds"].default == policy["folds"]
    assert parameters["selection_demonstrations"].default == policy["demonstrations"]
    # and from how many demonstrations the general reading makes subtasks, and its evidence level, by the
    # sweeps of the same run
    assert parameters["subtask_demonstrations"].default == metrics["subtasks"]["chosen"]
    assert parameters["evidence"].default == metrics["evidence"]["chosen"]


def test_the_caregiver_prose_holds_on_the_recorded_run() -> None:
    """docs/caregiver.md: Eq. 3.2 over the whole trajectory helps the goal-directed novice the generated sentence
    names less than either shorter memory does (the *Deviation: memory* paragraph's claim)."""
    metrics = _recorded("caregiver.json")
    assert isinstance(metrics, dict)
    _, differ = caregiver.novice_groups(metrics)
    reductions = caregiver.reductions(metrics, differ[0])
    assert reductions["trajectory"] < min(reductions["memory"], reductions["per-step"])


_MINUTES = pytest.mark.skipif(
    not os.environ.get("SUPPORTIVE_DOCS_VERIFY"),
    reason="a run of a minute or more, left out of `make test`: `make docs-verify` runs it",
)
RECORDED_RUNS = [
    ("edge-reduction", RECORDED["edge-reduction"]),
    ("active-learning-blocks", RECORDED["active-learning-blocks"]),
    pytest.param("captaincook", RECORDED["captaincook"], marks=_MINUTES),
    pytest.param("goal-inference", RECORDED["goal-inference"], marks=_MINUTES),
    pytest.param("transfer", RECORDED["transfer"], marks=_MINUTES),
    pytest.param("caregiver", RECORDED["caregiver"], marks=_MINUTES),
    pytest.param("captaincook-prediction", RECORDED["captaincook-prediction"], marks=_MINUTES),
    pytest.param("mistake-detection", RECORDED["mistake-detection"], marks=_MINUTES),
    pytest.param("active-learning", RECORDED["active-learning"], marks=_MINUTES),
    pytest.param("support-tamp", RECORDED["support-tamp"], marks=_MINUTES),
    pytest.param("generalisation", RECORDED["generalisation"], marks=_MINUTES),
    pytest.param("learner-settings", RECORDED["learner-settings"], marks=_MINUTES),
    pytest.param("selection-settings", RECORDED["selection-settings"], marks=_MINUTES),
]


@pytest.mark.slow
@pytest.mark.parametrize(("experiment", "file"), RECORDED_RUNS)
def test_a_recorded_run_is_what_a_fresh_run_gives(experiment: str, file: str) -> None:
    """The recorded ``metrics.json`` is what a fresh full run writes, byte for byte (captaincook where the
    dataset is)."""
    recorded = (RESULTS / file).read_text(encoding="utf-8")
    metrics = json.loads(recorded)
    if experiment in ("captaincook", "captaincook-prediction", "mistake-detection", "generalisation"):
        _captaincook_or_skip()
    result = run_experiment(experiment, trials=metrics["trials"], seed=metrics["seed"], progress=False)
    assert dump_json(result.metrics) == recorded


def _captaincook_or_skip() -> None:
    from supportive.errors import DatasetError
    from supportive.io.captaincook import default_root

    try:
        default_root()
    except DatasetError as exc:
        pytest.skip(f"CaptainCook4D not here ({exc}); CI has it in ../shared")


def test_filling_a_template_scales_and_formats() -> None:
    data = {"a": {"b/c": 0.01234, "n": 1904.5}, "share": 0.03}
    assert filled("{a.b/c|ms:.1f} ms, {a.b/c|us:.0f} µs", data) == "12.3 ms, 12340 µs"
    assert filled("{a.n:,.0f} ops, {share|pct:.0f} %, {a.n|k:.1f}k", data) == "1,904 ops, 3 %, 1.9k"
    with pytest.raises(KeyError):
        filled("{a.missing}", data)


@pytest.mark.slow
def test_the_recorded_captaincook_scores_are_what_the_command_gives(request: pytest.FixtureRequest) -> None:
    _captaincook_or_skip()
    reports = request.getfixturevalue("captaincook_reports")  # the command's own report (shared with other tests)
    fresh = json.loads(json.dumps([r.as_dict() for r in reports]))
    assert fresh == _recorded("captaincook.json")


def _top(pairs: list[tuple[str, float]]) -> str:
    label, p = pairs[0]
    return f'[("{label}", {round(p, 2)}), ...]'


def test_the_python_examples_quote_what_they_print() -> None:
    """The values the README's and docs/inference.md's Python examples show in comments, from a fresh run."""
    from supportive.inference import HierarchicalHMM, ObservationModel, StepPredictor
    from supportive.io import parse_task_file
    from supportive.learning import HTNLearner

    spec = parse_task_file(ROOT / "examples" / "ikea-chair.yaml")
    after = StepPredictor().fit(spec).next_step(["get_left_frame", "place_left_frame"])
    best = min(after, key=lambda a: (-after[a], a))  # ties by name
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert f'# {{"{best}": {round(after[best], 2)}, …, "<end>": {round(after["<end>"], 3)}}}' in readme

    learner = HTNLearner().fit(spec)
    model = HierarchicalHMM(learner.htn_, ObservationModel.from_spec(spec), mean_duration=4).fit()
    running = model.filter()
    belief = running.update({"hand-peg", "peg-left_frame"})
    inference = (ROOT / "docs" / "inference.md").read_text(encoding="utf-8")
    assert f"# {_top(running.top(belief.subgoals, running.subgoal_labels))}" in inference
    assert f"# {_top(running.top(belief.enclosing, running.enclosing_labels))}" in inference


def test_the_social_example_quotes_what_it_prints() -> None:
    """docs/social.md's example, run as written: the peer's reason and the student's choice it quotes."""
    text = (ROOT / "docs" / "social.md").read_text(encoding="utf-8")
    start = text.index("```python\nfrom supportive import examples")
    block = text[start + len("```python\n") : text.index("```", start + 3)]
    namespace: dict[str, object] = {}
    exec(compile(block, "docs/social.md", "exec"), namespace)
    decision = eval("PeerPolicy(switch_margin=0.2, halt_below=-0.5, seed=0).decide(mine, people)", namespace)
    chosen = eval("StudentPolicy(min_force=0.2, seed=0).decide(free, people).subtask", namespace)
    comments = " ".join(line.lstrip("# ").strip() for line in block.splitlines() if line.startswith("#"))
    assert f'reason="{decision.reason}")' in comments
    assert f"subtask='{decision.subtask}'" in comments
    assert f"# {chosen!r}" in block
