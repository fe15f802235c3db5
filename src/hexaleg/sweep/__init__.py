"""The sweep study: a grid of gaits and spring designs, run in parallel, stored as it goes.

:mod:`~hexaleg.sweep.spec` (the grid), :mod:`~hexaleg.sweep.ranges` (axis
values), :mod:`~hexaleg.sweep.optimal` (optimal-spring points),
:mod:`~hexaleg.sweep.runner` (tasks, futures, progress),
:mod:`~hexaleg.sweep.summary` (the best point per set, per metre across gaits),
:mod:`~hexaleg.sweep.store` (Parquet parts + manifest; one writer a directory,
:mod:`~hexaleg.parallel.lock`), :mod:`~hexaleg.sweep.dead_zones` (designs refused
up front) and :mod:`~hexaleg.sweep.executors` (serial, process pool whose workers end
with their parent, :mod:`~hexaleg.parallel.workers`, and Dask). Each point is evaluated by
:class:`hexaleg.design.evaluator.Evaluator`. See ``docs/sweep.md``.
"""

from hexaleg.sweep.executors import EXECUTORS, open_executor
from hexaleg.sweep.optimal import OptimalSpec
from hexaleg.sweep.ranges import parse_range
from hexaleg.sweep.runner import (
    SweepResult,
    evaluate_chunk,
    optimal_chunk,
    run_sweep,
)
from hexaleg.sweep.spec import SweepSpec
from hexaleg.sweep.store import ResultStore, read_table
from hexaleg.sweep.summary import summary

__all__ = [
    "EXECUTORS",
    "OptimalSpec",
    "ResultStore",
    "SweepResult",
    "SweepSpec",
    "evaluate_chunk",
    "open_executor",
    "optimal_chunk",
    "parse_range",
    "read_table",
    "run_sweep",
    "summary",
]
