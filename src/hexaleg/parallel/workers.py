"""Pool workers that end with their parent: no orphan keeps computing after a ``kill -9``.

A :class:`concurrent.futures.ProcessPoolExecutor` shuts its workers down when its parent exits
normally, but a parent killed with SIGKILL runs no cleanup, and its workers would go on
computing (and holding memory) as orphans. :func:`watch_parent`, the pool's worker initializer,
prevents that:

* on Linux it asks the kernel to send the worker SIGKILL when its parent dies
  (``prctl(PR_SET_PDEATHSIG, SIGKILL)``, prctl(2), through :mod:`ctypes`);
* elsewhere a daemon thread polls the parent's pid every :data:`POLL_INTERVAL` seconds and
  ends the worker when it has gone (the worker is re-parented, so ``os.getppid()`` changes);
* in both cases the worker ignores SIGINT (its parent answers Ctrl-C and stops it:
  :mod:`hexaleg.parallel.interrupt`), checks that the sweep's process still runs (it may have died
  between the fork and the initializer) and closes the sweep directory's lock descriptor it
  inherited (:func:`hexaleg.parallel.lock.close_inherited`).
"""

from __future__ import annotations

import contextlib
import ctypes
import ctypes.util
import os
import signal
import sys
import threading
import time

from hexaleg.parallel.interrupt import quiet_worker
from hexaleg.parallel.lock import close_inherited, running


def default_workers() -> int:
    """Worker count of the local process pool: the cores this process may use (≥ 1)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not on Linux
        return max(1, os.cpu_count() or 1)


PR_SET_PDEATHSIG = 1
"""prctl(2) option: the signal a process receives when its parent dies (linux/prctl.h)."""
POLL_INTERVAL = 0.5
"""Seconds between two checks of the parent where prctl is not available."""


def _prctl_parent_death() -> bool:
    """Linux: SIGKILL this process when its parent dies. Returns whether that was set up."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)
        return int(libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)) == 0
    except (OSError, AttributeError):
        return False


def _poll_parent(parent: int) -> None:  # pragma: no cover - only where prctl is missing
    while os.getppid() == parent:
        time.sleep(POLL_INTERVAL)
    os._exit(1)


def watch_parent(sweep_pid: int) -> None:
    """Worker initializer: end this worker when its parent process dies.

    Args:
        sweep_pid: The pid of the process that runs the sweep (the pool's owner); with a
            forkserver the worker's parent is the server, which itself ends with that process.
    """
    close_inherited()
    quiet_worker()
    if not _prctl_parent_death():  # pragma: no cover - not Linux
        threading.Thread(target=_poll_parent, args=(os.getppid(),), daemon=True,
                         name="hexaleg-parent-watch").start()
    if not running(sweep_pid):  # the sweep died before the watch began
        with contextlib.suppress(Exception):
            sys.stderr.flush()
        os._exit(1)
