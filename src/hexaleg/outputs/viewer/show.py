"""A motion with its analysis drawn in the browser with Meshcat (``hexaleg view``).

What is shown (:func:`view_motion`): a motion — a gait cycle, the cycle of a log of the robot's
own gait, the stand → sphere transformation — analysed with its springs, servos and contact,
with the foot forces as arrows and one joint quantity (motor power, motor torque or spring
torque) as joint colours; or (:func:`replay_motion`) a run of ``hexaleg simulate`` replayed
from its motion file
(:mod:`hexaleg.simulation.motion_file`), with the simulated contact forces and joint
quantities. How it is shown (:mod:`hexaleg.outputs.viewer`): one looping Meshcat animation, either

* written to one self-contained HTML page that plays offline (:func:`export_html`,
  ``hexaleg view --html FILE``), or that page served on 127.0.0.1 (:func:`serve`,
  ``hexaleg view``), or
* sent to a live Meshcat server (:func:`animate`, for a notebook).

Sources: Meshcat (meshcat-python 0.3 and its three.js viewer) for the scene and animation
protocol; Pinocchio's ``MeshcatVisualizer`` for the robot geometry; the diverging cool-warm colour
map of K. Moreland, "Diverging Color Maps for Scientific Visualization", ISVC 2009.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import meshcat
import numpy as np
from pinocchio.visualize import MeshcatVisualizer

from hexaleg.checks import one_of, positive, real, typed
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import analyze
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.trajectory import Motion
from hexaleg.outputs.viewer.keyframes import KEYFRAME_BYTES, MAX_FPS
from hexaleg.outputs.viewer.page import page_html, write_page
from hexaleg.outputs.viewer.scene import draw_motion, start_server
from hexaleg.outputs.viewer.server import LOCALHOST, serve_page
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.model import Robot
from hexaleg.robot.registry import DESCRIPTIONS, load
from hexaleg.robot.springs import SpringSet
from hexaleg.simulation.motion_file import SimulatedMotion, motion_path, read_motion

JOINT_QUANTITIES = {"power": ("power", "motor power (W)"),
                    "torque": ("tau_motor", "motor torque (N·m)"),
                    "spring": ("tau_spring", "spring torque (N·m)")}
"""``hexaleg view --joints`` choice → (Analysis and SimulatedMotion attribute, legend label)."""


@dataclass(frozen=True)
class ViewParams:
    """How a motion is drawn; the ``[view]`` table of a hexaleg config file.

    Attributes:
        fps: Keyframes per second of motion time, > 0 and at most
            :data:`~hexaleg.outputs.viewer.keyframes.MAX_FPS` (a memory bound); the motion is
            resampled at this rate (configurations interpolated on the configuration manifold,
            per-sample arrays linearly) and the browser interpolates between keyframes.
        arrow_length: Length of the longest ground-reaction-force arrow, m; the others are
            scaled in proportion to the force magnitude.
        marker_radius: Radius of the coloured joint markers, m.
    """

    fps: float = 30.0
    arrow_length: float = 0.15
    marker_radius: float = 0.018

    def __post_init__(self) -> None:
        real("ViewParams.fps", self.fps, low=0.0, low_open=True, high=MAX_FPS,
             allowed=f"a finite number > 0 and <= {MAX_FPS} keyframes per second (one keyframe "
                     f"costs about {KEYFRAME_BYTES // 1024} kB while the view is built, so "
                     f"{MAX_FPS} fill hexaleg's memory budget for a 1 s motion); 30 is smooth")
        for name in ("arrow_length", "marker_radius"):
            positive(f"ViewParams.{name}", getattr(self, name))


@dataclass(frozen=True)
class ViewedMotion:
    """What ``hexaleg view`` draws (:func:`view_motion`).

    Attributes:
        robot: The robot.
        motion: The motion, T samples.
        forces: World-frame foot forces, shape (T, n_legs, 3), N; None for a fixed base.
        joint_values: The joint colours' quantity, shape (T, nj).
        joint_label: What ``joint_values`` are, with units.
        springs: Which springs the motion was analysed or simulated with, in words (the
            legend's first line), or "".
    """

    robot: Robot
    motion: Motion
    forces: np.ndarray | None
    joint_values: np.ndarray
    joint_label: str
    springs: str = ""

    def options(self, params: ViewParams) -> dict[str, Any]:
        """Keyword arguments of :func:`serve` and :func:`export_html`."""
        return {"forces": self.forces, "joint_values": self.joint_values,
                "joint_label": self.joint_label, "springs": self.springs, "fps": params.fps,
                "arrow_length": params.arrow_length, "marker_radius": params.marker_radius}


def view_motion(robot: Robot, motion: Motion, springs: SpringSet, motor: Actuator, *,
                joints: str = "power", objective: str = "joule",
                contact: ContactParams | None = None, springs_label: str = "") -> ViewedMotion:
    """A robot's motion analysed (:func:`hexaleg.dynamics.prepare.analyze`) for the viewer:
    the foot forces as arrows, one joint quantity as colours.

    Args:
        robot: The robot.
        motion: The motion (a gait cycle, a logged cycle, stand → sphere).
        springs: The springs of the analysis.
        motor: The servos.
        joints: The joint colours: ``"power"`` (motor power, W), ``"torque"`` (motor torque,
            N·m) or ``"spring"`` (spring torque, N·m).
        objective: The force objective (:data:`hexaleg.dynamics.contact.OBJECTIVES`).
        contact: Contact settings (default :class:`~hexaleg.dynamics.contact.ContactParams`).
        springs_label: Which springs these are, in words (the legend says it), or "".

    Raises:
        UnknownNameError: ``joints`` is not one of the choices.
        HexalegError: as :func:`hexaleg.dynamics.prepare.analyze`.
    """
    one_of("joint quantity", joints, JOINT_QUANTITIES)
    result = analyze(robot, motion, springs, motor=motor, objective=objective,
                     contact=contact or ContactParams())
    attr, label = JOINT_QUANTITIES[joints]
    return ViewedMotion(robot=robot, motion=motion,
                        forces=None if motion.fixed_base else result.forces,
                        joint_values=getattr(result, attr), joint_label=label,
                        springs=springs_label)


def replay_motion(directory: str | Path, run: str = "springs", joints: str = "power",
                  robot: Robot | None = None) -> ViewedMotion:
    """A run of ``hexaleg simulate`` for the viewer: its motion file replayed.

    The simulated base and joints (the file's rows,
    :data:`~hexaleg.simulation.motion_file.RECORD_FPS` per second of simulated time,
    resampled at the keyframes as any motion), the simulated contact forces as arrows and the
    simulated joint quantity as colours.

    Args:
        directory: The out directory of ``hexaleg simulate``.
        run: ``"springs"`` (the run with the springs) or ``"baseline"`` (without).
        joints: As :func:`view_motion`, of the simulation.
        robot: The robot; None: the file's own (a registered robot).

    Raises:
        UnknownNameError: ``run`` or ``joints`` is not one of the choices.
        InvalidParameterError: the directory has no motion file of ``run``, the file is of
            another robot, or its robot is not registered and none is given.
        ConfigError: the file is not a motion file of ``hexaleg simulate``.
    """
    path = motion_path(directory, run)
    recorded = read_motion(path)
    return _replayed(recorded, path, joints,
                     robot if robot is not None else load(recorded_robot(recorded, path)))


def recorded_robot(recorded: SimulatedMotion, path: Path) -> str:
    """The file's robot if it is registered (a robot TOML must be given)."""
    if recorded.robot not in DESCRIPTIONS:
        raise InvalidParameterError(f"{path}: robot", recorded.robot,
                                    f"a registered robot ({', '.join(DESCRIPTIONS)}), or give "
                                    "its description (hexaleg view --robot FILE.toml)")
    return recorded.robot


def _simulated_springs(recorded: SimulatedMotion, path: Path) -> str:
    """The springs of a simulated run in words: none for the baseline, else what
    ``simulate.json`` beside the motion file says they were."""
    if recorded.run == "baseline":
        return "none (the run without springs)"
    try:
        design = json.loads((path.parent / "simulate.json").read_text()).get("design")
    except (OSError, ValueError, AttributeError):
        design = None
    return (f"simulated with {design}" if isinstance(design, str) and design
            else "the simulated run's (no simulate.json beside its motion file to name them)")


def _replayed(recorded: SimulatedMotion, path: Path, joints: str, robot: Robot
              ) -> ViewedMotion:
    """The recorded run of ``path`` on ``robot`` (checked), coloured by ``joints``."""
    one_of("joint quantity", joints, JOINT_QUANTITIES)
    recorded.check(robot, str(path))
    attr, label = JOINT_QUANTITIES[joints]
    return ViewedMotion(robot=robot, motion=recorded.motion(), forces=recorded.forces,
                        joint_values=getattr(recorded, attr), joint_label=f"simulated {label}",
                        springs=_simulated_springs(recorded, path))


@typed
def animate(robot: Robot, motion: Motion, *, forces: Any = None, joint_values: Any = None,
            joint_label: str = "", viewer: meshcat.Visualizer | None = None,
            fps: float = 30.0, arrow_length: float = 0.15,
            marker_radius: float = 0.018) -> MeshcatVisualizer:
    """Send a motion to a Meshcat viewer as a looping animation.

    The robot's visual model follows ``motion.q``; a ground plane with a 0.1 m grid is drawn at
    the height of the stance feet. With ``forces``, an arrow at each foot shows its force (hidden
    while the force is zero); with ``joint_values``, a sphere at each joint takes one of
    :data:`~hexaleg.outputs.viewer.colours.N_LEVELS` cool-warm colours on the symmetric scale
    ±max|value| (blue negative, grey ≈ 0, red positive).

    Args:
        robot: The robot the motion belongs to.
        motion: The motion; a periodic motion loops without a jump except the base's return by
            one cycle's displacement.
        forces: Per-sample forces on the feet, world frame, shape (T, n_legs, 3), N, legs in
            ``robot.legs`` order; or None for no arrows.
        joint_values: Per-sample values that colour the joints (e.g. spring torque N·m or
            motor power W), shape (T, nj), columns in ``robot.joint_names`` order; or None.
        joint_label: What ``joint_values`` are, with units (the legend of :func:`export_html`).
        viewer: A ``meshcat.Visualizer`` to draw into; None starts a Meshcat server that
            lives as long as this process (its URL: ``result.viewer.url()``; Meshcat's own
            server, which listens on every network interface — :func:`serve` binds 127.0.0.1).
        fps: Keyframes per second of motion time (see :class:`ViewParams`).
        arrow_length: Length of the longest force arrow, m.
        marker_radius: Radius of the joint markers, m.

    Returns:
        The Pinocchio visualiser driving the scene; its ``viewer`` is the Meshcat visualiser.

    Raises:
        InvalidParameterError: ``forces`` or ``joint_values`` has the wrong shape (the message
            names the expected one) or non-finite entries, ``motion`` does not fit the robot,
            ``viewer`` is not a Meshcat visualiser, or a drawing parameter is not > 0.
    """
    params = ViewParams(fps=fps, arrow_length=arrow_length, marker_radius=marker_radius)
    if viewer is None:
        viewer = start_server()
    elif not isinstance(viewer, meshcat.Visualizer):
        raise InvalidParameterError("viewer", viewer, "a meshcat.Visualizer or None")
    viz, _ = draw_motion(robot, motion, viewer, forces=forces, joint_values=joint_values,
                         joint_label=joint_label, fps=params.fps,
                         arrow_length=params.arrow_length, marker_radius=params.marker_radius)
    return viz


@typed
def serve(robot: Robot, motion: Motion, *, forces: Any = None, joint_values: Any = None,
          joint_label: str = "", springs: str = "", fps: float = 30.0,
          arrow_length: float = 0.15, marker_radius: float = 0.018,
          host: str = LOCALHOST) -> str:
    """Serve the animated motion's page (:func:`export_html`'s, with its legend) on a local
    HTTP server (:mod:`hexaleg.outputs.viewer.server`) that lives as long as the calling Python
    process; a browser opened on the URL, also after a reload, plays it. The keyword arguments
    are those of :func:`export_html`.

    Args:
        robot: The robot.
        motion: The motion.
        host: The address to listen on (default 127.0.0.1: this machine only).

    Returns:
        The view's URL, ``http://127.0.0.1:<port>/``.

    Raises:
        InvalidParameterError: as :func:`animate`; the server cannot listen on ``host``.
    """
    params = ViewParams(fps=fps, arrow_length=arrow_length, marker_radius=marker_radius)
    return serve_page(page_html(robot, motion, forces=forces, joint_values=joint_values,
                                joint_label=joint_label, springs=springs, fps=params.fps,
                                arrow_length=params.arrow_length,
                                marker_radius=params.marker_radius), host)


@typed
def export_html(robot: Robot, motion: Motion, path: str | Path, *, forces: Any = None,
                joint_values: Any = None, joint_label: str = "", springs: str = "",
                fps: float = 30.0, arrow_length: float = 0.15,
                marker_radius: float = 0.018) -> Path:
    """Write the animated motion to one self-contained HTML page that plays offline.

    The page inlines Meshcat's viewer JavaScript from the installed ``meshcat`` package and
    embeds the scene and its animation as data; it needs no server and fetches nothing over the
    network. A legend says which springs are shown and explains the joint colours and the
    force-arrow scale. The other keyword arguments are those of :func:`animate`.

    Args:
        robot: The robot.
        motion: The motion.
        path: Output file; its directory must exist.
        springs: Which springs the motion was analysed with, in words (the legend's first
            line), or "".

    Returns:
        The written path.

    Raises:
        OutputError: the file cannot be written (the message names the path and the reason).
        InvalidParameterError: as :func:`animate`.
    """
    params = ViewParams(fps=fps, arrow_length=arrow_length, marker_radius=marker_radius)
    return write_page(Path(path), page_html(
        robot, motion, forces=forces, joint_values=joint_values, joint_label=joint_label,
        springs=springs, fps=params.fps, arrow_length=params.arrow_length,
        marker_radius=params.marker_radius))


__all__ = ["JOINT_QUANTITIES", "ViewParams", "ViewedMotion", "animate", "export_html",
           "recorded_robot", "replay_motion", "serve", "view_motion"]
