"""Helpers of the tests that kill processes: which processes a process started, waiting (with
a generous hang guard, not a speed assertion) until processes have ended, and ending a command
started in its own session with every process it started. Linux /proc only."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

PROC = Path("/proc")
HAS_PROC = sys.platform.startswith("linux") and PROC.is_dir()


def _stat(pid: int) -> tuple[str, int] | None:
    """(state, parent pid) of a process, or None when it is gone."""
    try:
        text = (PROC / str(pid) / "stat").read_text()
    except (FileNotFoundError, ProcessLookupError):
        return None
    fields = text[text.rindex(")") + 2:].split()  # the name may hold spaces and parentheses
    return fields[0], int(fields[1])


def running(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie, dead but not yet reaped, does not count)."""
    stat = _stat(pid)
    return stat is not None and stat[0] not in ("Z", "X")


def children(pid: int) -> set[int]:
    """The running processes whose parent is ``pid``."""
    found = set()
    for entry in PROC.iterdir():
        if entry.name.isdigit():
            stat = _stat(int(entry.name))
            if stat is not None and stat[1] == pid and stat[0] not in ("Z", "X"):
                found.add(int(entry.name))
    return found


def wait_gone(pids: set[int], guard: float = 60.0) -> set[int]:
    """Wait until none of ``pids`` runs, at most ``guard`` seconds; the ones still running."""
    deadline = time.monotonic() + guard
    alive = {p for p in pids if running(p)}
    while alive and time.monotonic() < deadline:
        time.sleep(0.05)
        alive = {p for p in alive if running(p)}
    return alive


def end_session(proc: subprocess.Popen) -> None:
    """End ``proc`` and every process it started, however it stands, and reap it: ``proc`` was
    started in a session of its own (``start_new_session=True``: its own process group, which
    the workers it forks inherit), so one SIGKILL to the group reaches a hung command and its
    workers alike (killing ``proc`` alone would leave them running, orphaned). A group with no
    process left is no error (the command had ended with its workers); a running ``proc`` that
    leads no group is (it would have been left running): it is killed alone and
    ``AssertionError`` raised."""
    leads = True
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except ProcessLookupError:
        leads = proc.poll() is not None
        if not leads:
            proc.kill()
    proc.wait()
    for stream in (proc.stdin, proc.stdout, proc.stderr):
        if stream is not None:
            stream.close()
    assert leads, f"{proc.args} ran outside a session of its own: its workers may run on"
