"""A run's output folder, written as one consistent set or not at all.

Files are written into a staging folder beside the target and moved into
place together, so the target always holds either the previous complete set or
the new one. A lock file beside the target makes a second run into the same
folder refuse at once rather than interleave its files with the first. While
the set is moved into place, SIGINT and SIGTERM are held back until the move is
done; a run killed outright between the two renames of that move leaves the
previous set aside, and the next run puts it back. Only a folder that is empty or
holds a previous set (its files only, its summary a run's) is ever replaced: a
folder with anything else in it is refused, never deleted. A symbolic link to a
folder is followed (the set replaces the folder it points to); a mount point,
which cannot be renamed, is refused before anything runs.
"""

from __future__ import annotations

import errno
import fcntl
import json
import os
import shutil
import signal
import tempfile
import threading
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
    """Hold SIGINT and SIGTERM back for the duration; deliver the first one afterwards (in the main thread,
    the only one signals reach)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
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

    ``names`` are the files of a set, and ``summary`` the file and the keys that mark a
    folder as holding a previous set (a run's by default; another command names its own).

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

    def __init__(self, path: str | os.PathLike, names: frozenset = OUTPUT_NAMES,
                 summary: tuple[str, frozenset] = ("summary.json", frozenset({"status", "forces"}))):
        self.names, self.summary = frozenset(names), summary
        self.path = _absolute(path)
        if self.path.is_symlink():  # follow a link: the set replaces the folder it points to, not the link
            self.path = Path(os.path.realpath(self.path))
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
        if os.path.ismount(self.path):
            msg = (f"{self.path} is a mount point, which a run cannot replace (it moves a new set into place by "
                   "renaming); choose a folder inside it")
            raise FolderError(msg)
        if self.path.is_dir():
            entries = list(self.path.iterdir())
            others = sorted(p.name for p in entries if p.name not in self.names or not p.is_file() or p.is_symlink())
            if others:
                shown = ", ".join(others[:5]) + (", ..." if len(others) > 5 else "")
                msg = (f"{self.path} holds files that are not a run's outputs ({shown}); a run replaces "
                       "its folder whole, so choose an empty or new folder")
                raise FolderError(msg)
            name, keys = self.summary
            if entries and not _is_summary(self.path / name, keys):
                msg = (f"{self.path} holds {', '.join(sorted(p.name for p in entries))} but no {name} of a run: "
                       "not a previous output set, so it is not replaced; choose an empty or new folder")
                raise FolderError(msg)

    def _remove_leftovers(self) -> None:
        """Put back the previous set of a run killed between the two renames of its commit; remove the staging
        and previous folders of runs that were killed outright otherwise (we hold the lock)."""
        previous = sorted(self.path.parent.glob(f".{self.path.name}.previous-*"))
        if previous and not self.path.exists():
            os.rename(previous.pop(), self.path)
        for stale in [*self.path.parent.glob(f".{self.path.name}.staging-*"), *previous]:
            shutil.rmtree(stale, ignore_errors=True)

    def _cannot_write(self, err: OSError) -> FolderError:
        return FolderError(f"cannot write outputs to {self.path}: {err.strerror or err}")

    def _release(self) -> None:
        if self._lock_fd is not None:
            fcntl.flock(self._lock_fd, fcntl.LOCK_UN)
            os.close(self._lock_fd)
            self._lock_fd = None


def _is_summary(path: Path, keys: frozenset) -> bool:
    """Whether ``path`` is the summary of a previous set: a file holding a JSON object with ``keys``."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return False
    return isinstance(data, dict) and keys <= set(data)
