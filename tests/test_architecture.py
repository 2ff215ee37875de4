"""The architecture holds: import-linter's contracts (pyproject.toml) are kept by the code, and each one breaks
when a copy of the package is given one import it forbids; no two files import each other, no import runs from
a lower layer to a higher one (read from every import statement, function-level ones included); and
docs/architecture.md's generated part is what tools/architecture.py draws from the imports now."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

import architecture

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"
PYPROJECT = ROOT / "pyproject.toml"
LINT_IMPORTS = Path(sys.executable).with_name("lint-imports")
PACKAGES = sorted({architecture.package_of(m) for m in architecture.modules(SRC)} - {"supportive"})


@pytest.fixture(scope="module")
def found() -> list[architecture.Import]:
    """Every import in the package, read once for the module's tests."""
    return architecture.imports(SRC)


def _lint(config: Path, package_parent: Path, cwd: Path) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(package_parent), "COLUMNS": "200"}
    return subprocess.run(
        [str(LINT_IMPORTS), "--no-cache", str(config)],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )


def _contracts() -> dict[str, dict[str, object]]:
    return {str(c["id"]): c for c in architecture.contracts(PYPROJECT)}


def test_the_code_keeps_every_contract() -> None:
    result = _lint(PYPROJECT, SRC, ROOT)
    assert result.returncode == 0, result.stdout + result.stderr
    assert f"Contracts: {len(_contracts())} kept, 0 broken." in result.stdout


@dataclass(frozen=True)
class Plant:
    """One forbidden import put into a module of the copy: at module level, or inside a function."""

    module: str
    imported: str
    in_function: bool = False

    def text(self) -> str:
        if self.in_function:
            return f"\n\ndef _planted() -> None:\n    import {self.imported}  # noqa: F401\n"
        return f"\nimport {self.imported}  # noqa: E402, F401\n"


# Every contract, broken once: the import each line plants is one the layers alone would allow where it says so.
PLANTED = [
    ("layers", Plant("safety/caregiver.py", "supportive.envs.household.gym_env")),  # the cycle issue 17 found
    ("layers", Plant("tasks/htn.py", "supportive.learning.learner", in_function=True)),
    ("layers", Plant("inference/hmm.py", "supportive.cli")),
    ("layers", Plant("examples/__init__.py", "supportive.inference.observations", in_function=True)),
    ("domains", Plant("language/fluency.py", "supportive.social.force")),  # language is above social
    ("domains", Plant("evaluation/findings.py", "supportive.safety.priors", in_function=True)),
    ("envs", Plant("envs/tabletop/geometry.py", "supportive.envs.circuits.board")),
    ("envs", Plant("envs/workshop/chair.py", "supportive.envs.household.encoding", in_function=True)),
    ("planning", Plant("planning/weighting.py", "supportive.tasks.htn")),  # tasks is below planning's line
    ("planning", Plant("planning/world.py", "supportive.extras", in_function=True)),
    ("model", Plant("tasks/spec.py", "supportive.estimator")),  # estimator is below tasks's line
    ("drawing", Plant("learning/learner.py", "rich.console", in_function=True)),
    ("drawing", Plant("service/app.py", "matplotlib.pyplot")),
    ("web", Plant("inference/hmm.py", "fastapi")),
    ("web", Plant("io/atomic.py", "sqlalchemy", in_function=True)),
    ("command", Plant("io/taskfile.py", "typer", in_function=True)),
    ("rl", Plant("safety/caregiver.py", "gymnasium")),
    ("rl", Plant("render/household.py", "pettingzoo", in_function=True)),
    ("learning-wings", Plant("learning/general/noise.py", "supportive.learning.strict.compaction")),
]


