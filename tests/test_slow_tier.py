"""The slow tier's list (``SLOW`` in the root conftest.py) names modules and tests that exist: a module or test
renamed would otherwise leave the list silently and slow ``make test-fast`` down."""

from __future__ import annotations

import ast
import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _slow() -> dict[str, str]:
    spec = importlib.util.spec_from_file_location("root_conftest", ROOT / "conftest.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    slow: dict[str, str] = module.SLOW
    return slow


def test_every_slow_entry_names_a_test_module_or_a_test_in_one() -> None:
    missing = []
    for entry, why in _slow().items():
        path, _, name = entry.partition("::")
        file = ROOT / path
        assert why, entry
        if not (file.is_file() and file.name.startswith("test_")):
            missing.append(entry)
            continue
        tests = {n.name for n in ast.walk(ast.parse(file.read_text(encoding="utf-8"))) if isinstance(n, ast.FunctionDef)}
        if name and name not in tests:
            missing.append(entry)
    assert missing == []
