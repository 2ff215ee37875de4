"""Where ``teach`` and ``chat`` save: a copy of the task file that the user names, never the file they read
and never the installed package's own data.

:func:`working_copy` picks the copy (``--save PATH``; by default ``NAME.edited.yaml`` beside the user's file,
or in the current directory for a bundled example); the session's first change (:meth:`WorkingCopy.update`)
makes it from the task file with that change applied (comments and layout kept), whole or not at all, when
it does not exist yet — a session that changes nothing leaves no copy — and otherwise the session carries on
in it, so a second session adds to the first. A file whose name already ends in ``.edited`` is its own working
copy.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from supportive.errors import TaskFileError
from supportive.io.atomic import create_new, real_path
from supportive.io.safe_load import read_text
from supportive.io.task_edit import edited_text, update_task_file
from supportive.io.taskfile import dump_task, format_of, parse_task_file, parse_task_string
from supportive.tasks.spec import TaskSpec

__all__ = ["EDITED", "WorkingCopy", "package_folder", "working_copy"]

EDITED = ".edited"
"""What the default working copy's name adds before the suffix (``chair.yaml`` → ``chair.edited.yaml``)."""


@dataclass
class WorkingCopy:
    """The file a session works on.

    Attributes:
        path: The working copy (saved to after every change).
        source: The task file it is made from.
        made: True once :meth:`update` made it now; False while it is not made yet, or when it existed and the
            session carries on in it.
    """

    path: Path
    source: Path
    made: bool = False

    @property
    def exists(self) -> bool:
        """Whether the copy is there already (made earlier, or by :meth:`update`)."""
        return self.path.exists()

    def reads(self) -> Path:
        """The file the session's task comes from: the copy when it exists, else the source (nothing is written
        yet: a session that changes nothing leaves no file behind)."""
        return self.path if self.exists else self.source

    def update(self, change: Callable[[TaskSpec], TaskSpec]) -> TaskSpec:
        """Save a change to the copy (:func:`~supportive.io.task_edit.update_task_file`); the first change of a
        session that found no copy makes it, from the source's text with the change applied (its comments
        and layout kept; converted when the suffixes name different formats). The copy appears whole or not
        at all (:func:`~supportive.io.atomic.create_new`): a session that changes nothing leaves no file.

        Returns:
            The task as saved.

        Raises:
            TaskFileError: when the source cannot be read or the copy cannot be written.
        """
        if self.exists:
            return update_task_file(self.path, change)
        text = read_text(self.source, TaskFileError)
        old = parse_task_string(text, format_of(self.source), path=self.source)
        new = change(old)
        if format_of(self.source) == format_of(self.path):
            copied = edited_text(text, format_of(self.path), old, new, path=self.path)
        else:
            copied = dump_task(new, format_of(self.path))
        try:
            create_new(self.path, copied)
        except FileExistsError:  # made meanwhile by another session: save the change in it
            return update_task_file(self.path, change)
        except OSError as exc:
            raise TaskFileError(f"cannot make the working copy: {exc.strerror}", path=self.path) from None
        self.made = True
        return new

    def describe(self) -> str:
        """One line for the person: where their work is saved, and what stays untouched."""
        if self.path.resolve() == self.source.resolve():
            return f"Saving to {self.path} (the file you named)."
        if not self.exists or self.made:
            return f"Saving to {self.path}, a new copy of {self.source} (which is not changed), made at the first change."
        return f"Carrying on in {self.path} (saved there before; {self.source} is not changed)."


def package_folder() -> Path:
    """The installed ``supportive`` package's folder (its examples and pages are its own data)."""
    return Path(__file__).resolve().parents[1]


def working_copy(source: str | Path, save: str | Path | None = None) -> WorkingCopy:
    """The working copy of the task file ``source`` (not made yet: the first :meth:`WorkingCopy.update` makes
    it).

    Args:
        source: The task file the session starts from.
        save: The copy to work on (default: ``NAME.edited.SUFFIX`` beside ``source``, or in the current
            directory when ``source`` is inside the installed package; ``source`` itself when its name already
            ends in ``.edited``).

    Raises:
        TaskFileError: for a copy inside the installed package, in a folder that does not exist, or holding
            another task; and for a source that cannot be read.
    """
    source = Path(source)
    inside = _inside_package(source)
    if save is None:
        if source.stem.endswith(EDITED) and not inside:
            target = source
        else:
            name = f"{source.stem}{EDITED}{source.suffix}"
            target = Path(name) if inside else source.parent / name  # a bundled one: in the current folder
    else:
        target = Path(save)
    if target.is_dir():
        raise TaskFileError("is a folder; --save names the file of the copy (.yaml, .yml or .json)", path=target)
    format_of(target)  # a name whose suffix says no format is refused before anything is done
    if _inside_package(target):
        raise TaskFileError(
            f"{target} is inside the installed supportive package, whose examples are its own data: "
            "save your copy elsewhere with --save PATH"
        )
    spec = parse_task_file(source)
    if target.exists():
        kept = parse_task_file(target)
        if kept.name != spec.name:
            raise TaskFileError(
                f"it holds task {kept.name!r}, not {spec.name!r}: choose another file with --save PATH", path=target
            )
    elif not target.parent.is_dir():
        raise TaskFileError(f"folder {target.parent} does not exist", path=target)
    return WorkingCopy(target, source)


def _inside_package(path: Path) -> bool:
    return real_path(path).is_relative_to(package_folder())  # never raises, even on a symlink loop
