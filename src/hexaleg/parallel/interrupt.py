"""Ctrl-C and a kill end a run as an exception, so that every ``with`` and ``finally`` on the
way out runs: temporary files removed, locks released, pool workers stopped.

Python turns SIGINT into :class:`KeyboardInterrupt`; :func:`handled` (the command line's, for a
command's life) turns SIGTERM into :class:`Interrupted`, a :class:`KeyboardInterrupt` that
carries its signal, so one ``except KeyboardInterrupt`` handles both (exit status 128 + the
signal: 130, 143). :func:`deferred` holds both back for a few renames — a run's files published
into its output directory (:class:`hexaleg.outputs.directory.OutputFolder`) — and raises the
signal right after, so an interrupt never leaves half of a run published. SIGKILL cannot be
caught: what it leaves is handled by the next run (a stale lock, a staging folder).

Pool workers ignore SIGINT (:func:`quiet_worker`): Ctrl-C at a terminal signals the whole
process group, and only the parent, which stops them (:func:`stop_workers`), should answer it.
"""

from __future__ import annotations

import contextlib
import signal
import sys
import threading
from collections.abc import Iterator
from types import FrameType
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # not imported at run time: the command line imports this module
    from concurrent.futures import ProcessPoolExecutor

SIGNALS: tuple[signal.Signals, ...] = (signal.SIGINT, signal.SIGTERM)
"""The signals that end a run as an exception."""


class Interrupted(KeyboardInterrupt):
    """A run ended by a signal (SIGTERM; SIGINT is Python's own :class:`KeyboardInterrupt`).

    Args:
        signum: The signal.

    What the run kept on disk is noted on the exception on its way out (:func:`keep`).
    """

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


_pending: list[int] = []
_received: list[int] = []
"""The signals received while :func:`handled` is in force: an exception raised in a ``__del__``
or a callback is printed and dropped by Python, so :func:`check` raises it again at the next
point that must not go on after an interrupt."""
_deferring = threading.local()


def _raise(signum: int, frame: FrameType | None) -> None:
    _received.append(signum)
    if getattr(_deferring, "depth", 0):
        _pending.append(signum)
        return
    raise _exception(signum)


def _exception(signum: int) -> KeyboardInterrupt:
    return KeyboardInterrupt() if signum == signal.SIGINT else Interrupted(signum)


def check() -> None:
    """Raise the interrupt this process received if it was lost on the way (raised where Python
    drops exceptions: a ``__del__``, a weakref or C callback); called before a run publishes its
    files and when a command ends."""
    if _received:
        raise _exception(_received[0])


@contextlib.contextmanager
def handled(sigint: bool | None = None) -> Iterator[None]:
    """SIGINT and SIGTERM raise (:class:`KeyboardInterrupt`, :class:`Interrupted`) while the
    ``with`` block runs; the previous handlers are restored after it. Call from the main thread.
    One raised where Python drops it (a ``__del__``) is not printed ("Exception ignored in …"):
    :func:`check` raises it again.

    Args:
        sigint: Whether SIGINT is taken also where it was ignored when the process started (a
            command run in the background of a shell script inherits SIGINT ignored, POSIX
            shell semantics, and Python keeps it so); None: taken only where not ignored, as
            Python does. SIGTERM is taken unless it was ignored.
    """
    old = {s: signal.getsignal(s) for s in SIGNALS}
    hook = sys.unraisablehook
    _received.clear()

    def unraisable(info: Any) -> None:  # "Exception ignored in …": check() raises it again
        if not isinstance(info.exc_value, KeyboardInterrupt):
            hook(info)

    sys.unraisablehook = unraisable
    try:
        for s in SIGNALS:
            take = sigint if s == signal.SIGINT and sigint is not None else None
            if take or (take is None and old[s] is not signal.SIG_IGN):
                signal.signal(s, _raise)
        yield
    finally:
        for s, handler in old.items():
            signal.signal(s, handler)
        sys.unraisablehook = hook
        _received.clear()


