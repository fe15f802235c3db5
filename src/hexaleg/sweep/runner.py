"""Run a sweep: every point of a :class:`~hexaleg.sweep.spec.SweepSpec`, in parallel,
written to disk as chunks finish, resumable.

Data flow
---------
A *point* is (gait parameters, spring design per joint group). Points sharing a gait share one
:class:`~hexaleg.design.evaluator.Evaluator` (one :func:`hexaleg.dynamics.prepare.prepare`).
Workers never receive Pinocchio objects: a task (:func:`evaluate_chunk`) carries the small
picklable :class:`~hexaleg.scenario.scenario.Scenario` and the gait parameters, and each worker
keeps its evaluators in a per-process cache (:func:`hexaleg.design.evaluator.evaluator`).

Results are a tidy :class:`pandas.DataFrame`, one row per point, written incrementally by
:class:`hexaleg.sweep.store.ResultStore`; executors come from
:mod:`hexaleg.sweep.executors`. See ``docs/sweep.md``.
"""

from __future__ import annotations

import dataclasses
import functools
import importlib.metadata
import itertools
import math
import platform
import sys
import warnings
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from concurrent.futures import FIRST_COMPLETED, Executor, Future, wait
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from hexaleg.checks import typed
from hexaleg.design.evaluator import (
    SPRING_PARAMETERS,
    Design,
    Evaluator,
    evaluator,
    metric_row,
)
from hexaleg.design.families import family
from hexaleg.design.search.optimal import optimal_springs
from hexaleg.errors import (
    HexalegWarning,
    InfeasibleForcesError,
    TorqueLimitError,
)
from hexaleg.parallel.workers import default_workers
from hexaleg.robot.mirror import mirror
from hexaleg.robot.model import Robot
from hexaleg.scenario.scenario import Scenario
from hexaleg.sweep import executors, logged
from hexaleg.sweep.dead_zones import check_dead_zones
from hexaleg.sweep.executors import open_executor
from hexaleg.sweep.optimal import OptimalPoint, OptimalSpec
from hexaleg.sweep.spec import SweepSpec
from hexaleg.sweep.spec_tables import GAIT_PARAMETERS
from hexaleg.sweep.store import ResultStore

if TYPE_CHECKING:  # pandas is imported where tables are made: `import hexaleg` stays light
    import pandas as pd


# --------------------------------------------------------------------------- one task


def evaluate_chunk(run: Scenario, gait: Mapping[str, Any], groups: Mapping[str, Sequence[str]],
                   points: Sequence[tuple[int, Design]]) -> pd.DataFrame:
    """Rows of a chunk of points sharing one gait (the task a worker runs).

    Args:
        run: Robot, motor, objective, contact (picklable; the worker rebuilds the robot).
        gait: GaitParams keyword arguments.
        groups: Group → joint names.
        points: (point index, design) pairs.

    Returns:
        One row per point: ``point``, the gait parameters (:func:`gait_columns`), the design
        (``<group>.<parameter>``, NaN for a group without a spring at that point, see
        ``springs``), ``springs`` (the sprung groups joined by ``+``, or ``baseline``), then
        :meth:`~hexaleg.design.evaluator.Evaluator.row`.
    """
    import pandas as pd

    ev = _evaluator(run, gait)
    ev.prepared.reset_warm_start(ev.objective)  # a chunk's rows do not depend on the last chunk
    columns = gait_columns(run, gait)  # one gait per chunk
    rows = []
    for index, design in points:
        row: dict[str, Any] = {"point": index, **columns}
        row["springs"] = "+".join(design) or "baseline"
        row.update(_design_columns(groups, design))
        row.update(ev.row(groups, design))
        rows.append(row)
    return pd.DataFrame(rows)


def _evaluator(run: Scenario, gait: Mapping[str, Any]) -> Evaluator:
    """The evaluator of a gait of the grid: generated, or a log (:mod:`.logged`)."""
    if logged.is_log(gait):
        return logged.log_evaluator(run, gait)
    return evaluator(run.with_gait(gait))


