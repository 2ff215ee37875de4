"""Write the numbers the docs quote from the commands and experiments that produce them.

A generated passage sits between ``<!-- numbers:NAME -->`` and ``<!-- /numbers:NAME -->`` in docs/*.md or
README.md; :data:`BLOCKS` says how each one is made: from a file of recorded results in ``docs/results/``
(the output of a run too long for ``make test``; ``make docs-results`` runs them again and rewrites the files),
from ``benchmarks/results/`` (``make bench``) or by running a quick command.

    python tools/docs_numbers.py            # rewrite every block (make docs-numbers)
    python tools/docs_numbers.py --check    # exit 1 naming every block that would change (the tests run this)

Numbers quoted outside a block are checked against a fresh small run by a test instead (the ``small-runs``
table of docs/experiments.md: tests/experiments/test_docs_numbers.py; the others: tests/test_docs_numbers.py).
"""

from __future__ import annotations

import re
import sys
from collections.abc import Mapping
from pathlib import Path

from docs_blocks import (
    active_learning,
    benchmarks,
    captaincook,
    caregiver,
    commands,
    edge_reduction,
    goal_inference,
    learning,
    runs,
    summary,
    support_tamp,
    transfer,
)
from docs_blocks.common import ROOT, Block

_BLOCK = re.compile(r"<!-- numbers:(?P<name>[a-z0-9-]+) -->(?P<body>.*?)<!-- /numbers:(?P=name) -->", re.S)
_OPEN = re.compile(r"<!-- /?numbers:(?P<name>[^ ]*) -->")


def _assembled(*parts: Mapping[str, Block]) -> dict[str, Block]:
    """The blocks of every module, each name once.

    Raises:
        ValueError: for a name two modules make.
    """
    blocks: dict[str, Block] = {}
    for part in parts:
        twice = sorted(set(blocks) & set(part))
        if twice:
            raise ValueError(f"numbers blocks made twice: {twice}")
        blocks.update(part)
    return blocks


BLOCKS = _assembled(
    captaincook.BLOCKS,
    benchmarks.BLOCKS,
    summary.BLOCKS,
    edge_reduction.BLOCKS,
    goal_inference.BLOCKS,
    caregiver.BLOCKS,
    transfer.BLOCKS,
    active_learning.BLOCKS,
    support_tamp.BLOCKS,
    learning.BLOCKS,
    runs.BLOCKS,
    commands.BLOCKS,
)
"""Every block the documents hold, by name: how each is made (``docs_blocks``, one module per source)."""


def documents() -> list[Path]:
    """The files that may hold generated blocks: README.md and docs/*.md."""
    return [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def block_names(text: str) -> list[str]:
    """The names of the blocks in ``text``, in order.

    Raises:
        ValueError: for a marker without its partner or a name used twice.
    """
    names = [m.group("name") for m in _BLOCK.finditer(text)]
    markers = [m.group("name") for m in _OPEN.finditer(text)]
    if len(markers) != 2 * len(names):
        raise ValueError(f"unmatched numbers markers: {sorted(set(markers) - set(names)) or markers}")
    if len(set(names)) != len(names):
        raise ValueError(f"a block name used twice: {names}")
    return names


def render(text: str, made: Mapping[str, str]) -> str:
    """``text`` with every block's body replaced by ``made[name]``."""
    return _BLOCK.sub(
        lambda m: f"<!-- numbers:{m['name']} -->{made[m['name']]}<!-- /numbers:{m['name']} -->", text
    )


def where() -> dict[str, Path]:
    """Each block's name and the document it is in.

    Raises:
        ValueError: for a block :data:`BLOCKS` does not know, one in two documents, or one in none.
    """
    found: dict[str, Path] = {}
    for path in documents():
        for name in block_names(path.read_text(encoding="utf-8")):
            if name not in BLOCKS:
                raise ValueError(f"{path.relative_to(ROOT)}: unknown numbers block {name!r}")
            if name in found:
                raise ValueError(f"numbers block {name!r} in {found[name].name} and {path.name}")
            found[name] = path
    missing = sorted(set(BLOCKS) - set(found))
    if missing:
        raise ValueError(f"numbers blocks in no document: {missing}")
    return found


def stale(names: list[str] | None = None) -> list[str]:
    """The blocks (all, or ``names``) whose text differs from what they would be made from now."""
    located = where()
    chosen = sorted(located) if names is None else names
    return [n for n in chosen if _current(located[n], n) != BLOCKS[n].body()]


def write_all() -> list[Path]:
    """Rewrite every block; the documents that changed."""
    located = where()
    made = {name: block.body() for name, block in BLOCKS.items()}
    changed = []
    for path in sorted(set(located.values())):
        text = path.read_text(encoding="utf-8")
        new = render(text, made)
        if new != text:
            path.write_text(new, encoding="utf-8")
            changed.append(path)
    return changed


def _current(path: Path, name: str) -> str:
    for match in _BLOCK.finditer(path.read_text(encoding="utf-8")):
        if match["name"] == name:
            return match["body"]
    raise ValueError(f"{path.name}: no block {name!r}")


def main(argv: list[str]) -> int:
    """``--check``: 1 and the stale blocks' names when any would change, else 0; no argument: rewrite them."""
    if argv == ["--check"]:
        names = stale()
        for name in names:
            print(f"docs numbers out of date: {name} ({BLOCKS[name].source}); run `make docs-numbers`")
        return 1 if names else 0
    if argv:
        print("usage: python tools/docs_numbers.py [--check]", file=sys.stderr)
        return 2
    for path in write_all():
        print(f"rewrote {path.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
