"""Executors for sweeps: one ``concurrent.futures.Executor`` interface, three back ends.

* ``"serial"`` — :class:`SerialExecutor` runs each task when it is submitted, in this process (for
  debugging and tests; exceptions surface with a plain traceback).
* ``"process"`` (default) — a local :class:`concurrent.futures.ProcessPoolExecutor` with one worker
  per core; workers end with their parent, even a killed one
  (:func:`hexaleg.parallel.workers.watch_parent`). Workers are forked when the parent runs
  a single Python thread (fast: ~20 ms, nothing re-imported); otherwise — a fork of a
  multi-threaded parent can deadlock, see the :mod:`multiprocessing` documentation — they
  start from a ``forkserver`` that imports :mod:`hexaleg.sweep.runner` once (~3 s;
  the main script then needs the ``if __name__ == "__main__"`` guard, as with ``spawn``).
* ``"dask"`` — a Dask ``distributed`` cluster given by its scheduler address, through
  ``Client.get_executor()`` (Dask's own ``concurrent.futures`` adaptor). Dask is an optional
  dependency (``pip install hexaleg[dask]``) imported only here, only when asked for. Before the
  client connects, a ``tcp://`` address is probed at the protocol level
  (:func:`check_scheduler`): a Dask scheduler greets a new connection at once, so a port that
  accepts the connection but stays silent — a web server such as Dask's dashboard — is refused
  within :data:`CONNECT_TIMEOUT` instead of hanging (Dask's own connect waits for the greeting
  without a limit).

Tasks must be picklable module-level callables with picklable arguments (see
:func:`hexaleg.sweep.runner.evaluate_chunk`); Pinocchio objects never cross process
boundaries.
"""

from __future__ import annotations

import multiprocessing
import os
import socket
import threading
import time
from collections.abc import Callable, Iterator
from concurrent.futures import Executor, Future, ProcessPoolExecutor
from contextlib import contextmanager
from typing import Any

from hexaleg.checks import integer
from hexaleg.errors import ExecutorError, InvalidParameterError
from hexaleg.parallel.interrupt import stop_workers
from hexaleg.parallel.workers import default_workers, watch_parent

EXECUTORS: tuple[str, ...] = ("process", "serial", "dask")
"""Names accepted by :func:`open_executor`, default first."""

CONNECT_TIMEOUT = 10.0
"""Seconds to wait for a Dask scheduler before giving up, s."""


class SerialExecutor(Executor):
    """An executor that runs every task immediately in the calling process.

    ``submit`` returns an already finished :class:`~concurrent.futures.Future` holding the result
    or the exception, so code written for a pool runs unchanged (and deterministically).
    """

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> Future:
        """Run ``fn(*args, **kwargs)`` now; return its finished future."""
        future: Future = Future()
        try:
            future.set_result(fn(*args, **kwargs))
        except Exception as e:  # the future carries it to whoever asks for the result
            future.set_exception(e)
        return future


def _process_pool(workers: int) -> ProcessPoolExecutor:
    methods = multiprocessing.get_all_start_methods()
    ctx: multiprocessing.context.BaseContext
    if "fork" in methods and threading.active_count() == 1:
        ctx = multiprocessing.get_context("fork")
    else:
        ctx = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
        if ctx.get_start_method() == "forkserver":
            ctx.set_forkserver_preload(["hexaleg.sweep.runner"])
    return ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=watch_parent,
                               initargs=(os.getpid(),))


DASK_SCHEMES: tuple[str, ...] = ("tcp", "tls", "inproc", "ucx", "ws", "wss")
"""Protocols of a Dask scheduler address (``scheme://host:port``; no scheme means tcp)."""


def _silent_peer(address: str, sock: socket.socket, timeout: float, left: float
                 ) -> ExecutorError:
    """The error for a port that accepted the connection but sent no Dask greeting within
    ``timeout``; ``left`` seconds remain to ask whether it speaks HTTP."""
    answer = "nothing"
    try:  # is it a web server? (Dask's dashboard usually is, on port 8787)
        sock.settimeout(max(0.05, left))
        sock.sendall(b"GET / HTTP/1.0\r\n\r\n")
        if sock.recv(5).startswith(b"HTTP"):
            answer = "HTTP: a web server (Dask's dashboard, on port 8787 by default?)"
    except OSError:
        pass
    return ExecutorError(
        f"{address!r} accepts connections but does not speak the Dask protocol: no scheduler "
        f"greeting within {timeout:g} s, and it answers {answer}. Give the scheduler's own "
        "address (tcp://host:8786 by default; `dask scheduler` prints it)")


