"""Checking for an optional dependency (an extra) before the work that needs it starts, so a missing one is
one line at once rather than a failure after minutes of computing."""

from __future__ import annotations

import importlib.util

from supportive.errors import MissingExtraError

__all__ = ["require_extra"]


def require_extra(feature: str, module: str, extra: str) -> None:
    """Raise at once when ``module`` (installed by the ``extra``) is missing.

    Raises:
        MissingExtraError: naming the feature, the module and the extra to install.

    >>> require_extra("drawing", "json", "none")
    >>> require_extra("drawing", "no_such_module_here", "plot")
    Traceback (most recent call last):
    ...
    supportive.errors.MissingExtraError: drawing needs no_such_module_here, which is not installed: pip install 'supportive[plot]'
    """
    try:
        found = importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):
        found = False
    if not found:
        raise MissingExtraError(feature, module, extra)
