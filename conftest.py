"""The doctests (``--doctest-modules`` over ``src``) run from an empty folder and must leave it empty: they name
bundled files through ``supportive.examples``, never by a path relative to the repository, and write nothing
where they run (issue 17). Checked in the suite's own run of the doctests, not by running them twice."""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from pathlib import Path

import pytest
from _pytest.doctest import DoctestItem


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
