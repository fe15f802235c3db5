"""Tests of hexaleg.parallel.workers: the process pool's workers end when the sweep's process
is killed with SIGKILL (no orphans), and a worker whose sweep has already gone ends at once."""

from __future__ import annotations

import os
import signal
import subprocess
import sys

import pytest
from processes import HAS_PROC, children, wait_gone

from hexaleg.parallel import workers

pytestmark = pytest.mark.skipif(not HAS_PROC, reason="reads processes from Linux /proc")

POOL = """
import os, sys, time
from hexaleg.sweep.executors import open_executor
with open_executor("process", workers=2) as pool:
    # both workers started and busy, as in a sweep killed mid-chunk
    futures = [pool.submit(time.sleep, 120) for _ in range(2)]
    print("started", flush=True)
    time.sleep(120)
"""


def test_pool_workers_end_with_a_killed_parent():
    proc = subprocess.Popen([sys.executable, "-c", POOL], stdout=subprocess.PIPE, text=True)
    assert proc.stdout is not None and proc.stdout.readline().strip() == "started"
    pool_workers = children(proc.pid)
    try:
        assert len(pool_workers) == 2
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait()
        assert wait_gone(pool_workers) == set()  # the hang guard of wait_gone is 60 s
    finally:
        for pid in pool_workers:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass


def test_a_worker_whose_sweep_has_gone_ends_at_once():
    """The parent died between the fork and the initializer: the watch ends the worker."""
    gone = subprocess.Popen([sys.executable, "-c", "pass"])
    gone.wait()
    script = ("import sys; from hexaleg.parallel.workers import watch_parent; "
              f"watch_parent({gone.pid}); sys.exit(0)")
    done = subprocess.run([sys.executable, "-c", script], timeout=120)
    assert done.returncode == 1
    alive = subprocess.run([sys.executable, "-c", script.replace(str(gone.pid),
                                                                 "__import__('os').getppid()")],
                           timeout=120)
    assert alive.returncode == 0


def test_prctl_is_set_on_linux():
    if not sys.platform.startswith("linux"):
        pytest.skip("prctl is Linux-only")
    script = ("from hexaleg.parallel.workers import _prctl_parent_death; "
              "import ctypes, ctypes.util; assert _prctl_parent_death(); "
              "libc = ctypes.CDLL(ctypes.util.find_library('c')); sig = ctypes.c_int(); "
              "libc.prctl(2, ctypes.byref(sig), 0, 0, 0); print(sig.value)")  # PR_GET_PDEATHSIG
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         timeout=120)
    assert out.stdout.strip() == str(int(signal.SIGKILL)), out.stderr
    assert workers.PR_SET_PDEATHSIG == 1
