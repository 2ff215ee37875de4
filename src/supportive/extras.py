"""Which extra installs a missing optional dependency, read from the installed package's own metadata (the
``[project.optional-dependencies]`` of pyproject.toml), so the answer never drifts from what pip installs.

The command line turns a ``ModuleNotFoundError`` for one of them into one line naming the extra
(``serve needs sqlalchemy, which is not installed: pip install 'supportive[server]'``) wherever
the import happens; a module no extra provides is a real bug and keeps its traceback.
"""

from __future__ import annotations

import re
from functools import cache
from importlib.metadata import PackageNotFoundError, requires

__all__ = ["extra_of", "missing_extra"]

_REQUIREMENT = re.compile(r"^\s*([A-Za-z0-9._-]+)\s*(?:\[([^\]]*)\])?[^;]*;.*extra\s*==\s*['\"]([^'\"]+)['\"]")
_MODULES = {"scikit-learn": ("sklearn",), "psycopg": ("psycopg", "psycopg_binary")}
"""Distributions whose importable module is not their name with '-' as '_'."""
_PROVIDED = {("dask", "distributed"): ("distributed",)}
"""Modules a distribution's own extra brings (``dask[distributed]`` installs ``distributed``)."""
_NOT_FOR_COMMANDS = frozenset({"dev", "bench"})
"""Extras the commands never need (tests and benchmarks)."""


@cache
def _extras() -> dict[str, str]:
    """Top-level module → the first extra (in pyproject order) that installs it."""
    try:
        lines = requires("supportive") or []
    except PackageNotFoundError:
        return {}
    found: dict[str, str] = {}
    for line in lines:
        match = _REQUIREMENT.match(line)
        if match is None or match.group(3) in _NOT_FOR_COMMANDS:
            continue
        name, wanted, extra = match.group(1).lower(), match.group(2) or "", match.group(3)
        modules = list(_MODULES.get(name, (name.replace("-", "_").replace(".", "_"),)))
        for part in (w.strip() for w in wanted.split(",") if w.strip()):
            modules += _PROVIDED.get((name, part), ())
        for module in modules:
            found.setdefault(module, extra)
    return found


def extra_of(module: str) -> str | None:
    """The extra that installs a module (or a submodule of it), or None when no extra does.

    >>> extra_of("sqlalchemy.orm"), extra_of("matplotlib"), extra_of("numpy")
    ('server', 'plot', None)
    """
    return _extras().get(module.split(".")[0])


def missing_extra(error: ModuleNotFoundError, command: str) -> str | None:
    """The one line for a command that failed for want of an optional dependency; None when the missing
    module is no extra's."""
    module = error.name or ""
    extra = extra_of(module)
    if extra is None:
        return None
    top = module.split(".")[0]
    return f"{command} needs {top}, which is not installed: pip install 'supportive[{extra}]'"
