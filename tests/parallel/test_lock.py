"""Tests of hexaleg.parallel.lock: one holder at a time, named to the refused; a lock left by
a killed process is stale and taken over; released locks leave nothing; a forked child does not
keep its parent's lock."""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
import time

import pytest

from hexaleg.errors import DirectoryLockedError, OutputError
from hexaleg.parallel import lock as lock_module
from hexaleg.parallel.lock import LOCK, DirectoryLock, close_inherited

pytestmark = pytest.mark.skipif(lock_module.fcntl is None, reason="flock is POSIX-only")

HOLD = """
import sys, time
from hexaleg.parallel.lock import DirectoryLock
lock = DirectoryLock(sys.argv[1])
print("held", flush=True)
time.sleep(120)
"""


def hold_in_child(directory):
    """A child process that takes the lock and sleeps; returns it once it holds the lock."""
    proc = subprocess.Popen([sys.executable, "-c", HOLD, str(directory)], stdout=subprocess.PIPE,
                            text=True)
    assert proc.stdout is not None and proc.stdout.readline().strip() == "held"
    return proc


def test_the_holder_is_named_to_a_second_process(tmp_path):
    proc = hold_in_child(tmp_path)
    try:
        with pytest.raises(DirectoryLockedError) as e:
            DirectoryLock(tmp_path)
        assert e.value.pid == proc.pid and e.value.host == socket.gethostname()
        assert f"pid {proc.pid} on host {socket.gethostname()}, started " in str(e.value)
        assert str(tmp_path) in str(e.value) and "another --out directory" in str(e.value)
    finally:
        proc.kill()
        proc.wait()


def test_the_lock_of_a_killed_process_is_stale_and_taken_over(tmp_path):
    proc = hold_in_child(tmp_path)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    assert json.loads((tmp_path / LOCK).read_text())["pid"] == proc.pid  # left behind
    lock = DirectoryLock(tmp_path)
    assert lock.stale is not None and f"pid {proc.pid}" in lock.stale
    assert json.loads((tmp_path / LOCK).read_text())["pid"] == os.getpid()
    lock.release()
    lock.release()  # idempotent
    assert not (tmp_path / LOCK).exists()
    again = DirectoryLock(tmp_path)
    assert again.stale is None  # a released lock is not stale
    again.release()


def test_one_holder_within_one_process_too(tmp_path):
    first = DirectoryLock(tmp_path)
    with pytest.raises(DirectoryLockedError, match=rf"pid {os.getpid()}"):
        DirectoryLock(tmp_path)
    first.release()
    DirectoryLock(tmp_path).release()


def test_a_forked_child_closes_its_copy_and_the_lock_ends_with_the_parent(tmp_path):
    """The parent is killed while its forked child (a pool worker) lives on: the child closed its
    inherited descriptor, so the lock is free."""
    script = f"""
import os, sys, time
from hexaleg.parallel.lock import DirectoryLock, close_inherited
lock = DirectoryLock({str(tmp_path)!r})
child = os.fork()
if child == 0:
    close_inherited()
    open({str(tmp_path / "closed")!r}, "w").close()
    time.sleep(120)
    os._exit(0)
print(child, flush=True)
time.sleep(120)
"""
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
    assert proc.stdout is not None
    child = int(proc.stdout.readline())
    deadline = time.monotonic() + 60  # a hang guard
    while not (tmp_path / "closed").exists() and time.monotonic() < deadline:
        time.sleep(0.01)
    try:
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait()
        lock = DirectoryLock(tmp_path)  # the child still runs, but holds nothing
        assert lock.stale is not None
        lock.release()
    finally:
        os.kill(child, signal.SIGKILL)


def test_close_inherited_forgets_the_descriptors(tmp_path):
    lock = DirectoryLock(tmp_path)
    assert lock_module._HELD
    fd = next(iter(lock_module._HELD))
    duplicate = os.dup(fd)  # stands in for the copy a fork inherits
    lock_module._HELD.add(duplicate)
    lock_module._HELD.discard(fd)
    close_inherited()
    assert not lock_module._HELD
    with pytest.raises(OSError):
        os.fstat(duplicate)
    lock._fd = fd
    lock_module._HELD.add(fd)
    lock.release()


def test_an_unwritable_directory_is_an_output_error(tmp_path):
    with pytest.raises(OutputError, match=r"cannot create the sweep lock"):
        DirectoryLock(tmp_path / "missing")


def test_a_dropped_lock_is_released_and_a_forked_copy_never_releases(tmp_path):
    lock = DirectoryLock(tmp_path)
    del lock
    DirectoryLock(tmp_path).release()  # free again
    lock = DirectoryLock(tmp_path)
    child = os.fork()
    if child == 0:  # the copy in a forked process: releasing it must not touch the parent's lock
        lock.release()
        os._exit(0 if (tmp_path / LOCK).exists() else 1)
    _, status = os.waitpid(child, 0)
    assert os.waitstatus_to_exitcode(status) == 0 and (tmp_path / LOCK).exists()
    with pytest.raises(DirectoryLockedError):
        DirectoryLock(tmp_path)
    lock.release()


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_a_zombie_does_not_run():
    """An ended process not yet reaped by its parent: kill(2) still finds it, running() does
    not (a pool worker starting as its sweep is killed must see the sweep gone)."""
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    deadline = time.monotonic() + 60  # a hang guard, not a speed assertion
    while time.monotonic() < deadline:
        with open(f"/proc/{child.pid}/stat") as f:
            if f.read().rsplit(")", 1)[1].split()[0] == "Z":
                break
        time.sleep(0.01)
    try:
        os.kill(child.pid, 0)  # the zombie is still there for kill(2)
        assert not lock_module.running(child.pid)
        assert lock_module.running(os.getpid())
    finally:
        child.wait()
    assert not lock_module.running(child.pid)


def test_a_link_at_the_lock_is_refused_and_its_target_kept(tmp_path):
    """DIR/.lock a symbolic link to another file: the sweep refuses (it used to overwrite the
    target with its lock record and exit 0)."""
    target = tmp_path / "precious.txt"
    target.write_text("keep me")
    sweep = tmp_path / "sweep"
    sweep.mkdir()
    (sweep / LOCK).symlink_to(target)
    with pytest.raises(OutputError, match=r"\.lock is a symbolic link .*remove the link"):
        DirectoryLock(sweep)
    assert target.read_text() == "keep me"
    (sweep / LOCK).unlink()
    (sweep / LOCK).symlink_to(tmp_path / "missing")  # a dangling link: not created through
    with pytest.raises(OutputError, match="symbolic link"):
        DirectoryLock(sweep)
    assert not (tmp_path / "missing").exists()


def test_a_hard_link_or_a_pipe_at_the_lock_is_refused(tmp_path):
    target = tmp_path / "precious.txt"
    target.write_text("keep me")
    sweep = tmp_path / "sweep"
    sweep.mkdir()
    os.link(target, sweep / LOCK)
    with pytest.raises(OutputError, match=r"hard link shared with 1 other name"):
        DirectoryLock(sweep)
    assert target.read_text() == "keep me"
    (sweep / LOCK).unlink()
    os.mkfifo(sweep / LOCK)
    with pytest.raises(OutputError, match="not a regular file"):
        DirectoryLock(sweep)
