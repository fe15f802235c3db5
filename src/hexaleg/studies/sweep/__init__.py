"""The sweep study: a grid of gaits and spring designs, run in parallel, stored as it goes.

:mod:`~hexaleg.studies.sweep.spec` (the grid), :mod:`~hexaleg.studies.sweep.ranges` (axis
values), :mod:`~hexaleg.studies.sweep.optimal` (optimal-spring points),
:mod:`~hexaleg.studies.sweep.runner` (tasks, futures, progress),
:mod:`~hexaleg.studies.sweep.store` (Parquet parts + manifest) and
:mod:`~hexaleg.studies.sweep.executors` (serial, process pool, Dask). Each point is evaluated by
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
    summary,
)
from hexaleg.studies.sweep.spec import SweepSpec
from hexaleg.studies.sweep.store import ResultStore

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
    "run_sweep",
    "summary",
]