def gait_columns(run: Scenario, gait: Mapping[str, Any]) -> dict[str, float]:
    """``gait.<name>`` columns: every :data:`GAIT_PARAMETERS` value of the gait (the robot's own
    gait under the point's values), NaN where a parameter is None; of a log, what its cycle
    measures (:func:`~hexaleg.sweep.logged.log_columns`)."""
    if logged.is_log(gait):
        return logged.log_columns(logged.log_evaluator(run, gait), GAIT_PARAMETERS)
    full = dataclasses.asdict(run.with_gait(gait).gait)
    return {f"gait.{name}": math.nan if full[name] is None else full[name]
            for name in GAIT_PARAMETERS}


def optimal_chunk(run: Scenario, gait: Mapping[str, Any], groups: Mapping[str, Sequence[str]],
                  optimal: OptimalSpec, points: Sequence[tuple[int, OptimalPoint]]
                  ) -> pd.DataFrame:
    """Rows of a chunk of optimal-spring points sharing one gait (the task a worker runs).

    Returns:
        One row per point: ``point``, the gait parameters, ``springs`` (the sprung groups joined
        by ``+``), ``family``, the magnitudes and geometry (:meth:`OptimalSpec.columns`; SI,
        angles from each joint's centre of motion, NaN where the point has none and for an angle
        past which nothing acts, :meth:`~hexaleg.design.families.family.Family.idle`; a group's
        mirrored joints, :func:`hexaleg.robot.mirror.mirror`, get its spring mirrored, so a
        class shares one physical design as in ``hexaleg design``), the
        :func:`~hexaleg.design.evaluator.metric_row` columns and ``notes``. A point whose
        program has no solution has that error as its ``status``.
    """
    import pandas as pd

    ev = _evaluator(run, gait)
    ev.prepared.reset_warm_start(ev.objective)  # a chunk's rows do not depend on the last chunk
    columns = optimal.columns(list(groups))
    gait_row = gait_columns(run, gait)  # one gait per chunk
    mirrored = mirror(ev.robot).mirrored  # one physical spring a group, as hexaleg design
    rows = []
    for index, (fam, sprung) in points:
        row: dict[str, Any] = {"point": index, **gait_row, "springs": "+".join(sprung),
                               "family": fam}
        row.update({c: (None if c.endswith(".side") else math.nan) for c in columns})
        try:
            res = optimal_springs(ev.prepared, {g: groups[g] for g in sprung}, fam,
                                  run.objective, max_torque=optimal.max_torque,
                                  max_deflection=optimal.max_deflection, mirrored=mirrored)
        except (InfeasibleForcesError, TorqueLimitError) as e:
            row.update(metric_row(None, ev.baseline, e))
            row["notes"] = ""
        else:
            for g in sprung:
                idle = family(fam).idle(res.magnitudes[g])
                row.update({f"{g}.{n}": v for n, v in res.magnitudes[g].items()})
                row.update({f"{g}.{n}": math.nan if n in idle else v
                            for n, v in res.geometry[g].items()})
            row.update(metric_row(res.analysis.metrics, ev.baseline))
            row["notes"] = "; ".join(res.notes)
        rows.append(row)
    return pd.DataFrame(rows)


def _design_columns(groups: Mapping[str, Sequence[str]], design: Design) -> dict[str, float]:
    """``<group>.<parameter>`` columns; defaults filled in (k⁻ = k, offset 0), NaN for a dead-zone
    form the design does not use and for every parameter of a group without a spring."""
    out = {}
    for g in groups:
        params = dict(design.get(g, {}))
        if params:
            params.setdefault("k_minus", params["k"])
            params.setdefault("offset", 0.0)
        for p in SPRING_PARAMETERS:
            out[f"{g}.{p}"] = float(params[p]) if p in params else math.nan
    return out


# --------------------------------------------------------------------------- running sweeps


