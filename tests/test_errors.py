"""One error hierarchy (issue 17): every exception class is defined in supportive.errors under
SupportiveError, and library code raises no bare built-in exception a user's input can reach."""

from __future__ import annotations

import ast
import inspect
from pathlib import Path

import pytest

import supportive.errors as errors

SRC = Path(errors.__file__).resolve().parent
STANDALONE = {SRC / "examples" / "ros" / "board_client.py"}  # a script to copy into a ROS node: stdlib only
BARE = {"ValueError", "KeyError", "LookupError", "IndexError", "Exception"}
"""Built-ins library code may not raise itself (RuntimeError and TypeError stay for a caller's programming
mistakes and internal failures: a call with an unknown keyword, a solver that gives up)."""


def _modules() -> list[Path]:
    return sorted(p for p in SRC.rglob("*.py") if p not in STANDALONE)


def _raised(tree: ast.AST) -> list[tuple[int, str]]:
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Raise) and node.exc is not None:
            target = node.exc.func if isinstance(node.exc, ast.Call) else node.exc
            if isinstance(target, ast.Name) and target.id in BARE:
                found.append((node.lineno, target.id))
    return found


def test_library_code_raises_no_bare_built_in_error() -> None:
    found = [f"{p.relative_to(SRC)}:{line}: {name}" for p in _modules() for line, name in _raised(ast.parse(p.read_text()))]
    assert found == []


def test_every_exception_class_is_in_errors_py() -> None:
    outside = []
    for path in _modules():
        if path == SRC / "errors.py":
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ClassDef) and not node.name.startswith("_"):
                bases = {b.id for b in node.bases if isinstance(b, ast.Name)} | {
                    b.attr for b in node.bases if isinstance(b, ast.Attribute)
                }
                if any(base.endswith(("Error", "Exception")) for base in bases):
                    outside.append(f"{path.relative_to(SRC)}: {node.name}")
    assert outside == []


def _classes() -> list[type[BaseException]]:
    return [
        obj
        for _, obj in inspect.getmembers(errors, inspect.isclass)
        if issubclass(obj, BaseException) and obj.__module__ == errors.__name__
    ]


@pytest.mark.parametrize("cls", _classes(), ids=lambda c: c.__name__)
def test_every_error_is_a_supportive_error_and_exported(cls: type[BaseException]) -> None:
    assert issubclass(cls, errors.SupportiveError)
    assert cls.__name__ in errors.__all__
    assert cls.__doc__


def test_naming_puts_the_file_first_and_keeps_the_class() -> None:
    error = errors.naming(errors.UnknownNameError("no subtask named 'x'"), "task.yaml")
    assert isinstance(error, errors.UnknownNameError) and isinstance(error, KeyError)
    assert str(error) == "task.yaml: no subtask named 'x'"
