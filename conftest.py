"""The whole suite's rules, for ``tests/`` and the doctests in ``src/`` alike.

* The doctests (``--doctest-modules`` over ``src``) run from an empty folder and must leave it empty: they name
  bundled files through ``supportive.examples``, never by a path relative to the repository, and write nothing
  where they run (issue 17). Checked in the suite's own run of the doctests, not by running them twice.
* The ``slow`` tier: besides the tests marked ``@pytest.mark.slow`` where they are, every test of the modules
  in :data:`SLOW` (and the single tests named there) is marked slow here, in one list. ``make test`` runs
  every test, the slow ones first (so that the longest do not run alone at the end on one core), with
  ``--dist worksteal`` (an idle worker takes queued tests from a busy one);
  ``make test-fast`` (``-m "not slow"``) leaves them out for the edit-test loop.
"""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from pathlib import Path

import pytest
from _pytest.doctest import DoctestItem

SLOW = {
    # real processes, browsers, databases or whole experiment runs: seconds to minutes each
    "tests/cli/test_interrupt.py": "a real `supportive` process per test, sent a signal while it works",
    "tests/cli/test_cli_output.py": "every command's output at several terminal widths",
    "tests/test_missing_extras.py": "a fresh interpreter per command, its extra refused",
    "tests/test_new_user.py": "every README command",
    "tests/service/test_browser.py": "chromium against a running board",
    "tests/service/test_lab_screen.py": "chromium against a running board",
    "tests/service/test_faults.py": "ten thousand operations; servers killed and restarted",
    "tests/service/test_hardening.py": "a real `supportive serve` process per test, some under load or stopped",
    "tests/service/test_board_client.py": "the example client against a real `supportive serve`",
    "tests/fuzz/test_schemathesis.py": "the HTTP API fuzzed from its schema against a running server",
    "tests/experiments/test_reproduce_cli.py": "`reproduce all`: every experiment",
    "tests/experiments/test_active_learning.py": "whole experiment runs",
    "tests/experiments/test_support_tamp.py": "whole experiment runs",
    "tests/experiments/test_goal_inference.py": "whole experiment runs, one on a local Dask cluster",
    "tests/experiments/test_execution.py": "experiment runs on local Dask clusters",
    "tests/experiments/test_caregiver_experiment.py": "whole experiment runs",
    "tests/experiments/test_docs_numbers.py": "fresh runs of the experiments the docs quote",
    "tests/language/test_embeddings.py": "loads a sentence-embedding model (torch)",
    "tests/io/test_safe_load.py::test_the_largest_benchmark_task_passes_the_limits": "the largest benchmark task",
    "tests/envs/tabletop/test_world_and_team.py::test_prohibited_operators_are_never_chosen": "many team runs",
    "tests/fuzz/test_fuzz.py::test_malformed_observation_streams_get_one_line": "a command per generated stream",
    "tests/fuzz/test_fuzz_inputs.py::test_an_output_that_is_an_input_or_inside_one_is_refused": "a command per output placed in an input",
    "tests/fuzz/test_fuzz_commands.py::test_output_paths_that_are_folders_or_have_no_suffix_keep_the_promise": "a command per output path",
    "tests/service/test_tokens.py::test_restarts_keep_every_token_shown_and_a_revoked_one_is_refused_at_once": "a server started three times",
    "tests/service/test_reconcile.py::test_a_subtask_made_lead_only_at_a_restart_is_refused_to_an_assistant": "servers restarted",
    "tests/service/test_reconcile.py::test_a_robot_demoted_by_the_command_line_loses_its_role_its_old_token_and_its_claims": "servers restarted",
}
"""Test modules (``path``) and single tests (``path::function``) of the ``slow`` tier, with why."""

ROOT = Path(__file__).resolve().parent


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Mark the tests :data:`SLOW` names ``slow``, and run every slow test first: with pytest-xdist the long
    ones then start while the short ones fill the other workers, instead of one long test running alone at
    the end (the order is otherwise kept, so a module's tests stay together)."""
    for item in items:
        path = Path(item.path).resolve()
        if not path.is_relative_to(ROOT):
            continue
        module = path.relative_to(ROOT).as_posix()
        if module in SLOW or f"{module}::{getattr(item, 'originalname', item.name)}" in SLOW:
            item.add_marker(pytest.mark.slow)
    items.sort(key=lambda item: item.get_closest_marker("slow") is None)


@pytest.fixture(scope="session")
def _empty_folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("doctests-run-here")


@pytest.fixture(autouse=True)
def _doctests_run_elsewhere(request: pytest.FixtureRequest, _empty_folder: Path) -> Iterator[None]:
    if not isinstance(request.node, DoctestItem):
        yield
        return
    with pytest.MonkeyPatch.context() as patch:
        patch.chdir(_empty_folder)
        yield
    left = sorted(_empty_folder.iterdir())
    for path in left:  # cleared for the next doctest before this one fails
        shutil.rmtree(path) if path.is_dir() else path.unlink()
    assert left == [], f"{request.node.name} wrote {[p.name for p in left]} where it ran"
