"""A command's output directory for one run: locked, its files staged, published together.

Every command that writes a folder (report, design, codesign, simulate, paper) writes it through
an :class:`OutputFolder`:

* **one run at a time**: the directory's lock (:class:`hexaleg.parallel.lock.DirectoryLock`,
  the sweep's) is taken before any work, and held for the run's life; a second run into the
  same directory is refused with :class:`~hexaleg.errors.DirectoryLockedError` naming the
  first (its pid, host and start time);
* **nothing published before the end**: the run's files are written into a hidden staging
  folder inside the directory (``.hexaleg-staging-<pid>-<token>``, on the same file system),
  each through :func:`hexaleg.config.write_file`;
* **published together**: :meth:`OutputFolder.publish` renames them into the directory, one
  :func:`os.replace` each, with SIGINT and SIGTERM held back until the last
  (:func:`hexaleg.parallel.interrupt.deferred`); a file or link of the same name is replaced,
  never written through, and the files the command's previous run published there (its hidden
  record, :data:`RECORD`) that this run does not write are removed: one run's files;
* **a failed or interrupted run leaves nothing of its own**: leaving the ``with`` block without
  :meth:`~OutputFolder.publish` (an error, a full disk, Ctrl-C, a kill) removes the staging
  folder, and the directory if the run made it, and releases the lock; the previous run's
  files are as they were. Only SIGKILL, which no process can answer, leaves its staging folder
  and lock behind; the next run into the directory removes that folder and takes the lock over.
"""

from __future__ import annotations

import contextlib
import json
import os
import secrets
import shutil
from pathlib import Path
from types import TracebackType

from hexaleg.config import read_json, write_file
from hexaleg.errors import ConfigError, OutputError
from hexaleg.parallel.interrupt import check, deferred, found, keep
from hexaleg.parallel.lock import DirectoryLock

STAGING = ".hexaleg-staging-"
"""Prefix of a run's staging folder in its output directory (hidden: a dot first)."""


def _made(out: Path) -> list[Path]:
    """The directories ``out.mkdir(parents=True)`` would make, deepest first."""
    missing = []
    for p in (out, *out.parents):
        if p.exists() or p.is_symlink():
            break
        missing.append(p)
    return missing


RECORD = ".hexaleg-files-"
"""Prefix of the hidden record of the files a command's last run published in a folder
(``.hexaleg-files-report.json``): the next run of that command removes those it does not
write again (an earlier ``--svg``'s SVGs, an earlier design's maps), so the folder holds one
run's files."""


def _recorded(record: Path) -> list[str]:
    """The plain file names in a folder's record of its last run ([] when there is none, or it
    is not one: a link, unreadable, not a list of names)."""
    try:
        files = read_json(record, "record of a run's files", 1 << 20, follow=False)["files"]
    except (ConfigError, KeyError, TypeError):
        return []
    if not isinstance(files, list):
        return []
    return [n for n in files if isinstance(n, str) and n and Path(n).name == n
            and not n.startswith(".")]


