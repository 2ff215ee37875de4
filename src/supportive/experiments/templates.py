"""Report prose kept in template files, apart from the code that computes the numbers.

An experiment's package holds its templates in ``templates/`` (package data, read with
:mod:`importlib.resources`): markdown with :class:`string.Template` placeholders (``$name`` or ``${name}``;
``$$`` is a dollar sign). The report builder computes every value, tables and the sentences that depend on
the numbers included, and :func:`render` fills them in; the prose that never changes stays in the file. A
placeholder may also name an entry of the run's metrics (``$seed``, ``$trials``, ``$title``, …), which is then
written as it is.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import cache
from importlib.resources import files
from string import Template
from typing import Any

from supportive.errors import ExperimentError

__all__ = ["render", "section"]


def render(
    package: str | None, name: str, metrics: Mapping[str, Any] | None = None, /, **values: object
) -> str:
    """The template ``templates/<name>`` of ``package`` with its placeholders filled in.

    Args:
        package: The experiment's package (``"supportive.experiments.edge_reduction"``): the calling
            module's ``__package__``.
        name: The template's file name in its ``templates/`` folder.
        metrics: The run's metrics: a placeholder no value names is filled with the metrics' entry of that
            name.
        values: The other placeholders' values: text; lines (a list or tuple of text: a markdown table, a
            list), joined by newlines; or anything else, as ``str`` writes it (as an f-string's ``{value}``
            would).

    Raises:
        ExperimentError: when a placeholder has no value (nor metrics entry), when a value has no
            placeholder, or without a package.
    """
    if not package:
        raise ExperimentError(f"template {name}: no package to read it from")
    template = _load(package, name)
    wanted, given = set(template.get_identifiers()), set(values)
    found = {key: (metrics or {})[key] for key in wanted - given if key in (metrics or {})}
    missing, extra = sorted(wanted - given - set(found)), sorted(given - wanted)
    if missing or extra:
        raise ExperimentError(
            f"template {package}:templates/{name}: missing values {missing}, values it has no place for {extra}"
        )
    return template.substitute({key: _text(value) for key, value in (found | values).items()})


def _text(value: object) -> str:
    if isinstance(value, list | tuple):
        return "\n".join(value)
    return str(value)


def section(
    package: str | None, name: str, metrics: Mapping[str, Any] | None = None, /, **values: object
) -> str:
    """An optional part of a report, to follow other text: a blank line, then the template filled in as by
    :func:`render`, without its last newline.

    Raises:
        ExperimentError: as :func:`render`.
    """
    return "\n\n" + render(package, name, metrics, **values).rstrip("\n")


@cache
def _load(package: str, name: str) -> Template:
    return Template(files(package).joinpath("templates", name).read_text(encoding="utf-8"))
