"""Executors for sweeps: one ``concurrent.futures.Executor`` interface, three back ends.

* ``"serial"`` — :class:`SerialExecutor` runs each task when it is submitted, in this process (for
  debugging and tests; exceptions surface with a plain traceback).
* ``"process"`` (default) — a local :class:`concurrent.futures.ProcessPoolExecutor` with one worker
  per core. Workers are forked when the parent runs a single Python thread (fast: ~20 ms, nothing
  re-imported); otherwise — a fork of a multi-threaded parent can deadlock, see the
  :mod:`multiprocessing` documentation — they start from a ``forkserver`` that imports
  :mod:`hexaleg.studies.sweep.runner` once (~3 s; the main script then needs the ``if __name__ ==
  "__main__"`` guard, as with ``spawn``).
* ``"dask"`` — a Dask ``distributed`` cluster given by its scheduler address, through
  ``Client.get_executor()`` (Dask's own ``concurrent.futures`` adaptor). Dask is an optional
  dependency (``pip install hexaleg[dask]``) imported only here, only when asked for.

Tasks must be picklable module-level callables with picklable arguments (see
:func:`hexaleg.studies.sweep.runner.evaluate_chunk`); Pinocchio objects never cross process
boundaries.
"""

from __future__ import annotations

import multiprocessing
import os
import threading
from collections.abc import Callable, Iterator
from concurrent.futures import Executor, Future, ProcessPoolExecutor
from contextlib import contextmanager
from typing import Any

from hexaleg.checks import integer
from hexaleg.errors import ExecutorError, InvalidParameterError

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


def default_workers() -> int:
    """Worker count of the local process pool: the cores this process may use (≥ 1)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not on Linux
        return max(1, os.cpu_count() or 1)


def _process_pool(workers: int) -> ProcessPoolExecutor:
    methods = multiprocessing.get_all_start_methods()
    ctx: multiprocessing.context.BaseContext
    if "fork" in methods and threading.active_count() == 1:
        ctx = multiprocessing.get_context("fork")
    else:
        ctx = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
        if ctx.get_start_method() == "forkserver":
            ctx.set_forkserver_preload(["hexaleg.studies.sweep.runner"])
    return ProcessPoolExecutor(max_workers=workers, mp_context=ctx)


@contextmanager
def _dask_executor(address: str) -> Iterator[Executor]:
    try:
        from distributed import Client
    except ImportError as e:
        raise ExecutorError("the dask executor needs dask[distributed] "
                            "(pip install 'hexaleg[dask]')") from e
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
            yield pool
    else:
        with _dask_executor(str(scheduler)) as executor:
            yield executor
