"""A resumable on-disk result store: Parquet part files plus a JSON manifest in one directory.

Layout of a sweep directory::

    _manifest.json                 the spec (canonical JSON), robot, gait, motor, software versions
    part-0000000-0000049.parquet   rows of points 0…49, written when that chunk finished
    part-0000050-0000099.parquet   …
    .lock                          while a sweep writes here: who (pid, host, start time)

``pandas.read_parquet(DIR)`` reads every part as one table (pyarrow skips names that start with
``.`` or ``_``: the manifest, the lock, temporary and set-aside files); :func:`read_table` does
the same sorted by point. Guarantees:

* **One writer.** :class:`ResultStore` takes the directory's lock
  (:class:`~hexaleg.parallel.lock.DirectoryLock`) before it reads or writes anything; a
  second sweep into the same directory is refused by name, and the lock of a killed sweep is
  recognised as stale and taken over.
* **Whole parts only.** A part is written to a unique hidden temporary name (pid and a random
  token), synced, and renamed into place (:func:`os.replace`, atomic on POSIX); a killed sweep
  leaves at most a hidden temporary file, removed by the next writer.
* **Checked on resume.** Which points are finished is read back from the parts' ``point``
  column. A part that cannot be read (truncated, corrupted) or whose points do not match its
  name is set aside as ``_unreadable-<name>`` with a
  :class:`~hexaleg.errors.HexalegWarning`, and its points are computed again.
* **One sweep per directory.** A directory whose manifest holds a different spec is refused
  with an error naming the differing keys — two sweeps' rows are never mixed.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import secrets
import warnings
from collections.abc import Callable, Mapping
from pathlib import Path
from types import TracebackType
from typing import TYPE_CHECKING, Any, BinaryIO

from hexaleg.config import read_json
from hexaleg.errors import ConfigError, HexalegWarning, OutputError
from hexaleg.parallel.interrupt import keep
from hexaleg.parallel.lock import DirectoryLock
from hexaleg.quantities import json_text

if TYPE_CHECKING:
    import pandas as pd

MANIFEST = "_manifest.json"
"""Name of the manifest file in a store directory (``_``: not read as a part by pyarrow)."""
LEGACY_MANIFEST = "manifest.json"
"""The manifest's name before the lock existed; renamed to :data:`MANIFEST` on resume."""
PART = re.compile(r"part-(\d+)-(\d+)\.parquet")
"""Name of a part file: the first and last point it holds."""
SET_ASIDE = "_unreadable-"
"""Prefix of a part that could not be read on resume (kept for inspection, never read)."""


def _flatten(d: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in d.items():
        name = f"{prefix}{key}"
        if isinstance(value, Mapping):
            out.update(_flatten(value, name + "."))
        else:
            out[name] = value
    return out


def spec_differences(old: Mapping[str, Any], new: Mapping[str, Any]) -> list[str]:
    """Human-readable differences between two (nested) specs, one line per differing key."""
    a, b = _flatten(old), _flatten(new)
    lines = []
    for key in sorted(set(a) | set(b)):
        if key not in a:
            lines.append(f"{key}: (absent) → {b[key]!r}")
        elif key not in b:
            lines.append(f"{key}: {a[key]!r} → (absent)")
        elif a[key] != b[key]:
            lines.append(f"{key}: {a[key]!r} → {b[key]!r}")
    return lines


def _temporary(path: Path) -> Path:
    """A unique hidden temporary name beside ``path``."""
    return path.with_name(f".{path.name}.{os.getpid()}-{secrets.token_hex(4)}.tmp")


def _write_atomic(path: Path, write: Callable[[BinaryIO], object]) -> None:
    """``write`` the file to a unique hidden temporary name, sync it and rename it to ``path``
    (:func:`os.replace`, atomic on POSIX): readers see the whole file or none. The temporary is
    removed on failure.

    Raises:
        OSError: the file cannot be written.
    """
    tmp = _temporary(path)
    try:  # a new file of its own: never through a link or into an existing file
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0),
                     0o644)
        with os.fdopen(fd, "wb") as f:
            write(f)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            tmp.unlink()
        raise


def parts(directory: str | Path) -> list[Path]:
    """The part files of a sweep directory, sorted by name (= by first point)."""
    return sorted(p for p in Path(directory).glob("part-*.parquet") if PART.fullmatch(p.name))


def read_table(directory: str | Path) -> pd.DataFrame:
    """Every row on disk in a sweep directory, sorted by ``point`` (no lock: a reader may read
    while a sweep writes, and sees the parts finished so far).

    Raises:
        OutputError: a part cannot be read (the message names it; a resuming sweep sets it
            aside and recomputes its points).
    """
    import pandas as pd

    found = parts(directory)
    if not found:
        return pd.DataFrame()
    frames = []
    for part in found:
        try:
            frames.append(pd.read_parquet(part))
        except (OSError, ValueError) as e:  # pyarrow's ArrowInvalid is a ValueError
            raise OutputError(f"cannot read sweep part {part}: {e}; rerun the sweep with the "
                              "same spec and --out to recompute its points") from e
    df = pd.concat(frames, ignore_index=True)
    return df.sort_values("point", kind="stable").reset_index(drop=True)


