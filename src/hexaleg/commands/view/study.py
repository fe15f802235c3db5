"""``hexaleg view``: a motion of the run drawn in the browser (:mod:`hexaleg.outputs.viewer.show`).

What is shown: one cycle of the run's gait (or of its log, ``--motion FILE``) or the stand →
sphere transformation, analysed with the report's settings of the config file (servos, contact,
objective: :class:`~hexaleg.report.config.ReportConfig`) and the springs the report analyses
(its answer's, else the configured or reference springs; the legend names them), drawn with its
``[view]`` table; or a run of ``hexaleg simulate`` replayed from its motion file
(``--simulation DIR``). Served on 127.0.0.1 until Ctrl-C (:func:`serve_view`) or written as an
offline page (:func:`export_view`) — the same page.
"""

from __future__ import annotations

import argparse
import signal
import time
from collections.abc import Callable
from pathlib import Path

from hexaleg.commands.options import load_run
from hexaleg.config import from_mapping
from hexaleg.dynamics.prepare import prepare
from hexaleg.errors import InvalidParameterError, did_you_mean
from hexaleg.motion.recorded.bag import bag_directory
from hexaleg.motion.trajectory import Motion
from hexaleg.motion.transform import transform_motion
from hexaleg.outputs.viewer.server import LOCALHOST
from hexaleg.outputs.viewer.show import (
    ViewedMotion,
    ViewParams,
    export_html,
    recorded_robot,
    replay_motion,
    serve,
    view_motion,
)
from hexaleg.report.answer import answer_springs
from hexaleg.report.config import ReportConfig, SpringDesign
from hexaleg.robot.springs import SpringSet
from hexaleg.scenario.scenario import Scenario
from hexaleg.simulation.motion_file import motion_path, read_motion

MOTIONS = ("gait", "transform")
"""What ``hexaleg view --motion`` can show besides a log: the gait cycle or stand → sphere."""


def _params(scenario: Scenario) -> ViewParams:
    """The file's ``[view]`` table."""
    return from_mapping(ViewParams, scenario.table("view"), f"{scenario.where} [view]")


def _springs(scenario: Scenario, cfg: ReportConfig, shown: Motion) -> tuple[SpringSet, str]:
    """The springs ``hexaleg report`` analyses on this run — its answer's
    (:func:`hexaleg.report.answer.answer_springs`, designed on the run's gait), else the
    configured or reference springs on the motion shown — and which they are, in words."""
    if cfg.springs is None:
        gait = scenario.motion()
        prepared = prepare(scenario.model, gait, motor=cfg.motor, contact=cfg.contact)
        springs, label, _ = answer_springs(cfg, prepared)
        if springs is not None:
            return springs, label
    reference = cfg.reference(scenario.model)
    if isinstance(reference, SpringDesign):
        label = (f"the {reference.design} design on the {reference.joints} joints"
                 + (" (the paper's, the report's reference)" if cfg.springs is None else ""))
    else:
        label = f"the springs of {scenario.where} [springs]"
    return cfg.spring_set(scenario.model, shown), label


def _shown(config: str | Path | None, motion: str | None, joints: str, robot: str | None,
           simulation: str | Path | None, run: str | None, cycle: str = "auto",
           args: argparse.Namespace | None = None) -> tuple[ViewedMotion, ViewParams]:
    """What ``hexaleg view`` shows and how (module docstring)."""
    if simulation is None:
        if run is not None:
            raise InvalidParameterError("run", run, "a run of a simulation (--simulation DIR)")
        log = None if motion is None or motion in MOTIONS else motion
        if log is not None and not (Path(log).is_file() or bag_directory(Path(log))):
            what = ("exists but is not a regular file or a ROS 2 bag directory"
                    if Path(log).exists() else "does not exist" + did_you_mean(log, MOTIONS))
            raise InvalidParameterError("motion", motion, f"one of {', '.join(MOTIONS)}, or a "
                                        "log of the robot's own gait (a CSV or NPZ file, or a "
                                        f"ROS 2 bag directory; docs/motion.md): {log} {what}")
        scenario = load_run(robot, config, log, cycle, args)
        cfg = ReportConfig.from_scenario(scenario)
        shown = (transform_motion(scenario.model) if motion == "transform"
                 else scenario.motion())
        springs, label = _springs(scenario, cfg, shown)
        return view_motion(scenario.model, shown, springs, cfg.motor, joints=joints,
                           objective=cfg.report.objective, contact=cfg.contact,
                           springs_label=label), _params(scenario)
    if motion is not None:
        raise InvalidParameterError("motion", motion, f"none with a simulation ({simulation}): "
                                    "the replay shows the simulated gait")
    path = motion_path(simulation, run or "springs")
    scenario = load_run(robot or recorded_robot(read_motion(path), path), config)
    return (replay_motion(simulation, run or "springs", joints, scenario.model),
            _params(scenario))


