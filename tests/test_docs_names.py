"""Every dotted ``supportive.…`` name the README and docs/ quote in backticks is one a user can import or reach:
docs/inference.md once named ``supportive.inference.MistakeDetector`` and ``supportive.evaluation.evaluate_mistakes``,
which only their modules had. And docs/architecture.md's table of what each package exports is its ``__all__``."""

from __future__ import annotations

import importlib
import re
from pathlib import Path
from types import ModuleType

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
QUOTED = re.compile(r"`(supportive(?:\.[A-Za-z_]\w*)+)(?:\(|`)")


def quoted_names() -> list[tuple[str, str]]:
    """``(page, name)`` for every dotted name quoted in backticks (alone, or as a call)."""
    found = {(page.name, m.group(1)) for page in PAGES for m in QUOTED.finditer(page.read_text(encoding="utf-8"))}
    return sorted(found)


def resolve(name: str) -> object:
    """The object ``name`` names: its longest importable module prefix, then attributes.

    Raises:
        AttributeError: when an attribute is missing.
    """
    parts = name.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            found: object = importlib.import_module(".".join(parts[:cut]))
        except ModuleNotFoundError:
            continue
        for attribute in parts[cut:]:
            found = getattr(found, attribute)
        return found
    raise AttributeError(name)


def test_the_pages_quote_names() -> None:
    names = quoted_names()
    assert len(names) > 50 and ("inference.md", "supportive.inference.MistakeDetector") in names


@pytest.mark.parametrize(("page", "name"), quoted_names())
def test_a_quoted_name_resolves(page: str, name: str) -> None:
    found = resolve(name)
    assert found is not None
    if not isinstance(found, ModuleType) and "." in name.removeprefix("supportive."):
        assert getattr(found, "__module__", "supportive").startswith("supportive"), f"{page}: {name} is not ours"


def test_a_name_that_is_not_there_does_not_resolve() -> None:
    with pytest.raises(AttributeError):
        resolve("supportive.inference.NoSuchDetector")


ARCHITECTURE = ROOT / "docs" / "architecture.md"
LISTED = re.compile(r"^\| `(supportive[\w.]*)` \| ((?:`\w+`(?:, )?)+) \|$", re.M)


def listed_exports() -> list[tuple[str, frozenset[str]]]:
    """docs/architecture.md's public-API table: each package whose row is a plain list of names, and the names."""
    text = ARCHITECTURE.read_text(encoding="utf-8")
    return [(m.group(1), frozenset(re.findall(r"`(\w+)`", m.group(2)))) for m in LISTED.finditer(text)]


def test_the_api_table_lists_packages() -> None:
    assert len(listed_exports()) > 15


@pytest.mark.parametrize(("package", "names"), listed_exports(), ids=[p for p, _ in listed_exports()])
def test_the_api_table_lists_what_each_package_exports(package: str, names: frozenset[str]) -> None:
    """docs/architecture.md once left out what later issues exported (the detector, the known-task generators)."""
    assert names == frozenset(importlib.import_module(package).__all__)
