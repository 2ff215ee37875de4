"""The layers of docs/architecture.md hold: import-linter's contract (pyproject.toml) is kept by the code, and
it breaks when a lower layer imports a higher one (checked on a copy of the package with one such import)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
LINT_IMPORTS = Path(sys.executable).with_name("lint-imports")


def _lint(config: Path, package_parent: Path, cwd: Path) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(package_parent)}
    return subprocess.run(
        [str(LINT_IMPORTS), "--no-cache", str(config)], cwd=cwd, env=env, capture_output=True, text=True, timeout=300
    )


def test_the_code_keeps_the_layers() -> None:
    result = _lint(ROOT / "pyproject.toml", ROOT / "src", ROOT)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "0 broken" in result.stdout


@pytest.mark.parametrize(
    ("module", "upward"),
    [
        ("safety/caregiver.py", "supportive.envs.household.gym_env"),  # the cycle issue 17 found
        ("tasks/htn.py", "supportive.learning.learner"),
        ("inference/hmm.py", "supportive.cli"),
        ("learning/general/noise.py", "supportive.learning.strict.compaction"),  # the wings are independent
    ],
)
def test_an_upward_import_breaks_the_contract(tmp_path: Path, module: str, upward: str) -> None:
    shutil.copytree(ROOT / "src" / "supportive", tmp_path / "supportive", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    with (tmp_path / "supportive" / module).open("a", encoding="utf-8") as file:
        file.write(f"\nimport {upward}  # noqa: E402\n")
    result = _lint(tmp_path / "pyproject.toml", tmp_path, tmp_path)
    assert result.returncode == 1, result.stdout + result.stderr
    assert "BROKEN" in result.stdout and upward in result.stdout