def export_view(config: str | Path | None, html: str | Path, *, motion: str | None = None,
                joints: str = "power", robot: str | None = None,
                simulation: str | Path | None = None, run: str | None = None,
                cycle: str = "auto", args: argparse.Namespace | None = None) -> Path:
    """``hexaleg view --html``: what is shown (module docstring) written as an offline page.

    Args:
        config: The config file (only its ``[view]`` table applies to a replay), or None.
        html: The page to write.
        motion: ``"gait"`` (default), ``"transform"`` or a log of the robot's own gait
            (``--motion FILE``); not with ``simulation``.
        joints: The joint colours (:data:`hexaleg.outputs.viewer.show.JOINT_QUANTITIES`).
        robot: The robot (default the built-in one; for a replay, the motion file's).
        simulation: An out directory of ``hexaleg simulate`` to replay, or None.
        run: ``"springs"`` (default) or ``"baseline"``; only with ``simulation``.
        cycle: With a log: which part of it is the cycle.
        args: The command's parsed options, which keep the run (its log's quality printed
            after the command, :func:`hexaleg.commands.options.add_motion_option`).

    Returns:
        The written path.

    Raises:
        InvalidParameterError: ``motion`` with ``simulation``, ``run`` without it, a ``motion``
            that is neither a choice nor a file; as the run's loader
            (:func:`hexaleg.commands.options.load_run`) and the viewer.
    """
    shown, params = _shown(config, motion, joints, robot, simulation, run, cycle, args)
    return export_html(shown.robot, shown.motion, html, **shown.options(params))


def serve_view(config: str | Path | None, *, motion: str | None = None,
               joints: str = "power", robot: str | None = None,
               simulation: str | Path | None = None, run: str | None = None,
               cycle: str = "auto", args: argparse.Namespace | None = None,
               host: str = LOCALHOST) -> str:
    """``hexaleg view``: what is shown, served (:func:`hexaleg.outputs.viewer.show.serve`) on
    ``host`` (default 127.0.0.1, this machine only); the other arguments are those of
    :func:`export_view`.

    Returns:
        The view's URL.
    """
    shown, params = _shown(config, motion, joints, robot, simulation, run, cycle, args)
    return serve(shown.robot, shown.motion, **shown.options(params), host=host)


def wait_until_interrupted(ready: Callable[[], None] | None = None) -> None:
    """Block until Ctrl-C or a kill (SIGTERM), both of which then leave through the normal exit
    that stops the server of :func:`serve_view` (it lives as long as this process).
    Call from the main thread. Ctrl-C (SIGINT) is taken even where it was ignored when the
    process started (a command run in the background of a script inherits SIGINT ignored,
    POSIX shell semantics; Python then keeps it ignored and the server could only be killed).

    Args:
        ready: Called once both signals are taken (e.g. to print the URL and "Ctrl-C to stop":
            a Ctrl-C before that line is one the process could have lost)."""
    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, signal.default_int_handler)
    try:
        if ready is not None:
            ready()
        while True:
            time.sleep(3600)
    except KeyboardInterrupt:
        return


__all__ = ["MOTIONS", "export_view", "serve_view", "wait_until_interrupted"]
