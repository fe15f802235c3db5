"""Tests of hexaleg.parallel.interrupt: SIGINT and SIGTERM end a run as an exception, held back
while a run publishes, and a pool's workers end with an interrupted run."""

from __future__ import annotations

import multiprocessing
import os
import signal
import time
from concurrent.futures import ProcessPoolExecutor

import pytest
from processes import HAS_PROC, wait_gone

from hexaleg.parallel import interrupt


def test_sigterm_raises_an_interrupt_that_carries_it():
    with interrupt.handled():
        with pytest.raises(interrupt.Interrupted) as e:
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(5)
    assert isinstance(e.value, KeyboardInterrupt) and e.value.signum == signal.SIGTERM
    assert signal.getsignal(signal.SIGTERM) is signal.SIG_DFL  # restored


def test_an_ignored_sigint_stays_ignored_unless_taken():
    old = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        with interrupt.handled():
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.05)  # ignored: nothing raised
        with interrupt.handled(sigint=True), pytest.raises(KeyboardInterrupt):
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(5)
        assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN
    finally:
        signal.signal(signal.SIGINT, old)


def test_deferred_raises_after_the_block():
    done = []
    with interrupt.handled(), pytest.raises(interrupt.Interrupted):
        with interrupt.deferred():
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(0.05)
            done.append("renamed")
    assert done == ["renamed"]


def test_kept_notes():
    e = KeyboardInterrupt()
    assert interrupt.kept(e) == []
    interrupt.keep(e, "a kept")
    interrupt.keep(e, "b kept")
    assert interrupt.kept(e) == ["a kept", "b kept"]


def _sleep(seconds: float) -> int:
    time.sleep(seconds)
    return os.getpid()


@pytest.mark.skipif(not HAS_PROC, reason="needs /proc")
def test_stop_workers_ends_the_items_being_computed():
    pool = ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("fork"),
                               initializer=interrupt.quiet_worker)
    jobs = [pool.submit(_sleep, 60) for _ in range(4)]
    time.sleep(0.5)
    workers = {p.pid for p in pool._processes.values()}
    assert len(workers) == 2
    start = time.monotonic()
    interrupt.stop_workers(pool)
    assert not wait_gone(workers, 30)
    assert time.monotonic() - start < 30  # a hang guard, not a speed assertion
    assert all(j.cancelled() or j.done() for j in jobs[2:])


PARTIAL_WRITE = """
import gc, os, signal, struct, sys, threading, time
from multiprocessing.queues import SimpleQueue
from hexaleg.parallel.forked import fork_map

signal.signal(signal.SIGINT, signal.default_int_handler)  # ignored where the runner ignores it
flag = sys.argv[1]

def work(i):
    if i == 0:  # a result half written when the worker is killed, made certain
        (results,) = [o for o in gc.get_objects() if type(o) is SimpleQueue]
        os.write(results._writer.fileno(), struct.pack("!i", 1 << 20) + b"part")
        open(flag, "w").close()
    time.sleep(60)

def interrupt():
    while not os.path.exists(flag):
        time.sleep(0.01)
    os.kill(os.getpid(), signal.SIGINT)

threading.Thread(target=interrupt, daemon=True).start()
try:
    fork_map(work, [0, 1], workers=2)
except KeyboardInterrupt:
    print("interrupted")
"""


def test_a_worker_killed_while_it_writes_its_result_does_not_hang_the_exit(tmp_path):
    """The pool's manager thread, reading a result half written, used to wait for the rest and
    the interpreter to wait for it at exit: fails on :func:`interrupt.stop_workers` without the
    result pipe's write end closed (the process then hangs until the guard kills it)."""
    import subprocess
    import sys

    proc = subprocess.Popen([sys.executable, "-c", PARTIAL_WRITE, str(tmp_path / "written")],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    try:
        out, err = proc.communicate(timeout=60)  # a hang guard, not a speed assertion
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        pytest.fail("the interrupted map hung at exit")
    assert proc.returncode == 0 and out == "interrupted\n" and "Traceback" not in err, err


def test_an_interrupt_is_found_behind_the_error_it_caused():
    """Ctrl-C inside a C extension's import surfaces as ImportError("initialization failed")
    raised from it (seen importing MuJoCo)."""
    stop = interrupt.Interrupted(signal.SIGTERM)
    try:
        try:
            raise stop
        except KeyboardInterrupt as e:
            raise ImportError("initialization failed") from e
    except ImportError as e:
        assert interrupt.found(e) is stop
    assert interrupt.found(ValueError("no")) is None and interrupt.found(None) is None


def test_an_interrupt_lost_in_a_destructor_is_raised_again_by_check(capsys):
    """Python prints and drops an exception raised in __del__; check() raises it again."""

    class Dropper:
        def __del__(self):
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(0.05)  # the handler runs here, inside __del__: its exception is dropped

    with interrupt.handled():
        interrupt.check()  # nothing received: nothing raised
        Dropper()  # Python would print "Exception ignored in ... __del__" and go on
        with pytest.raises(interrupt.Interrupted):
            interrupt.check()
    interrupt.check()  # cleared with the handlers
    assert capsys.readouterr().err == ""  # not printed