@contextlib.contextmanager
def deferred() -> Iterator[None]:
    """Hold SIGINT and SIGTERM back while the block runs (in the thread that runs the handlers,
    the main one), then raise the first that came. Only where :func:`handled` is in force; a
    second interrupt during the block is the same interrupt."""
    _deferring.depth = getattr(_deferring, "depth", 0) + 1
    try:
        yield
    finally:
        _deferring.depth -= 1
        if not _deferring.depth and _pending:
            signum = _pending[0]
            _pending.clear()
            raise _exception(signum)


def found(error: BaseException | None) -> KeyboardInterrupt | None:
    """The interrupt ``error`` is, or was raised from or during: an interrupt inside a C
    extension's import surfaces as ``ImportError("initialization failed")`` caused by it."""
    seen: set[int] = set()
    while error is not None and id(error) not in seen:
        if isinstance(error, KeyboardInterrupt):
            return error
        seen.add(id(error))
        error = error.__cause__ or error.__context__
    return None


def keep(interrupt: KeyboardInterrupt, what: str) -> None:
    """Note on an interrupt on its way out what the run keeps (``"out/ kept as it was"``); the
    command line prints the notes in its one line (:func:`kept`)."""
    notes = getattr(interrupt, "kept", None)
    if not isinstance(notes, list):
        notes = []
        interrupt.kept = notes  # type: ignore[attr-defined]
    notes.append(what)


def kept(interrupt: KeyboardInterrupt) -> list[str]:
    """The notes :func:`keep` put on ``interrupt``."""
    notes = getattr(interrupt, "kept", None)
    return list(notes) if isinstance(notes, list) else []


def quiet_worker() -> None:
    """In a pool worker: SIGINT ignored (its parent answers Ctrl-C and stops it), SIGTERM ends
    it at once (the default action, not the parent's handler inherited through the fork)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def stop_workers(pool: ProcessPoolExecutor) -> None:
    """Cancel a process pool's queued work and kill its workers now: an interrupted run must
    not wait for the items being computed (``shutdown(wait=True)`` would).

    A worker killed while it writes its result leaves part of a message in the result pipe,
    and the pool's manager thread, reading it, waits for the rest; the interpreter joins that
    thread at exit, so the run hung after its interrupt (a ``hexaleg design`` stopped by
    Ctrl-C, orphaned with two zombie workers; a map of 32-MB results interrupted 30 times at
    random moments hung 20 times; ``tests/parallel/test_interrupt.py`` makes the half-written
    result certain). The pool's result pipe is also open for writing in this process; with
    that end closed once the workers are killed, the thread reads end-of-file, takes the pool
    as broken and ends (CPython's own path for a worker that died,
    ``_ExecutorManagerThread.terminate_broken``). It is waited for here: ending, it
    closes its wake-up pipe, and the interpreter's exit, waking it at the same moment, wrote
    to the pipe just closed (``OSError: Bad file descriptor``, printed as an exception ignored
    in ``threading._shutdown``; 1 of 10 ``hexaleg design`` runs stopped at random moments)."""
    processes = dict(getattr(pool, "_processes", None) or {})  # no public way before 3.14
    results = getattr(pool, "_result_queue", None)  # the same: the pipe's write end is ours
    manager = getattr(pool, "_executor_manager_thread", None)  # the same
    pool.shutdown(wait=False, cancel_futures=True)  # forgets them
    for process in processes.values():
        with contextlib.suppress(OSError, ValueError):
            process.kill()
    writer = getattr(results, "_writer", None)
    if writer is not None:
        with contextlib.suppress(OSError):
            writer.close()
    if manager is not None:
        manager.join()


__all__ = ["SIGNALS", "Interrupted", "check", "deferred", "found", "handled", "keep", "kept",
           "quiet_worker", "stop_workers"]