class ResultStore:
    """The rows of one sweep, on disk in ``directory``, written by this process alone.

    Use it as a context manager (or call :meth:`close`) so that the directory's lock is released.

    Args:
        directory: The output directory (created if missing).
        spec: The sweep's canonical spec (JSON-serialisable; lists, not tuples). It identifies
            the sweep: an existing directory must hold the same spec.
        metadata: Extra manifest entries written when the directory is new (robot, software
            versions, …); not compared on resume.

    Attributes:
        lock: The directory's lock (its ``stale`` says whose stale lock was taken over).

    Raises:
        DirectoryLockedError: another running sweep writes to the directory (names its pid,
            host and start time).
        ConfigError: the directory holds a different sweep (the message lists the differences)
            or an unreadable manifest.
        OutputError: the directory cannot be created or written.
    """

    def __init__(self, directory: str | Path, spec: Mapping[str, Any],
                 metadata: Mapping[str, Any] | None = None) -> None:
        self.directory = Path(directory)
        self.spec = json.loads(json.dumps(spec))  # canonical: tuples → lists, keys as str
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
        except OSError as e:
            raise OutputError(f"cannot write the sweep manifest in {self.directory}: {e}") from e
        self.lock = DirectoryLock(self.directory)
        try:
            self.manifest = self._open_manifest(metadata)
            for stray in self.directory.glob(".*.tmp"):  # a killed writer's, never a live one's
                stray.unlink(missing_ok=True)
        except BaseException:
            self.lock.release()
            raise

    def _open_manifest(self, metadata: Mapping[str, Any] | None) -> dict[str, Any]:
        path, legacy = self.directory / MANIFEST, self.directory / LEGACY_MANIFEST
        if not path.exists() and legacy.exists():
            os.replace(legacy, path)
        if path.exists() or path.is_symlink():
            try:  # bounded, a regular file, not through a link
                manifest = read_json(path, "sweep manifest", follow=False)
                old = manifest["spec"]
            except (ConfigError, KeyError, TypeError) as e:
                raise ConfigError(f"{path} is not a hexaleg sweep manifest: {e}") from e
            diff = spec_differences(old, self.spec)
            if diff:
                raise ConfigError(f"{self.directory} holds a different sweep; use another --out "
                                  "directory or the same spec. Differences (old → new): "
                                  + "; ".join(diff))
            return dict(manifest)
        manifest = {"spec": self.spec, **(metadata or {})}
        try:
            _write_atomic(path, lambda f: f.write(json_text(manifest, indent=2).encode()))
        except OSError as e:
            raise OutputError(f"cannot write the sweep manifest {path}: {e}") from e
        return manifest

    def close(self) -> None:
        """Release the directory's lock (idempotent)."""
        self.lock.release()

    def __enter__(self) -> ResultStore:
        return self

    def __exit__(self, kind: type[BaseException] | None, value: BaseException | None,
                 tb: TracebackType | None) -> None:
        self.close()
        if isinstance(value, KeyboardInterrupt):
            keep(value, f"the {len(self.parts())} finished part(s) in {self.directory} kept "
                        "(the same command resumes the rest)")

    def parts(self) -> list[Path]:
        """The finished part files, sorted by name (= by first point)."""
        return parts(self.directory)

    def _set_aside(self, part: Path, why: str) -> None:
        target = part.with_name(SET_ASIDE + part.name)
        os.replace(part, target)
        first, last = PART.fullmatch(part.name).groups()  # type: ignore[union-attr]
        warnings.warn(f"sweep part {part} {why}; its points ({int(first)}…{int(last)}) will "
                      f"be computed again (the file is kept as {target.name})", HexalegWarning,
                      stacklevel=3)

    def finished(self) -> set[int]:
        """Indices of the points whose rows are on disk.

        Every part is read whole; one that cannot be read, holds no ``point`` column, holds
        points other than its name says, or repeats points of another part is set aside with
        a :class:`~hexaleg.errors.HexalegWarning`, so that its points count as missing.
        """
        import pyarrow.parquet as pq

        done: set[int] = set()
        for part in self.parts():
            first, last = (int(x) for x in PART.fullmatch(part.name).groups())  # type: ignore
            try:
                points = [int(p) for p in pq.read_table(part).column("point").to_pylist()]
            except (OSError, ValueError, KeyError) as e:  # ArrowInvalid is a ValueError
                self._set_aside(part, f"cannot be read ({type(e).__name__}: {e})")
                continue
            if not points or min(points) != first or max(points) != last \
                    or len(set(points)) != len(points):
                self._set_aside(part, "holds other points than its name says")
            elif done & set(points):
                self._set_aside(part, "repeats points of another part")
            else:
                done.update(points)
        return done

    def write(self, rows: pd.DataFrame) -> Path:
        """Write one finished chunk's rows (a ``point`` column of int indices is required).

        Columns with no value in this chunk (``None`` throughout) are stored as strings, so
        that every part has one schema and ``pandas.read_parquet(DIR)`` can read them together.

        Returns:
            The part file.

        Raises:
            OutputError: the file cannot be written.
        """
        import pyarrow as pa
        import pyarrow.parquet as pq

        first, last = int(rows["point"].min()), int(rows["point"].max())
        path = self.directory / f"part-{first:07d}-{last:07d}.parquet"
        table = pa.Table.from_pandas(rows, preserve_index=False)
        schema = pa.schema([f.with_type(pa.string()) if pa.types.is_null(f.type) else f
                            for f in table.schema], metadata=table.schema.metadata)
        try:
            _write_atomic(path, lambda f: pq.write_table(table.cast(schema), f))
        except OSError as e:
            raise OutputError(f"cannot write sweep results {path}: {e}") from e
        return path

    def table(self) -> pd.DataFrame:
        """All rows on disk, one per finished point, sorted by ``point`` (:func:`read_table`)."""
        return read_table(self.directory)