@dataclass
class SweepResult:
    """The outcome of :func:`run_sweep`.

    Attributes:
        table: One row per point, sorted by ``point``.
        directory: Where the parts and manifest are.
        computed: Points evaluated by this call.
        reused: Points found finished on disk and not recomputed.
    """

    table: pd.DataFrame
    directory: Path
    computed: int
    reused: int


def software_versions() -> dict[str, str]:
    """Versions of Python and the libraries a sweep's numbers depend on."""
    import pandas as pd
    import pinocchio
    import scipy

    return {"hexaleg": importlib.metadata.version("hexaleg"), "python": platform.python_version(),
            "pinocchio": pinocchio.__version__, "numpy": np.__version__,
            "scipy": scipy.__version__, "pandas": pd.__version__}


def _metadata(spec: SweepSpec, robot: Robot, groups: Mapping[str, tuple[str, ...]]
              ) -> dict[str, Any]:
    """Manifest entries beside the spec: robot, motor, gaits, number of points, versions; a
    logged sweep's quality figures (:func:`~hexaleg.scenario.logged.quality_data`)."""
    from hexaleg.scenario.logged import quality_data

    return {
        "robot": {"name": robot.name, "description": spec.run.robot,
                  "urdf": str(robot.urdf_path), "nq": robot.model.nq,
                  "nv": robot.model.nv, "mass_kg": robot.mass, "groups": groups},
        "motor": spec.run.actuator.name,
        "gaits": spec.gaits(),
        "n_points": spec.n_points,
        "versions": software_versions(),
        **({"motion_quality": quality_data(_evaluator(spec.run, spec.gaits()[0]).motion)}
           if spec.motion is not None else {}),
    }


