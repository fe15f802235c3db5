"""A sweep on a robot's own log (``hexaleg sweep --motion FILE``): the log's cycle is the sweep's
one gait.

The grid's gait axis is the log (:meth:`SweepSpec.gaits` gives one gait, ``{"motion": path,
"cycle": cycle}``), so gait parameters do not apply and are refused by name
(:func:`on_log`). Each worker reads the log once (:func:`hexaleg.scenario.logged.
logged_motion`: one periodic cycle) and keeps its evaluator, as it keeps a generated gait's
(:func:`log_evaluator`); the rows' ``gait.<name>`` columns hold what the cycle measures
(:func:`log_columns`: period, samples, travel per cycle, mean duty factor; NaN for the
parameters a log does not have).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from hexaleg.design.evaluator import Evaluator
from hexaleg.dynamics.prepare import prepare
from hexaleg.errors import InvalidParameterError
from hexaleg.scenario.scenario import Scenario

if TYPE_CHECKING:
    from hexaleg.sweep.spec import SweepSpec

_LOGS: dict[tuple, Evaluator] = {}
"""(run, log path, cycle) → the evaluator of the log's cycle, per process."""


def is_log(gait: Mapping[str, Any]) -> bool:
    """Whether a gait of the grid is a log (:meth:`SweepSpec.gaits` on a logged sweep)."""
    return "motion" in gait


def on_log(spec: SweepSpec, path: str | Path, cycle: str = "auto") -> SweepSpec:
    """``spec`` swept on the log at ``path`` (its cycle: ``--cycle``).

    Raises:
        InvalidParameterError: gait parameters in the spec (``[gait]``, ``--period``,
            ``--samples``), named: the log is the gait.
    """
    if spec.gait:
        raise InvalidParameterError(
            "sweep gait", ", ".join(spec.gait), f"no gait parameters with --motion {path}: the "
            "logged motion is the gait and keeps its own period and samples; remove the [gait] "
            "table (or --period/--samples) or the --motion option")
    return dataclasses.replace(spec, motion=str(path), cycle=cycle)


def log_evaluator(run: Scenario, gait: Mapping[str, Any]) -> Evaluator:
    """The evaluator of a logged gait (``{"motion": path, "cycle": cycle}``), built once per
    process."""
    key = (run.key(), str(gait["motion"]), str(gait["cycle"]))
    if key not in _LOGS:
        from hexaleg.scenario.logged import logged_motion

        robot = run.model
        motion = logged_motion(robot, gait["motion"], gait["cycle"])
        _LOGS[key] = Evaluator(prepare(robot, motion, motor=run.actuator,
                                       contact=run.contact), run.objective)
    return _LOGS[key]


def log_columns(ev: Evaluator, names: tuple[str, ...]) -> dict[str, float]:
    """``gait.<name>`` columns of a logged cycle: period, samples, travel per cycle
    (``stride_length``) and the mean stance fraction (``duty_factor``); NaN for the others."""
    m = ev.motion
    measured = {"period": m.period, "samples": m.n_samples, "stride_length": m.distance,
                "duty_factor": float(m.stance.mean())}
    return {f"gait.{n}": float(measured.get(n, math.nan)) for n in names}
