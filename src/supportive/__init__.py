"""supportive: supportive behaviors for human-robot teaming.

Learn Clique/Chain HTNs from a few demonstrations (thesis §2.1) and build on them.

>>> from supportive import HTNLearner
>>> HTNLearner(mode="strict").fit([["knife", "carrots", "celery"], ["knife", "celery", "carrots"]]).htn_.complete
True

The names below are imported when first used (PEP 562), so ``import supportive`` (and the ``supportive``
command's start, before it can handle Ctrl-C) costs the error classes only.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from supportive.errors import SupportiveError, TaskFileError

if TYPE_CHECKING:
    from supportive.learning import HTNLearner, conjugate_task_graph, learn
    from supportive.tasks import (
        HTN,
        ActionNode,
        ChainNode,
        CliqueNode,
        Demonstration,
        TaskGraph,
        TaskSpec,
    )

__version__ = "0.1.0"

__all__ = [
    "HTN",
    "ActionNode",
    "ChainNode",
    "CliqueNode",
    "Demonstration",
    "HTNLearner",
    "SupportiveError",
    "TaskFileError",
    "TaskGraph",
    "TaskSpec",
    "__version__",
    "conjugate_task_graph",
    "learn",
]

_HOMES = {
    **dict.fromkeys(("HTNLearner", "conjugate_task_graph", "learn"), "supportive.learning"),
    **dict.fromkeys(
        ("HTN", "ActionNode", "ChainNode", "CliqueNode", "Demonstration", "TaskGraph", "TaskSpec"), "supportive.tasks"
    ),
}


def __getattr__(name: str) -> Any:
    """A public name, imported from its package on first use."""
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module 'supportive' has no attribute {name!r}")
    value = getattr(importlib.import_module(home), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
