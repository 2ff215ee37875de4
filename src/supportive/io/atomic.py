"""Writing a user's file so that nothing is lost: atomically, keeping its mode and its symlinks, one writer
at a time.

* :func:`atomic_write` writes the new text to a temporary file beside the target, flushes it to disk and
  renames it over the target: a reader, a crash or a full disk sees the old file or the new one, never half
  of one. A symlink is followed (the file it names is replaced, the link stays a link); the file's mode (and,
  where allowed, its owner) is kept; a new file gets the mode ``open()`` would give it. A file its user may
  not write (read-only) is refused, as ``open()`` would refuse it, though a rename could replace it.
* :func:`create_new` makes a file that must not exist yet, whole or not at all (never a truncated one).
* :func:`atomic_target` gives a writer that wants a file name (matplotlib, Pillow) a temporary one beside
  the target, renamed over it once the writer is done; :func:`check_target` checks such a target's name
  before any work (a folder, or a name without the suffix that says the format, is refused).
* :func:`uninterrupted` holds Ctrl-C and SIGTERM back while a few renames that belong together run (the two
  files of an HDDL export, the files of an experiment's report), so an interruption never leaves some of them
  new and some old.
* :func:`exclusive` holds a lock on the file while a read-change-write cycle runs, so a second ``supportive``
  process editing the same file waits for the first instead of overwriting what it just saved. The lock is
  ``flock`` on the file itself; a writer that waited checks it still holds the file that is there now (the
  first one renamed a new file over it) and locks that one.

>>> import tempfile, pathlib
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> target = atomic_write(folder / "notes.txt", "first\\n")
>>> with exclusive(target):
...     _ = atomic_write(target, target.read_text() + "second\\n")
>>> target.read_text()
'first\\nsecond\\n'
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import signal
import stat
import tempfile
import threading
from collections.abc import Iterable, Iterator
from pathlib import Path
from types import FrameType

from supportive.errors import FileFormatError

__all__ = [
    "atomic_target",
    "atomic_write",
    "check_apart",
    "check_target",
    "create_new",
    "exclusive",
    "real_path",
    "uninterrupted",
]


def real_path(path: str | Path) -> Path:
    """The file ``path`` names, through any symlinks (the path itself when it does not exist yet)."""
    return Path(os.path.realpath(path))


def check_apart(output: str | Path, inputs: Iterable[str | Path], option: str) -> None:
    """Refuse an output that is one of the inputs, or inside one (a folder such as a rosbag2 bag), through
    any symlinks: writing it would change what was read.

    Raises:
        FileFormatError: naming the output, the option and the input.
    """
    target = real_path(output)
    for given in inputs:
        source = real_path(given)
        if target == source or source in target.parents:
            where = "is" if target == source else "is inside"
            raise FileFormatError(f"{option} {where} the input {given}; write the result elsewhere", path=output)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def atomic_write(
    path: str | Path, text: str, *, error: type[FileFormatError] = FileFormatError, mode: int | None = None
) -> Path:
    """Replace the file at ``path`` (through symlinks) with ``text``, atomically.

    Args:
        path: The file to write; its directory must exist.
        text: The whole new content (UTF-8).
        error: The kind of error to raise.
        mode: The new file's permission bits (default: an existing file's, else ``0o666`` less the umask).

    Returns:
        The file written (the symlink's target when ``path`` is a symlink).

    Raises:
        error: naming the file, when it cannot be written (nothing is changed then).
    """
    target = real_path(path)
    try:
        current: os.stat_result | None = target.stat()
    except FileNotFoundError:
        current = None
    except OSError as exc:
        raise error(f"cannot write: {exc.strerror}", path=path) from None
    if current is not None and not stat.S_ISREG(current.st_mode):
        raise error("cannot write: not a regular file", path=path)
    if current is not None and not os.access(target, os.W_OK):  # a rename would replace it all the same
        raise error("cannot write: the file is read-only (make it writable to replace it)", path=path)
    if mode is None:
        mode = stat.S_IMODE(current.st_mode) if current is not None else 0o666 & ~_umask()
    try:
        descriptor, temporary = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
    except OSError as exc:
        raise error(f"cannot write: {exc.strerror}", path=path) from None
    try:
        with os.fdopen(descriptor, "w", encoding="utf-8", newline="") as handle:
            handle.write(text)
            handle.flush()
            os.fchmod(handle.fileno(), mode)
            if current is not None:
                with contextlib.suppress(PermissionError):  # only root may give a file away
                    os.fchown(handle.fileno(), current.st_uid, current.st_gid)
            os.fsync(handle.fileno())
        os.replace(temporary, target)
    except OSError as exc:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        raise error(f"cannot write: {exc.strerror}", path=path) from None
    except BaseException:  # interrupted (Ctrl-C, or SIGTERM turned into one): the old file, and no temporary
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        raise
    with contextlib.suppress(OSError):  # the rename itself reaches the disk
        folder = os.open(target.parent, os.O_RDONLY)
        try:
            os.fsync(folder)
        finally:
            os.close(folder)
    return target


def create_new(path: str | Path, text: str) -> Path:
    """Make the new file ``path`` with ``text`` (UTF-8): written and flushed to disk under a temporary name,
    then linked to ``path``, which must not exist. A crash, a kill or Ctrl-C leaves no file or the whole one.

    Raises:
        FileExistsError: when ``path`` exists (nothing is changed).
        OSError: when it cannot be written.
    """
    target = Path(path)
    descriptor, temporary = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent or ".")
    try:
        with os.fdopen(descriptor, "w", encoding="utf-8", newline="") as handle:
            handle.write(text)
            handle.flush()
            os.fchmod(handle.fileno(), 0o666 & ~_umask())
            os.fsync(handle.fileno())
        os.link(temporary, target)  # fails when the target exists: never replaces a file
    finally:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
    return target


def check_target(path: str | Path, suffix: str, what: str, *, error: type[FileFormatError] = FileFormatError) -> Path:
    """Check that ``path`` can be written as a file of the kind ``what`` whose name ends in ``suffix`` (any
    case): not a folder, not a name without that suffix. Nothing is written.

    Raises:
        error: naming the file, otherwise.
    """
    target = Path(path)
    if target.is_dir():
        raise error(f"is a folder; {what} is written to a file whose name ends in {suffix}", path=path)
    if target.suffix.lower() != suffix:
        raise error(f"{what} is written to a file whose name ends in {suffix}", path=path)
    return target


@contextlib.contextmanager
def atomic_target(path: str | Path, *, error: type[FileFormatError] = FileFormatError) -> Iterator[Path]:
    """A temporary file beside ``path`` (same suffix: writers choose the format by it) for the block to write;
    once the block ends it replaces ``path`` atomically. A failure or an interruption removes it, and ``path``
    is as it was.

    Raises:
        error: naming the file, when it cannot be written.
    """
    target = real_path(path)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        descriptor, name = tempfile.mkstemp(prefix=f".{target.name}.", suffix=f".tmp{target.suffix}", dir=target.parent)
        os.close(descriptor)
    except OSError as exc:
        raise error(f"cannot write: {exc.strerror}", path=path) from None
    temporary = Path(name)
    try:
        yield temporary
        os.replace(temporary, target)
    except OSError as exc:
        raise error(f"cannot write: {exc.strerror}", path=path) from None
    finally:
        with contextlib.suppress(OSError):
            temporary.unlink()  # gone already once it replaced the target


@contextlib.contextmanager
def exclusive(path: str | Path, *, error: type[FileFormatError] = FileFormatError) -> Iterator[Path]:
    """Hold the write lock of the existing file at ``path`` (through symlinks) until the block ends; another
    process asking for it meanwhile waits. Yields the file locked.

    Raises:
        error: naming the file, when it does not exist or cannot be opened.
    """
    target = real_path(path)
    while True:
        try:
            descriptor = os.open(target, os.O_RDONLY | os.O_NONBLOCK)
        except FileNotFoundError:
            raise error("no such file", path=path) from None
        except OSError as exc:
            raise error(f"cannot open: {exc.strerror}", path=path) from None
        try:
            fcntl.flock(descriptor, fcntl.LOCK_EX)
            try:
                same = os.fstat(descriptor).st_ino == os.stat(target).st_ino
            except FileNotFoundError:
                same = False
            if same:
                yield target
                return
        finally:
            os.close(descriptor)  # closing releases the lock
        # another writer replaced the file while we waited: lock the one that is there now


@contextlib.contextmanager
def uninterrupted() -> Iterator[None]:
    """Hold back Ctrl-C (SIGINT) and SIGTERM while the block runs, then deliver the first that came: for a few
    quick steps that must all happen or none (renaming a set of files into place). Outside the main thread,
    where Python runs no signal handler, it changes nothing."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []

    def hold(signum: int, frame: FrameType | None) -> None:
        caught.append(signum)

    previous = {number: signal.signal(number, hold) for number in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler if handler is not None else signal.SIG_DFL)
        if caught:
            signal.raise_signal(caught[0])
