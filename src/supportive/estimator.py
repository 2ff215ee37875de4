"""The estimator contract every learning class keeps (docs/architecture.md), after scikit-learn and hmmlearn:

* ``__init__`` takes the settings, checks them and stores each under its own name, unchanged; it learns
  nothing and sets no attribute ending in ``_``;
* ``fit(data)`` learns every attribute ending in ``_`` afresh (a refit forgets earlier fits) and returns
  ``self``; ``partial_fit``, where there is one, adds to what was learned;
* asking an unfitted estimator for what ``fit`` learns raises :class:`~supportive.errors.NotFittedError`
  (an ``AttributeError``, so ``hasattr`` still answers False);
* everything random takes ``seed: int | numpy.random.Generator | None`` (:mod:`supportive.seeding`).

>>> class Mean(Estimator):
...     def fit(self, values: list[float]) -> "Mean":
...         self.mean_ = sum(values) / len(values)
...         return self
>>> Mean().mean_
Traceback (most recent call last):
...
supportive.errors.NotFittedError: Mean is not fitted: call fit(...) before asking for mean_
>>> Mean().fit([1.0, 2.0]).mean_
1.5
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from supportive.errors import NotFittedError

__all__ = ["Estimator"]


class Estimator:
    """Base of the estimators: a learned attribute asked for before ``fit`` raises NotFittedError."""

    if not TYPE_CHECKING:  # for mypy, attributes stay checked by name

        def __getattr__(self, name: str) -> Any:
            if name.endswith("_") and not name.startswith("__"):
                raise NotFittedError(f"{type(self).__name__} is not fitted: call fit(...) before asking for {name}")
            raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    def _forget(self) -> None:
        """Drop every learned attribute: the first step of ``fit``, so that a refit (or a failed one) keeps
        nothing of an earlier fit."""
        for name in [n for n in vars(self) if n.endswith("_") and not n.startswith("__")]:
            delattr(self, name)

    @property
    def fitted(self) -> bool:
        """True once ``fit`` has run (some learned attribute exists)."""
        return any(name.endswith("_") and not name.startswith("__") for name in vars(self))
