"""Writing pictures to files: the name checked before any drawing (a folder, or a name without the suffix
that says the format, is refused), and the file written atomically (:mod:`supportive.io.atomic`): an
interrupted or failed drawing leaves the file as it was."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from supportive.errors import ExportError, FileFormatError
from supportive.io.atomic import atomic_target, check_target

__all__ = ["picture_file", "picture_path"]


def picture_path(path: str | Path, suffix: str, what: str) -> Path:
    """``path``, checked to name a file of the kind ``what`` ending in ``suffix`` (``".gif"``, ``".png"``).

    Raises:
        ExportError: naming the file, for a folder or another suffix.
    """
    try:
        return check_target(path, suffix, what)
    except FileFormatError as exc:
        raise ExportError(str(exc)) from None


@contextmanager
def picture_file(path: str | Path, suffix: str, what: str) -> Iterator[Path]:
    """A temporary file for a picture writer (matplotlib, Pillow) that becomes ``path`` once the block ends.

    Raises:
        ExportError: as :func:`picture_path`, and when the file cannot be written.
    """
    target = picture_path(path, suffix, what)
    try:
        with atomic_target(target) as temporary:
            yield temporary
    except FileFormatError as exc:
        raise ExportError(str(exc)) from None
