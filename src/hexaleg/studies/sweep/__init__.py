"""The sweep study: a grid of gaits and spring designs, run in parallel, stored as it goes.

:mod:`~hexaleg.studies.sweep.spec` (the grid), :mod:`~hexaleg.studies.sweep.ranges` (axis
values), :mod:`~hexaleg.studies.sweep.optimal` (optimal-spring points),
:mod:`~hexaleg.studies.sweep.runner` (tasks, futures, progress),
:mod:`~hexaleg.studies.sweep.summary` (the best point per set, per metre across gaits),
:mod:`~hexaleg.studies.sweep.store` (Parquet parts + manifest; one writer a directory,
:mod:`~hexaleg.studies.sweep.lock`), :mod:`~hexaleg.studies.sweep.dead_zones` (designs refused
up front) and :mod:`~hexaleg.studies.sweep.executors` (serial, process pool whose workers end
with their parent, :mod:`~hexaleg.studies.sweep.workers`, and Dask). Each point is evaluated by
:class:`hexaleg.design.evaluator.Evaluator`. See ``docs/sweep.md``.
"""

from hexaleg.design.evaluator import RunSpec
from hexaleg.studies.sweep.executors import EXECUTORS, open_executor
from hexaleg.studies.sweep.optimal import OptimalSpec
from hexaleg.studies.sweep.ranges import parse_range
from hexaleg.studies.sweep.runner import (
    SweepResult,
    evaluate_chunk,
    optimal_chunk,
    run_sweep,
)
from hexaleg.studies.sweep.spec import SweepSpec
from hexaleg.studies.sweep.store import ResultStore, read_table
from hexaleg.studies.sweep.summary import summary

__all__ = [
    "EXECUTORS",
    "OptimalSpec",
    "ResultStore",
    "RunSpec",
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