@pytest.fixture(scope="module")
def copy(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """One copy of the package and its configuration for the whole module; each test plants into it and takes
    its import out again."""
    parent = tmp_path_factory.mktemp("package")
    shutil.copytree(SRC / "supportive", parent / "supportive", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(PYPROJECT, parent / "pyproject.toml")
    return parent


@pytest.fixture
def planted(copy: Path, request: pytest.FixtureRequest) -> Iterator[Path]:
    """The copy with ``request.param`` (a :class:`Plant`) in it, for the duration of one test."""
    plant: Plant = request.param
    file = copy / "supportive" / plant.module
    original = file.read_text(encoding="utf-8")
    file.write_text(original + plant.text(), encoding="utf-8")
    try:
        yield copy
    finally:
        file.write_text(original, encoding="utf-8")


@pytest.mark.slow  # one lint-imports run each (about a second): the whole suite runs them, test-fast does not
@pytest.mark.parametrize(
    ("contract", "planted"),
    PLANTED,
    indirect=["planted"],
    ids=[f"{c}:{p.module}->{p.imported}" for c, p in PLANTED],
)
def test_a_forbidden_import_breaks_its_contract(contract: str, planted: Path) -> None:
    result = _lint(planted / "pyproject.toml", planted, planted)
    assert result.returncode == 1, result.stdout + result.stderr
    name = _contracts()[contract]["name"]
    assert f"{name} BROKEN" in result.stdout, result.stdout


def test_every_contract_is_broken_by_some_plant() -> None:
    assert {contract for contract, _ in PLANTED} == set(_contracts())


# What each whitelist contract lets its packages import, and where each third-party package may be imported:
# the contract must name every other package, so that a new package is forbidden too until someone decides.
MAY_IMPORT = {
    "planning": {"planning", "errors", "estimator", "seeding"},
    "model": {"tasks", "errors", "seeding"},
}
CONFINED_TO = {
    "drawing": {"render", "cli", "experiments"},
    "web": {"service"},
    "command": {"cli"},
    "rl": {"envs"},
}


def _short(names: object) -> set[str]:
    assert isinstance(names, list)
    return {name.removeprefix("supportive.") for name in names}


@pytest.mark.parametrize("contract", sorted(MAY_IMPORT))
def test_a_whitelist_forbids_every_other_package(contract: str) -> None:
    forbidden = _short(_contracts()[contract]["forbidden_modules"])
    assert forbidden == set(PACKAGES) - MAY_IMPORT[contract]


@pytest.mark.parametrize("contract", sorted(CONFINED_TO))
def test_a_third_party_package_is_forbidden_everywhere_else(contract: str) -> None:
    sources = _short(_contracts()[contract]["source_modules"])
    assert sources == set(PACKAGES) - CONFINED_TO[contract]


def test_no_two_files_import_each_other(found: list[architecture.Import]) -> None:
    assert architecture.cycles(architecture.module_graph(found)) == []


@pytest.mark.parametrize(
    "planted",
    [Plant("tasks/spec.py", "supportive.io.taskfile", in_function=True)],  # io.taskfile imports tasks.spec
    indirect=True,
)
def test_a_circle_through_a_function_level_import_is_found(planted: Path) -> None:
    circles = architecture.cycles(architecture.module_graph(architecture.imports(planted)))
    assert any({"supportive.tasks.spec", "supportive.io.taskfile"} <= set(group) for group in circles), (
        circles
    )


def test_no_import_runs_from_a_lower_layer_to_a_higher_one(found: list[architecture.Import]) -> None:
    assert architecture.upward_imports(found, PYPROJECT) == []


@pytest.mark.parametrize(
    "planted",
    [Plant("inference/hmm.py", "supportive.language.fluency", in_function=True)],
    indirect=True,
)
def test_an_upward_function_level_import_is_found(planted: Path) -> None:
    upward = architecture.upward_imports(architecture.imports(planted), planted / "pyproject.toml")
    assert [(i.importer, i.imported) for i in upward] == [
        ("supportive.inference.hmm", "supportive.language.fluency")
    ]


def test_the_architecture_doc_is_drawn_from_the_imports(found: list[architecture.Import]) -> None:
    document = (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")
    assert architecture.updated(document, architecture.render(SRC, PYPROJECT, found)) == document, (
        "docs/architecture.md's generated part is out of date: run `make architecture`"
    )


def test_the_table_lists_every_import_between_packages(found: list[architecture.Import]) -> None:
    drawn = architecture.render(SRC, PYPROJECT, found)
    rows = {
        line.split("|")[1].strip(" `"): line.split("|")
        for line in drawn.splitlines()
        if line.startswith("| `")
    }
    assert sorted(rows) == PACKAGES
    graph = architecture.package_graph(SRC, found)
    assert graph.has_edge("inference", "learning") and not graph.has_edge("learning", "inference")
    for importer, imported in graph.edges:
        assert f"`{imported}`" in rows[importer][3] and f"`{importer}`" in rows[imported][4]