class OutputFolder:
    """The output directory of one run (module docstring). Use as a context manager::

        with OutputFolder(out, "report") as folder:
            ...                                     # compute
            write_file(folder.path("report.json"), text)
            files = folder.publish()                # the files, now in ``out``

    Args:
        out: The directory (created with its parents if missing).
        what: What the run writes, for the messages (``"report"``, ``"design"``, …).

    Attributes:
        directory: ``out``.
        staging: The staging folder, where the run's files are written.
        lock: The directory's lock (its ``stale`` says whose stale lock was taken over).

    Raises:
        DirectoryLockedError: another run writes into ``out`` (names its pid, host and start
            time).
        OutputError: ``out`` cannot be created or written (names it and the reason).
    """

    def __init__(self, out: str | Path, what: str) -> None:
        self.directory = Path(out)
        self.what = what
        self._made = _made(self.directory)
        self._open = True
        self._published = False
        self.staging = self.directory / f"{STAGING}{os.getpid()}-{secrets.token_hex(4)}"
        self.lock: DirectoryLock | None = None
        try:
            with deferred():  # an interrupt waits until the folder is set up, then cleans up
                self._set_up()
        except BaseException as e:
            shutil.rmtree(self.staging, ignore_errors=True)
            self._close(remove=True)
            interrupted = found(e)
            if interrupted is not None:
                keep(interrupted, self.kept())
            raise

    def _set_up(self) -> None:
        """Make the directory, take its lock, remove a killed run's staging folder, make this
        run's."""
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
        except OSError as e:
            raise OutputError(f"cannot write the {self.what} to the directory "
                              f"{self.directory}: {e.strerror or e}") from e
        self.lock = DirectoryLock(self.directory, self.what)  # proves the directory writable
        try:
            for stray in self.directory.glob(STAGING + "*"):  # a killed run's, never a live one
                shutil.rmtree(stray, ignore_errors=True)
            self.staging.mkdir()
        except OSError as e:
            raise OutputError(f"cannot write the {self.what} to the directory "
                              f"{self.directory}: {e.strerror or e}") from e

    def path(self, name: str) -> Path:
        """Where the run writes its file ``name`` (in the staging folder until published)."""
        if Path(name).name != name or name.startswith("."):
            raise OutputError(f"cannot write the {self.what}: {name!r} is not a plain file name")
        return self.staging / name

    def write(self, name: str, data: bytes | str) -> Path:
        """Write the run's file ``name`` (:func:`hexaleg.config.write_file`) into the staging
        folder; the path written."""
        return write_file(self.path(name), data, f"the {self.what}")

    def publish(self) -> list[Path]:
        """Move the run's files into the directory, all of them, then give the directory up.

        Returns:
            The published files, in the directory, by name.

        Raises:
            OutputError: a directory stands where a file goes (named; nothing is published).
        """
        check()  # an interrupt that was lost on the way still stops the run here
        names = sorted(p.name for p in self.staging.iterdir())
        for name in names:
            target = self.directory / name
            if target.is_dir() and not target.is_symlink():
                raise OutputError(f"cannot write the {self.what}: {target} is a directory; "
                                  f"remove it or give another --out directory")
        record = self.directory / f"{RECORD}{self.what.replace(' ', '-')}.json"
        stale = [n for n in _recorded(record) if n not in names]
        write_file(self.staging / record.name, json.dumps({"files": names}), f"the {self.what}")
        try:
            with deferred():  # an interrupt waits for the last rename
                for name in [*names, record.name]:
                    os.replace(self.staging / name, self.directory / name)
                for name in stale:  # the previous run's files this run does not write
                    with contextlib.suppress(FileNotFoundError, IsADirectoryError):
                        (self.directory / name).unlink()
                self.staging.rmdir()
                self._published = True
                self._close(remove=False)
        except OSError as e:
            raise OutputError(f"cannot write the {self.what} to {self.directory}: "
                              f"{e.strerror or e}") from e
        return [self.directory / name for name in names]

    def discard(self) -> None:
        """Remove everything of this run (its staging folder, the directories it made) and give
        the directory up; the files of earlier runs stay as they were (idempotent)."""
        if not self._open:
            return
        shutil.rmtree(self.staging, ignore_errors=True)
        self._close(remove=True)

    def _close(self, *, remove: bool) -> None:
        self._open = False
        if self.lock is not None:
            self.lock.release()
        if remove:
            self._remove_made()

    def _remove_made(self) -> None:
        for made in self._made:  # only while empty: another process may have written there
            try:
                made.rmdir()
            except OSError:
                break

    def kept(self) -> str:
        """What an interrupted or failed run leaves, in words."""
        if self._made:
            return f"nothing of this run written to {self.directory}"
        return f"{self.directory} kept as it was, nothing of this run written"

    def __enter__(self) -> OutputFolder:
        return self

    def __exit__(self, kind: type[BaseException] | None, value: BaseException | None,
                 tb: TracebackType | None) -> None:
        if not self._open:
            interrupted = found(value)
            if self._published and interrupted is not None:
                keep(interrupted, f"this run's files published in {self.directory}")
            return
        self.discard()
        interrupted = found(value)
        if interrupted is not None:
            keep(interrupted, self.kept())
        elif isinstance(value, OutputError) and str(self.staging) in str(value):
            # named by where the run writes it, not by its staging folder
            raise OutputError(str(value).replace(str(self.staging), str(self.directory))
                              + f"; {self.kept()}") from value


__all__ = ["RECORD", "STAGING", "OutputFolder"]
