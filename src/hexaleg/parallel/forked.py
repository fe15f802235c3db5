"""Independent pieces of one study run in forked processes, one per core, sharing the robot.

A forked child is a copy of this process: every object that existed at the fork is at the same
address in both. A child's result comes back pickled, and the shared objects it refers to (the
robot, its Pinocchio model and data, its visual and collision geometry) are written as their
``id`` and read back as this process's own objects (:mod:`pickle`'s persistent ids). Without
that, a result that refers to the robot carries it: A1's visual meshes alone pickle to 400 MB,
and each of A1's design families, 2 s of work, spent 20 s pickling and unpickling them.

:func:`fork_map` is the same computation as ``[fn(x) for x in items]`` (tested bit for bit); it
runs in this process where it cannot fork or on one core.
"""

from __future__ import annotations

import io
import multiprocessing
import os
import pickle
from collections.abc import Callable, Iterable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from typing import Any, TypeVar

from hexaleg.parallel.interrupt import stop_workers
from hexaleg.robot.model import Robot

T = TypeVar("T")
R = TypeVar("R")

_WORK: list[Any] = []
"""The function, its items and the shared objects by id that the forked workers read
(inherited through the fork, not pickled: the function may be any closure)."""


def robot_objects(robot: Robot) -> tuple[object, ...]:
    """The objects of ``robot`` a result may refer to and should not carry: the robot, its
    model, data and geometry models."""
    return (robot, robot.model, robot.data, robot.visual_model, robot.collision_model)


class _Pickler(pickle.Pickler):
    def __init__(self, file: io.BytesIO, shared: dict[int, object]) -> None:
        super().__init__(file, protocol=pickle.HIGHEST_PROTOCOL)
        self._shared = shared

    def persistent_id(self, obj: object) -> int | None:
        return id(obj) if self._shared.get(id(obj), _Pickler) is obj else None


class _Unpickler(pickle.Unpickler):
    def __init__(self, file: io.BytesIO, shared: dict[int, object]) -> None:
        super().__init__(file)
        self._shared = shared

    def persistent_load(self, pid: Any) -> object:
        return self._shared[pid]


def _run(index: int) -> bytes:
    """One item's result in a forked worker, pickled with the shared objects as their ids."""
    fn, items, shared = _WORK
    out = io.BytesIO()
    _Pickler(out, shared).dump(fn(items[index]))
    return out.getvalue()


def fork_map(fn: Callable[[T], R], items: Sequence[T], *, shared: Iterable[object] = (),
             workers: int | None = None,
             done: Callable[[int, R], None] | None = None) -> list[R]:
    """``[fn(x) for x in items]``, the items spread over forked processes (module docstring).

    Args:
        fn: The work on one item (any callable: the workers inherit it, it is not pickled).
        items: The items.
        shared: Objects of this process the results may refer to, sent back as references
            (e.g. :func:`robot_objects`).
        workers: Processes; default one per core this process may use, at most one per item.
        done: Called in this process with (index, result) as each item ends.

    Returns:
        The results, in the order of ``items``. An exception of ``fn`` is raised here.
    """
    from hexaleg.parallel.workers import default_workers, watch_parent  # patched in tests

    n = min(len(items), workers or default_workers())
    results: dict[int, R] = {}
    if n < 2 or "fork" not in multiprocessing.get_all_start_methods():
        for i, x in enumerate(items):
            results[i] = fn(x)
            if done is not None:
                done(i, results[i])
        return [results[i] for i in range(len(items))]
    table = {id(o): o for o in shared}
    outer = _WORK[:]  # a map inside a worker of another: that worker's work is kept
    _WORK[:] = [fn, items, table]
    try:
        with ProcessPoolExecutor(n, mp_context=multiprocessing.get_context("fork"),
                                 initializer=watch_parent, initargs=(os.getpid(),)) as pool:
            jobs = {pool.submit(_run, i): i for i in range(len(items))}
            try:
                for job in as_completed(jobs):
                    i = jobs[job]
                    results[i] = _Unpickler(io.BytesIO(job.result()), table).load()
                    if done is not None:
                        done(i, results[i])
            except KeyboardInterrupt:  # Ctrl-C or a kill: the items being computed end too
                stop_workers(pool)
                raise
            except BaseException:  # the first failure ends the map: drop the items not begun
                for job in jobs:
                    job.cancel()
                raise
    finally:
        _WORK[:] = outer
    return [results[i] for i in range(len(items))]