def check_scheduler(address: str, timeout: float) -> None:
    """Check at the protocol level that ``address`` is a Dask scheduler, within ``timeout`` s.

    A ``tcp://`` (or scheme-less ``host:port``) address is connected to and must send the
    scheduler's greeting (its handshake, which Dask servers write first) within ``timeout``;
    other schemes are left to Dask's client.

    Args:
        address: The scheduler address, e.g. ``"tcp://10.0.0.5:8786"``.
        timeout: Seconds for the connection and the greeting together.

    Raises:
        ExecutorError: an unknown scheme, no port, nothing listening, or a listener that does
            not speak the Dask protocol (names the address, what answered and what to give).
    """
    scheme, _, location = address.rpartition("://")
    scheme = scheme or "tcp"
    if scheme not in DASK_SCHEMES:
        raise ExecutorError(f"scheduler address {address!r}: {scheme}:// is not a Dask protocol "
                            f"(one of {', '.join(DASK_SCHEMES)}); give tcp://host:8786")
    if scheme != "tcp":
        return
    host, sep, port = location.rpartition(":")
    if not sep or not port.isdigit() or not host:
        raise ExecutorError(f"scheduler address {address!r} has no host:port; give e.g. "
                            "tcp://host:8786")
    deadline = time.monotonic() + timeout
    try:
        with socket.create_connection((host.strip("[]"), int(port)), timeout=timeout) as sock:
            # a scheduler greets within milliseconds; the last quarter of the time is for
            # asking a silent listener whether it is a web server
            sock.settimeout(max(0.05, deadline - time.monotonic() - timeout / 4))
            try:
                greeting = sock.recv(8)
            except TimeoutError:
                raise _silent_peer(address, sock, timeout,
                                   deadline - time.monotonic()) from None
            if not greeting:
                raise ExecutorError(f"{address!r} closed the connection without a Dask "
                                    "greeting; is it a Dask scheduler?")
    except OSError as e:
        raise ExecutorError(f"cannot reach the Dask scheduler at {address!r} within "
                            f"{timeout:g} s: {e}") from e


@contextmanager
def _dask_executor(address: str) -> Iterator[Executor]:
    try:
        from distributed import Client
    except ImportError as e:
        raise ExecutorError("the dask executor needs dask[distributed] "
                            "(pip install 'hexaleg[dask]')") from e
    check_scheduler(address, CONNECT_TIMEOUT)
    try:
        client = Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False)
    except (OSError, TimeoutError, ValueError) as e:
        raise ExecutorError(f"cannot reach the Dask scheduler at {address!r} within "
                            f"{CONNECT_TIMEOUT:g} s: {e}") from e
    try:
        yield client.get_executor(pure=False)
    finally:
        client.close()


@contextmanager
def open_executor(kind: str = "process", *, workers: int | None = None,
                  scheduler: str | None = None) -> Iterator[Executor]:
    """An executor for sweep tasks, shut down when the ``with`` block ends.

    Args:
        kind: One of :data:`EXECUTORS`: ``"process"`` (local pool), ``"serial"`` or ``"dask"``.
        workers: Local pool size (``"process"`` only), ≥ 1; default :func:`default_workers`.
        scheduler: Dask scheduler address such as ``"tcp://10.0.0.5:8786"`` (required for, and
            only used by, ``"dask"``).

    Yields:
        A :class:`concurrent.futures.Executor`.

    Raises:
        InvalidParameterError: unknown ``kind``, ``workers`` < 1, a scheduler address without
            ``"dask"`` or ``"dask"`` without one.
        ExecutorError: the Dask scheduler cannot be reached (names the address), or Dask is not
            installed.
    """
    if kind not in EXECUTORS:
        raise InvalidParameterError("executor", kind, "one of " + ", ".join(EXECUTORS))
    if workers is not None:
        integer("workers", workers, low=1)
    if (kind == "dask") != (scheduler is not None):
        raise InvalidParameterError("scheduler", scheduler,
                                    "a scheduler address exactly when the executor is dask")
    if kind == "serial":
        yield SerialExecutor()
    elif kind == "process":
        with _process_pool(workers or default_workers()) as pool:
            try:
                yield pool
            except KeyboardInterrupt:  # Ctrl-C or a kill: the chunks being computed end too
                stop_workers(pool)
                raise
    else:
        with _dask_executor(str(scheduler)) as executor:
            yield executor
