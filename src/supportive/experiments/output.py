"""The files a run writes: ``metrics.json`` (deterministic), ``report.md``, ``run.json`` (wall time and
where it ran) and, when trials measured wall-clock times, ``timing.json``; all of them into their folder
together (:func:`write_folder`), so an interrupted or failed run leaves the folder as it was."""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import tempfile
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

from supportive.errors import ExperimentError, FileFormatError
from supportive.io.atomic import atomic_write, uninterrupted

__all__ = [
    "METRICS_FILE",
    "REPORT_FILE",
    "RUN_FILE",
    "TIMING_FILE",
    "check_folder",
    "dump_json",
    "write_folder",
    "write_text",
]

METRICS_FILE = "metrics.json"
"""The metrics: the same trials give the same bytes, however many workers ran them."""
REPORT_FILE = "report.md"
"""The markdown report: this run's numbers beside the thesis's."""
RUN_FILE = "run.json"
"""How the run went: wall time, workers, scheduler, versions. Differs from run to run by design."""
TIMING_FILE = "timing.json"
"""The trials' wall-clock measurements (their ``"timing"``), in trial order. Differs from run to run by
design."""


def dump_json(data: Mapping[str, Any], *, what: str = "metrics") -> str:
    """``data`` as JSON text that depends on nothing but its content: sorted keys, fixed indentation.

    Raises:
        ExperimentError: when ``data`` is not plain JSON data (or holds NaN or infinity).

    >>> dump_json({"b": 1, "a": [0.5, None]})
    '{\\n  "a": [\\n    0.5,\\n    null\\n  ],\\n  "b": 1\\n}\\n'
    """
    try:
        return json.dumps(data, sort_keys=True, indent=2, ensure_ascii=False, allow_nan=False) + "\n"
    except (TypeError, ValueError) as exc:
        raise ExperimentError(f"{what} are not plain JSON data: {exc}") from None


def write_text(path: Path, text: str) -> Path:
    """Write ``text`` to ``path`` (UTF-8, atomically), creating its directory.

    Raises:
        ExperimentError: when the file cannot be written.
    """
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        atomic_write(path, text)
    except OSError as exc:
        raise ExperimentError(f"{path}: cannot write: {exc.strerror or exc}") from None
    except FileFormatError as exc:
        raise ExperimentError(str(exc)) from None
    return path


def check_folder(output: Path) -> None:
    """Check that ``output`` can be a run's folder (it is one, or does not exist yet), before the run.

    Raises:
        ExperimentError: when it is a file.
    """
    if output.exists() and not output.is_dir():
        raise ExperimentError(f"{output}: is a file; the output is a folder (it gets {METRICS_FILE}, {REPORT_FILE}, …)")


def write_folder(output: Path, write: Callable[[Path], Sequence[Path]]) -> list[Path]:
    """Write a run's files into the folder ``output`` all together: ``write(folder)`` writes them into a
    hidden folder beside ``output`` and returns them; then, with Ctrl-C and SIGTERM held back, they are moved
    into ``output`` (made when missing). A run interrupted or failing before that leaves ``output`` as it was
    (a folder it would have made is not made) and no hidden folder; files of ``output`` the run does not
    write are kept.

    Returns:
        The files, under ``output``.

    Raises:
        ExperimentError: when ``output`` is a file or cannot be written.
    """
    check_folder(output)
    target = output.absolute()
    missing = [folder for folder in (target, *target.parents) if not folder.exists()]
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        staging = Path(tempfile.mkdtemp(prefix=f".{target.name}.", suffix=".partial", dir=target.parent))
    except OSError as exc:
        _remove_empty(missing)
        raise ExperimentError(f"{output}: cannot write: {exc.strerror or exc}") from None
    try:
        written = [path.relative_to(staging) for path in write(staging)]
        with uninterrupted():
            if not target.exists():
                os.rename(staging, target)
            else:
                for name in written:
                    (target / name).parent.mkdir(parents=True, exist_ok=True)
                    os.replace(staging / name, target / name)
    except OSError as exc:
        _remove_empty(missing)
        raise ExperimentError(f"{output}: cannot write: {exc.strerror or exc}") from None
    except BaseException:
        _remove_empty(missing)
        raise
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return [output / name for name in written]


def _remove_empty(folders: list[Path]) -> None:
    """Remove the folders a failed write made (deepest first), if nothing else went into them."""
    for folder in folders:
        with contextlib.suppress(OSError):
            folder.rmdir()
