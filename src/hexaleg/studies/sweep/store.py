"""A resumable on-disk result store: Parquet part files plus a JSON manifest in one directory.

Layout of a sweep directory::

    manifest.json               the spec (canonical JSON), robot, gait, motor, software versions
    part-0000000-0000049.parquet   rows of points 0…49, written when that chunk finished
    part-0000050-0000099.parquet   …

A part file is written to a temporary name and renamed into place (:func:`os.replace`, atomic on
POSIX), so a killed sweep leaves only whole part files (and possibly a stray ``*.tmp`` that is
ignored and removed). Which points are finished is read back from the parts' ``point`` column, so
a restart computes exactly the missing points whatever the chunking. A directory whose manifest
holds a different spec is refused with an error naming the differing keys — two sweeps' rows are
never mixed.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from hexaleg.errors import ConfigError, OutputError

if TYPE_CHECKING:
    import pandas as pd

MANIFEST = "manifest.json"
"""Name of the manifest file in a store directory."""


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


class ResultStore:
    """The rows of one sweep, on disk in ``directory``.

    Args:
        directory: The output directory (created if missing).
        spec: The sweep's canonical spec (JSON-serialisable; lists, not tuples). It identifies
            the sweep: an existing directory must hold the same spec.
        metadata: Extra manifest entries written when the directory is new (robot, software
            versions, …); not compared on resume.

    Raises:
        ConfigError: the directory holds a different sweep (the message lists the differences)
            or an unreadable manifest.
        OutputError: the directory cannot be created or written.
    """

    def __init__(self, directory: str | Path, spec: Mapping[str, Any],
                 metadata: Mapping[str, Any] | None = None) -> None:
        self.directory = Path(directory)
        self.spec = json.loads(json.dumps(spec))  # canonical: tuples → lists, keys as str
        path = self.directory / MANIFEST
        if path.exists():
            try:
                manifest = json.loads(path.read_text())
                old = manifest["spec"]
            except (OSError, ValueError, KeyError) as e:
                raise ConfigError(f"{path} is not a hexaleg sweep manifest: {e}") from e
            diff = spec_differences(old, self.spec)
            if diff:
                raise ConfigError(f"{self.directory} holds a different sweep; use another --out "
                                  "directory or the same spec. Differences (old → new): "
                                  + "; ".join(diff))
            self.manifest = manifest
        else:
            self.manifest = {"spec": self.spec, **(metadata or {})}
            try:
                self.directory.mkdir(parents=True, exist_ok=True)
                self._write_atomic(path, json.dumps(self.manifest, indent=2).encode())
            except OSError as e:
                raise OutputError(f"cannot write the sweep manifest {path}: {e}") from e
        for stray in self.directory.glob("*.tmp"):
            stray.unlink(missing_ok=True)

    @staticmethod
    def _write_atomic(path: Path, payload: bytes) -> None:
        tmp = path.with_name(path.name + ".tmp")
        tmp.write_bytes(payload)
        os.replace(tmp, path)

    def parts(self) -> list[Path]:
        """The finished part files, sorted by name (= by first point)."""
        return sorted(self.directory.glob("part-*.parquet"))

    def finished(self) -> set[int]:
        """Indices of the points whose rows are on disk."""
        import pandas as pd

        done: set[int] = set()
        for part in self.parts():
            done.update(int(p) for p in pd.read_parquet(part, columns=["point"])["point"])
        return done

    def write(self, rows: pd.DataFrame) -> Path:
        """Write one finished chunk's rows (a ``point`` column of int indices is required).

        Returns:
            The part file.

        Raises:
            OutputError: the file cannot be written.
        """
        first, last = int(rows["point"].min()), int(rows["point"].max())
        path = self.directory / f"part-{first:07d}-{last:07d}.parquet"
        tmp = path.with_name(path.name + ".tmp")
        try:
            rows.to_parquet(tmp, index=False)
            os.replace(tmp, path)
        except OSError as e:
            raise OutputError(f"cannot write sweep results {path}: {e}") from e
        return path

    def table(self) -> pd.DataFrame:
        """All rows on disk, one per finished point, sorted by ``point``."""
        import pandas as pd

        parts = self.parts()
        if not parts:
            return pd.DataFrame()
        df = pd.concat([pd.read_parquet(p) for p in parts], ignore_index=True)
        return df.sort_values("point", kind="stable").reset_index(drop=True)
