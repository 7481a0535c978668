"""A run's output folder, written as one consistent set or not at all.

Files are written into a staging folder beside the target and moved into
place together, so the target always holds either the previous complete set or
the new one. A lock file beside the target makes a second run into the same
folder refuse at once rather than interleave its files with the first. While
the set is moved into place, SIGINT and SIGTERM are held back until the move is
done. Only a folder that is empty or holds nothing but a run's outputs is ever
replaced: a folder with other files in it is refused, never deleted.
"""

from __future__ import annotations

import errno
import fcntl
import os
import shutil
import signal
import tempfile
from contextlib import contextmanager
from pathlib import Path

__all__ = ["FolderError", "OUTPUT_NAMES", "OutputFolder", "held_signals", "writable_folder"]

#: The files a run writes; a folder holding only these (or nothing) may be replaced.
OUTPUT_NAMES = frozenset({"trajectory.csv", "summary.json", "trajectory.png", "scene.resolved.toml"})


class FolderError(ValueError):
    """An output folder that cannot be used: a bad path, no permission, or another run owns it."""


def _absolute(path: str | os.PathLike) -> Path:
    text = os.fspath(path)
    if not text.strip():
        msg = "the output folder must be a path, got an empty string"
        raise FolderError(msg)
    return Path(text).absolute()


def _not_through_a_file(path: Path) -> None:
    for parent in reversed(path.parents):
        if parent.exists() and not parent.is_dir():
            msg = f"cannot write outputs to {path}: {parent} is a file, not a folder"
            raise FolderError(msg)
    if path.exists() and not path.is_dir():
        msg = f"cannot write outputs to {path}: it is a file, not a folder"
        raise FolderError(msg)


def writable_folder(path: str | os.PathLike) -> Path:
    """A folder that outputs are added to (a report, a table), made if missing and checked writable.

    Raises
    ------
    FolderError
        For an empty path, a path through or onto a file, or a place that cannot be written.
    """
    folder = _absolute(path)
    _not_through_a_file(folder)
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as err:
        msg = f"cannot write outputs to {folder}: {err.strerror or err}"
        raise FolderError(msg) from err
    return folder


@contextmanager
def held_signals():
    """Hold SIGINT and SIGTERM back for the duration; deliver the first one afterwards."""
    received: list[int] = []

    def note(signum, _frame):
        received.append(signum)

    previous = {s: signal.signal(s, note) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
        if received:
            signal.raise_signal(received[0])


class OutputFolder:
    """Context manager for writing a run's outputs into ``path`` as one set.

    On entry the path is checked, the lock taken and an empty staging folder
    made (so an unwritable place is found before anything runs); write into
    :attr:`staging` and call :meth:`commit`. On exit without a commit the
    staging folder is removed and the target is left as it was.

    Raises
    ------
    FolderError
        For an empty path, a path through or onto a file, a folder holding
        other files, a place that cannot be written, or a folder another run
        is writing.
    """

    def __init__(self, path: str | os.PathLike):
        self.path = _absolute(path)
        self.staging = self.path.parent / f".{self.path.name}.staging-{os.getpid()}"
        self._lock_fd: int | None = None
        self._committed = False

    def __enter__(self) -> OutputFolder:
        self._check_target()
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._lock_fd = os.open(self.path.parent / f".{self.path.name}.lock", os.O_RDWR | os.O_CREAT, 0o666)
        except OSError as err:
            raise self._cannot_write(err) from err
        try:
            fcntl.flock(self._lock_fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as err:
            os.close(self._lock_fd)
            self._lock_fd = None
            if err.errno in (errno.EWOULDBLOCK, errno.EACCES):
                msg = f"another run is writing to {self.path}; wait for it or choose another folder"
                raise FolderError(msg) from err
            raise self._cannot_write(err) from err
        try:
            self._remove_leftovers()
            self.staging.mkdir()
        except OSError as err:
            self._release()
            raise self._cannot_write(err) from err
        return self

    def __exit__(self, *exc) -> None:
        if not self._committed:
            shutil.rmtree(self.staging, ignore_errors=True)
        self._release()

    def commit(self) -> Path:
        """Move the staging folder into place, replacing a previous set; return the folder."""
        previous = self.path.parent / f".{self.path.name}.previous-{os.getpid()}"
        with held_signals():
            if self.path.exists():
                self._check_target()
                os.rename(self.path, previous)
            os.rename(self.staging, self.path)
            self._committed = True
            shutil.rmtree(previous, ignore_errors=True)
        return self.path

    def _check_target(self) -> None:
        _not_through_a_file(self.path)
        if self.path.is_dir():
            others = sorted(p.name for p in self.path.iterdir() if p.name not in OUTPUT_NAMES)
            if others:
                shown = ", ".join(others[:5]) + (", ..." if len(others) > 5 else "")
                msg = (f"{self.path} holds files that are not a run's outputs ({shown}); a run replaces "
                       "its folder whole, so choose an empty or new folder")
                raise FolderError(msg)

    def _remove_leftovers(self) -> None:
        """Staging and previous folders of runs that were killed outright (we hold the lock)."""
        for pattern in (f".{self.path.name}.staging-*", f".{self.path.name}.previous-*"):
            for stale in self.path.parent.glob(pattern):
                shutil.rmtree(stale, ignore_errors=True)

    def _cannot_write(self, err: OSError) -> FolderError:
        return FolderError(f"cannot write outputs to {self.path}: {err.strerror or err}")

    def _release(self) -> None:
        if self._lock_fd is not None:
            fcntl.flock(self._lock_fd, fcntl.LOCK_UN)
            os.close(self._lock_fd)
            self._lock_fd = None
