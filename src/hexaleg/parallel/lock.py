"""One writer per output directory: a lock file that names its holder and dies with it.

:class:`DirectoryLock` holds ``DIR/.lock`` for as long as a run writes to ``DIR`` (a sweep, or a
command's output folder: :class:`hexaleg.outputs.directory.OutputFolder`). The file says who
holds it (what, pid, host, start time, command line), so a second run started into the same
directory is refused with a :class:`~hexaleg.errors.DirectoryLockedError` naming the first. The
lock itself is an advisory ``flock`` (POSIX, :func:`fcntl.flock`) on that file: the kernel drops
it when the holding process ends, however it ends — a ``kill -9`` leaves the file behind, but
unlocked, and the next run recognises it as stale, says so, and takes it over. Where ``fcntl``
is missing (Windows) the lock is the file's existence (``O_EXCL``) and a lock whose process no
longer runs on this host is stale.

The name starts with a dot, so ``pandas.read_parquet(DIR)`` skips it (pyarrow ignores files
whose names start with ``.`` or ``_``).
"""

from __future__ import annotations

import contextlib
import json
import os
import socket
import stat
import sys
import time
from pathlib import Path
from typing import Any

from hexaleg.config import read_json
from hexaleg.errors import ConfigError, DirectoryLockedError, OutputError

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None  # type: ignore[assignment]

LOCK = ".lock"
"""Name of the lock file in an output directory."""

_HELD: set[int] = set()
"""File descriptors of the locks this process holds; forked pool workers close their copies
(:func:`close_inherited`), so a worker can never keep its parent's lock alive."""


def running(pid: int) -> bool:
    """Whether process ``pid`` runs on this host (signal 0: kill(2) checks without sending).

    A zombie — ended, not yet reaped by its parent — does not run, though kill(2) still finds
    it: a pool worker that starts just as its sweep is killed must see the sweep as gone
    (:func:`hexaleg.parallel.workers.watch_parent`), or it computes on as an orphan.
    """
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # it exists, as another user
        pass
    return not _zombie(pid)


def _zombie(pid: int) -> bool:
    """Whether ``pid`` is a zombie, from its state in ``/proc/PID/stat`` (proc(5)); False where
    there is no ``/proc`` (kill(2) has decided)."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    fields = stat[stat.rindex(")") + 2:].split()  # the command name may hold spaces and ")"
    return bool(fields) and fields[0] in ("Z", "X")


def _holder(what: str) -> dict[str, Any]:
    return {"what": what, "pid": os.getpid(), "host": socket.gethostname(),
            "started": time.strftime("%Y-%m-%d %H:%M:%S %z"), "argv": sys.argv}


def _describe(info: dict[str, Any]) -> str:
    return (f"pid {info.get('pid', '?')} on host {info.get('host', '?')}, started "
            f"{info.get('started', '?')}")


MAX_LOCK_BYTES = 64 * 1024
"""Largest lock file read back, B (a holder's record is a few hundred)."""
_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)


def _read(path: Path) -> dict[str, Any]:
    """The holder's record in a lock file, or {} (missing, unreadable, a link, not a record)."""
    try:
        return read_json(path, "lock file", MAX_LOCK_BYTES, follow=False)
    except ConfigError:
        return {}


def _not_a_link(path: Path, what: str) -> None:
    """Refuse a lock path that is a symbolic link (whatever it points to)."""
    if path.is_symlink():
        raise OutputError(f"the {what} lock {path} is a symbolic link (to {os.readlink(path)}); "
                          "hexaleg never writes through a link in a directory it owns: remove "
                          f"the link, or give the {what} another --out directory")


def _check_own(path: Path, fd: int, what: str) -> None:
    """Refuse an opened lock that is not a regular file of its own (a hard link to another
    file would be truncated with it)."""
    info = os.fstat(fd)
    if not stat.S_ISREG(info.st_mode) or info.st_nlink > 1:
        kind = ("not a regular file" if not stat.S_ISREG(info.st_mode)
                else f"a hard link shared with {info.st_nlink - 1} other name(s)")
        raise OutputError(f"the {what} lock {path} is {kind}; hexaleg writes its lock only into "
                          f"a file of its own: remove it, or give the {what} another --out "
                          "directory")


