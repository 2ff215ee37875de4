"""Read a stream of known actions: one action id per line (blank lines and ``#`` comments skipped).

What a task board reports as completed, or a dataset's step labels, for ``supportive infer --actions``.
"""

from __future__ import annotations

from pathlib import Path

from supportive.errors import ObservationFileError
from supportive.io.safe_load import read_text
from supportive.io.values import check_id

__all__ = ["parse_action_file"]


def parse_action_file(path: str | Path) -> list[str]:
    """The action ids of the file, in order.

    Raises:
        ObservationFileError: when the file cannot be read, holds no action, or a line holds more than one
            word (the message names the line).

    >>> import tempfile, os
    >>> with tempfile.NamedTemporaryFile("w", suffix=".txt", delete=False) as f:
    ...     _ = f.write("knife\\n# then\\ncarrots\\n\\n")
    >>> parse_action_file(f.name); os.unlink(f.name)
    ['knife', 'carrots']
    """
    path = Path(path)
    text = read_text(path, ObservationFileError)
    actions = []
    for number, line in enumerate(text.splitlines(), start=1):
        content = line.split("#", 1)[0].strip()
        if not content:
            continue
        if len(content.split()) != 1:
            raise ObservationFileError(f"expected one action id, got {content!r}", path=path, line=number)
        try:
            actions.append(check_id(content, action=True, what="an action id"))
        except ValueError as exc:
            raise ObservationFileError(str(exc), path=path, line=number) from None
    if not actions:
        raise ObservationFileError("no action ids in the file", path=path)
    return actions
