"""Every dotted ``supportive.…`` name the README and docs/ quote in backticks is one a user can import or reach:
docs/inference.md once named ``supportive.inference.MistakeDetector`` and ``supportive.evaluation.evaluate_mistakes``,
which only their modules had."""

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