def _chunks(spec: SweepSpec, todo: Sequence[int]) -> Iterator[tuple[dict, list[int]]]:
    """Unfinished points grouped by gait, at most ``chunk_size`` per chunk."""
    gaits, n_designs = spec.gaits(), len(spec.points_of_gait())
    for gi, points in itertools.groupby(todo, key=lambda i: i // n_designs):
        block = list(points)
        for start in range(0, len(block), spec.chunk_size):
            yield gaits[gi], block[start:start + spec.chunk_size]


@typed
def run_sweep(spec: SweepSpec, out: str | Path, *, executor: str = "process",
              workers: int | None = None, scheduler: str | None = None,
              progress: bool = False,
              on_chunk: Callable[[pd.DataFrame], None] | None = None) -> SweepResult:
    """Evaluate every point of ``spec``, writing rows to ``out`` as chunks finish; resumable.

    Points already on disk (a sweep killed earlier with the same spec) are not recomputed; a
    part file that cannot be read is set aside and its points computed again, with a
    :class:`~hexaleg.errors.HexalegWarning` (:class:`~hexaleg.sweep.store.ResultStore`).

    Args:
        spec: The sweep.
        out: Output directory (manifest + Parquet parts,
            :class:`hexaleg.sweep.store.ResultStore`).
        executor: ``"process"`` (local pool), ``"serial"`` or ``"dask"``
            (:func:`hexaleg.sweep.executors.open_executor`).
        workers: Local pool size (default: the cores available).
        scheduler: Dask scheduler address (with ``executor="dask"``).
        progress: Show a tqdm progress bar on stderr.
        on_chunk: Called with each finished chunk's rows after they are on disk.

    Returns:
        The full table and counts of computed and reused points.

    Raises:
        UnknownNameError: a group that is neither a joint class nor a joint (lists them).
        InvalidParameterError: a dead zone too wide to ever engage
            (:func:`~hexaleg.sweep.dead_zones.check_dead_zones`).
        ConfigError: ``out`` holds a different sweep (names the differences).
        DirectoryLockedError: another running sweep writes to ``out`` (names its pid, host and
            start time).
        ExecutorError: the Dask scheduler cannot be reached (nothing is computed or lost).
        OutputError: results cannot be written.
    """
    robot = spec.run.model
    groups = spec.groups(robot)
    check_dead_zones(spec, robot, groups)
    if executor == "dask" and scheduler is not None:  # before the output directory is touched
        executors.check_scheduler(scheduler, executors.CONNECT_TIMEOUT)
    with ResultStore(out, spec.to_dict(), _metadata(spec, robot, groups)) as store:
        if store.lock.stale:
            warnings.warn(f"took over the lock of a sweep that ended without releasing it "
                          f"({store.lock.stale}); resuming where it stopped", HexalegWarning,
                          stacklevel=2)
        done = store.finished()
        computed = _run(spec, store, done, groups, executor=executor, workers=workers,
                        scheduler=scheduler, progress=progress, on_chunk=on_chunk)
        return SweepResult(table=store.table(), directory=store.directory, computed=computed,
                           reused=len(done))


def _run(spec: SweepSpec, store: ResultStore, done: set[int],
         groups: Mapping[str, tuple[str, ...]], *, executor: str, workers: int | None,
         scheduler: str | None, progress: bool,
         on_chunk: Callable[[pd.DataFrame], None] | None) -> int:
    """Compute the points of ``spec`` not in ``done`` into ``store``; the points computed."""
    designs = spec.points_of_gait()
    todo = [i for i in range(spec.n_points) if i not in done]
    tasks = ((gait, [(i, designs[i % len(designs)]) for i in block])
             for gait, block in _chunks(spec, todo))
    task: Callable[..., pd.DataFrame] = (
        functools.partial(evaluate_chunk, spec.run, groups=groups) if spec.optimal is None
        else functools.partial(optimal_chunk, spec.run, groups=groups, optimal=spec.optimal))
    # Chunks in flight: enough to keep every worker busy, few enough that an interrupted sweep
    # has computed little that is not on disk yet.
    window = {"serial": 1, "process": 2 * (workers or default_workers())}.get(executor, 64)
    if executor == "process" and todo:
        # Forked workers inherit this process's evaluator cache: build the first gait's
        # evaluator (gait, prepare, baseline) once here instead of once in every worker.
        _evaluator(spec.run, spec.gaits()[todo[0] // len(designs)])
    with open_executor(executor, workers=workers, scheduler=scheduler) as ex:
        return _drain(ex, task, tasks, window, store, total=len(todo) if progress else 0,
                      on_chunk=on_chunk)


def _drain(ex: Executor, task: Callable[..., pd.DataFrame],
           tasks: Iterable[tuple[dict, Sequence[tuple[int, Any]]]], window: int,
           store: ResultStore, *, total: int,
           on_chunk: Callable[[pd.DataFrame], None] | None) -> int:
    """Submit ``task(gait, points=…)`` for each of ``tasks`` with at most ``window`` in flight;
    write each finished chunk to ``store``.

    Args:
        total: Points to show on a tqdm progress bar on stderr; 0 for no bar.

    Returns:
        Points computed.
    """
    pending: set[Future] = set()
    tasks = iter(tasks)

    def refill() -> None:
        for gait, points in itertools.islice(tasks, window - len(pending)):
            pending.add(ex.submit(task, gait, points=points))

    refill()
    bar = None
    computed = 0
    if total:  # after the pool has started: tqdm runs a monitor thread
        from tqdm import tqdm

        bar = tqdm(total=total, file=sys.stderr, unit="pt", desc="sweep")
    try:
        while pending:
            finished, _ = wait(pending, return_when=FIRST_COMPLETED)
            pending -= finished
            refill()
            # a failed chunk first (it raises), then the others in point order
            for fut in sorted(finished, key=lambda f: -1 if f.exception() is not None
                              else int(f.result()["point"].iloc[0])):
                rows = fut.result()
                store.write(rows)
                computed += len(rows)
                if bar is not None:
                    bar.update(len(rows))
                if on_chunk is not None:
                    on_chunk(rows)
    finally:
        for fut in pending:
            fut.cancel()
        if bar is not None:
            bar.close()
    return computed
