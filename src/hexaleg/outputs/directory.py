"""The output directory of a command: created and proved writable before any work is done."""

from __future__ import annotations

from pathlib import Path

from hexaleg.errors import OutputError


def writable_directory(out: str | Path, what: str) -> Path:
    """Create ``out`` (with parents) and check that a file can be written in it, so that a long
    computation does not end in an unwritable directory.

    Args:
        out: The directory.
        what: What will be written there, for the message (``"the report"``).

    Returns:
        The directory as a :class:`~pathlib.Path`.

    Raises:
        OutputError: the directory cannot be created or written (names it and the reason).
    """
    out = Path(out)
    try:
        out.mkdir(parents=True, exist_ok=True)
        probe = out / ".hexaleg-write-test"
        probe.write_bytes(b"")
        probe.unlink()
    except OSError as e:
        raise OutputError(f"cannot write {what} to the directory {out}: {e}") from e
    return out
