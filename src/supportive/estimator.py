"""The estimator contract every learning class keeps (docs/architecture.md), after scikit-learn and hmmlearn:

* ``__init__`` takes the settings, checks them and stores each under its own name, unchanged; it learns
  nothing and sets no attribute ending in ``_``;
* ``fit(data)`` learns every attribute ending in ``_`` afresh (a refit forgets earlier fits) and returns
  ``self``; ``partial_fit``, where there is one, adds to what was learned; a ``fit`` or ``partial_fit`` that
  raises leaves the estimator unfitted (this class sees to it), never half fitted;
* ``get_params()`` and ``set_params(**settings)`` read and change the settings, as in scikit-learn
  (``type(e)(**e.get_params())`` is an unfitted copy; ``set_params`` checks what it is given as ``__init__``
  does); settings are named parameters, never ``**kwargs``;
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

import functools
import inspect
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Self

from supportive.errors import LearningError, NotFittedError

__all__ = ["Estimator"]


_FITS = ("fit", "partial_fit")


def _unfitted_on_failure(fit: Callable[..., Any]) -> Callable[..., Any]:
    """``fit`` (or ``partial_fit``) that drops every learned attribute when it raises."""

    @functools.wraps(fit)
    def fitting(self: Estimator, *args: Any, **kwargs: Any) -> Any:
        try:
            return fit(self, *args, **kwargs)
        except BaseException:
            self._forget()
            raise

    fitting.__wrapped_by_estimator__ = True  # type: ignore[attr-defined]
    return fitting


class Estimator:
    """Base of the estimators: a learned attribute asked for before ``fit`` raises NotFittedError; a fit that
    raises leaves the estimator unfitted; ``get_params``/``set_params`` as in scikit-learn."""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        for name in _FITS:
            method = cls.__dict__.get(name)
            if callable(method) and not getattr(method, "__wrapped_by_estimator__", False):
                setattr(cls, name, _unfitted_on_failure(method))
        for parameter in inspect.signature(cls.__init__).parameters.values() if cls._has_settings() else ():
            if parameter.kind in (inspect.Parameter.VAR_KEYWORD, inspect.Parameter.VAR_POSITIONAL):
                raise TypeError(f"{cls.__name__}: an estimator's settings are named parameters, not *{parameter.name}")

    @classmethod
    def _has_settings(cls) -> bool:
        """False for an estimator without an ``__init__`` of its own (it has no settings)."""
        return cls.__init__ is not object.__init__

    @classmethod
    def _setting_names(cls) -> list[str]:
        """The names of ``__init__``'s parameters, in order."""
        if not cls._has_settings():
            return []
        return [name for name in inspect.signature(cls.__init__).parameters if name != "self"]

    def get_params(self, deep: bool = True) -> dict[str, Any]:
        """The settings, by name, as ``__init__`` stored them; with ``deep``, also every setting of a setting
        that is itself an estimator, as ``name__setting`` (scikit-learn's contract)."""
        params: dict[str, Any] = {}
        for name in self._setting_names():
            value = getattr(self, name)
            params[name] = value
            if deep and isinstance(value, Estimator):
                params.update((f"{name}__{k}", v) for k, v in value.get_params(deep=True).items())
        return params

    def set_params(self, **params: Any) -> Self:
        """Change settings (``name__setting`` reaches a setting that is an estimator) and return ``self``. The
        new values are checked as ``__init__`` checks them; what was learned stays until the next ``fit``.

        Raises:
            LearningError: for a name that is no setting, or a value ``__init__`` refuses.
        """
        names = self._setting_names()
        own: dict[str, Any] = {}
        nested: dict[str, dict[str, Any]] = {}
        for key, value in params.items():
            name, _, rest = key.partition("__")
            if name not in names or (rest and not isinstance(getattr(self, name), Estimator)):
                raise LearningError(
                    f"{type(self).__name__} has no setting {key!r}; its settings: {', '.join(names)}"
                )
            if rest:
                nested.setdefault(name, {})[rest] = value
            else:
                own[name] = value
        checked = type(self)(**{**self.get_params(deep=False), **own})
        for name in own:
            setattr(self, name, getattr(checked, name))
        for name, settings in nested.items():
            getattr(self, name).set_params(**settings)
        return self

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