class DirectoryLock:
    """The exclusive right to write to an output directory.

    Args:
        directory: The directory (must exist).
        what: What writes there, for the messages (``"sweep"``, ``"report"``, …); the holder's
            record keeps it, so a refused run is told what holds the directory.

    Attributes:
        path: The lock file.
        stale: What the lock file said when this process took it over from a process that
            had ended (its holder's description), or None when there was no earlier lock.

    Raises:
        DirectoryLockedError: another running process holds the lock (the message names its
            pid, host and start time).
        OutputError: the lock file cannot be created.
    """

    def __init__(self, directory: str | Path, what: str = "sweep") -> None:
        self.path = Path(directory) / LOCK
        self.what = what
        self.stale: str | None = None
        self._fd: int | None = None
        self._held = False
        self._owner = os.getpid()  # a forked copy of this object never releases the lock
        try:
            if fcntl is not None:
                self._acquire_flock()
            else:  # pragma: no cover - Windows
                self._acquire_exclusive()
        except OSError as e:
            raise OutputError(f"cannot create the {what} lock {self.path}: {e.strerror or e}; "
                              "give as --out a directory that can be written, with free space"
                              ) from e
        self._held = True

    def _refuse(self, info: dict[str, Any]) -> DirectoryLockedError:
        holder = info.get("what", "sweep")  # a lock of hexaleg 0.2 is a sweep's
        return DirectoryLockedError(
            f"another {holder} ({_describe(info)}) is writing to {self.path.parent}; wait for "
            f"it to finish, stop it, or give this {self.what} another --out directory (lock "
            f"file {self.path})", directory=self.path.parent, pid=info.get("pid"),
            host=info.get("host"), started=info.get("started"))

    def _acquire_flock(self) -> None:
        assert fcntl is not None
        while True:
            _not_a_link(self.path, self.what)
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT | os.O_NONBLOCK | _NOFOLLOW, 0o644)
            try:
                _check_own(self.path, fd, self.what)
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                os.close(fd)
                raise self._refuse(_read(self.path)) from None
            except (OSError, OutputError):
                os.close(fd)
                raise
            try:  # the holder may have released (removed) the file between open and flock
                if os.stat(self.path).st_ino == os.fstat(fd).st_ino:
                    break
            except FileNotFoundError:
                pass
            os.close(fd)
        old = _read(self.path)
        if old:  # left by a process that ended without releasing it (a kill -9)
            self.stale = _describe(old)
        try:
            os.ftruncate(fd, 0)
            os.pwrite(fd, json.dumps(_holder(self.what)).encode(), 0)
            os.fsync(fd)
        except OSError:  # a full disk: no lock of ours left behind
            self.path.unlink(missing_ok=True)
            os.close(fd)
            raise
        self._fd = fd
        _HELD.add(fd)

    def _acquire_exclusive(self) -> None:  # pragma: no cover - Windows
        for _ in range(3):
            try:
                fd = os.open(self.path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | _NOFOLLOW, 0o644)
            except FileExistsError:
                old = _read(self.path)
                if old.get("host") == socket.gethostname() and isinstance(old.get("pid"), int) \
                        and not running(old["pid"]):
                    self.stale = _describe(old)
                    self.path.unlink(missing_ok=True)
                    continue
                raise self._refuse(old) from None
            os.write(fd, json.dumps(_holder(self.what)).encode())
            os.close(fd)
            return
        raise self._refuse(_read(self.path))

    def release(self) -> None:
        """Give the directory up (idempotent; only in the process that took it): the lock file
        is removed and unlocked."""
        if not self._held or os.getpid() != self._owner:
            return
        self._held = False
        self.path.unlink(missing_ok=True)  # before the unlock: a waiting opener retries
        if self._fd is not None:
            _HELD.discard(self._fd)
            os.close(self._fd)  # closing the descriptor drops the flock
            self._fd = None

    def __del__(self) -> None:  # a store dropped without close() still frees its directory
        with contextlib.suppress(Exception):
            self.release()


def close_inherited() -> None:
    """Close the lock descriptors a forked process inherited (in a pool worker's initializer):
    the parent keeps its locks, and they end with the parent, not with its last worker."""
    for fd in list(_HELD):
        try:
            os.close(fd)
        except OSError:
            pass
        _HELD.discard(fd)
