"""MuJoCo's stage timers, switched off while a run steps: they cost 7 % of a step.

MuJoCo times every stage of a step into ``mjData.timer`` (``mjTIMER_STEP``,
``mjTIMER_POSITION``, …) through its global callback ``mjcb_time``, and reads no clock where it
is NULL (MuJoCo documentation, API reference, "Callbacks": ``mjcb_time``; the engine's
``TM_START``/``TM_END`` macros). MuJoCo's Python bindings put a clock there when they make an
``MjData`` and find it NULL, and in MuJoCo 4.0 ``mujoco.set_mjcb_time(None)`` leaves that clock
in place (measured: the C pointer is unchanged and ``mjData.timer`` keeps counting). So every
step read the clock about 30 times: on the default robot 0.68 of a 10.1 µs step
(``analysis/bench_simulate.py``, ``docs/simulate.md`` "Speed"), for timers hexaleg never reads.

:func:`untimed` sets the C pointer to NULL (through :mod:`ctypes`, on the library the bindings
loaded) for the span of a run and puts the clock back after. The timers write only
``mjData.timer``, so the steps are the same to the bit (tested). A timer the user set from
Python (``mujoco.set_mjcb_time``) is left running; where the library or its symbol cannot be
found (a MuJoCo build laid out otherwise), the run steps with the timers, as before.
"""

from __future__ import annotations

import ctypes
import os
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from functools import cache
from pathlib import Path

LIBRARIES = ("libmujoco.so*", "libmujoco*.dylib", "mujoco.dll")
"""File name patterns of MuJoCo's shared library inside the ``mujoco`` package (Linux, macOS,
Windows)."""

_lock = threading.Lock()
_depth = 0
"""Runs stepping untimed now (threads): the first switches the clock off, the last back on."""
_saved: int | None = None
"""The clock :func:`untimed` switched off."""


@cache
def clock_pointer() -> ctypes.c_void_p | None:
    """MuJoCo's ``mjcb_time`` as a pointer that can be written, or None where its library or
    the symbol is not found. Only the library the bindings already loaded is opened
    (``RTLD_NOLOAD`` where the platform has it): a second copy would hold a pointer of its own."""
    import mujoco

    package = Path(mujoco.__file__).parent
    mode = ctypes.DEFAULT_MODE | getattr(os, "RTLD_NOLOAD", 0)
    for pattern in LIBRARIES:
        for path in sorted(package.glob(pattern)):
            try:
                return ctypes.c_void_p.in_dll(ctypes.CDLL(str(path), mode=mode), "mjcb_time")
            except (OSError, ValueError):
                continue
    return None


@contextmanager
def untimed() -> Iterator[None]:
    """MuJoCo's stage timers off inside the ``with`` block, back as they were after (module
    docstring); nested and concurrent blocks switch them back on when the last one ends."""
    import mujoco

    global _depth, _saved
    pointer = clock_pointer()
    if pointer is None or mujoco.get_mjcb_time() is not None:  # the user's own timer runs
        yield
        return
    with _lock:
        if _depth == 0:
            _saved = pointer.value
            pointer.value = None
        _depth += 1
    try:
        yield
    finally:
        with _lock:
            _depth -= 1
            if _depth == 0 and pointer.value is None:  # not since set by a new MjData
                pointer.value = _saved
