"""Reading a user's text file, with failures reported as the caller's kind of file error."""

from __future__ import annotations

from pathlib import Path

from supportive.errors import FileFormatError

__all__ = ["read_text"]


def read_text(path: Path, error: type[FileFormatError]) -> str:
    """The file's text (UTF-8).

    Raises:
        error: "no such file" or "cannot read: …", naming the file.
    """
    try:
        return path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise error("no such file", path=path) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise error(f"cannot read: {exc}", path=path) from None
