"""The Meshcat scene of a motion: robot, ground, foot-force arrows and coloured joint markers.

The robot's visual model is drawn by Pinocchio's :class:`pinocchio.visualize.MeshcatVisualizer`;
on top of it come a ground plane with a 0.1 m grid, ground-reaction-force arrows at the feet and
a colour-coded marker at every joint. The whole motion is sent to the viewer as one looping
Meshcat animation (:mod:`~hexaleg.outputs.viewer.keyframes`). Joint colours are a stack of
pre-coloured spheres per joint of which one is visible at a time (a binned colour map): a mesh's
material cannot be animated reliably (see the keyframes module).

Sources: Meshcat (meshcat-python 0.3 and its three.js viewer) for the scene protocol; Pinocchio's
``MeshcatVisualizer`` for the robot geometry.
"""

from __future__ import annotations

import contextlib
import io
import math
from dataclasses import dataclass
from typing import Any

import meshcat
import meshcat.geometry as mg
import numpy as np
import pinocchio as pin
from pinocchio.visualize import MeshcatVisualizer

from hexaleg.errors import InvalidParameterError
from hexaleg.motion.trajectory import Motion
from hexaleg.outputs.viewer.colours import N_LEVELS, colours, value_bins
from hexaleg.outputs.viewer.keyframes import Frames, Tracks, resample
from hexaleg.robot.model import Robot

_GROUND_COLOR = 0xE8E4DA
_GRID_COLOR = 0xB8B2A6
_ARROW_COLOR = 0x00B140
_Y = np.array([0.0, 1.0, 0.0])


@dataclass(frozen=True)
class Legend:
    """What the colours and arrows mean: joint scale half-width and full-length force.

    Attributes:
        joint_label: What the joint values are, with units ("" if unnamed).
        vmax: Half-width of the joint colour scale, or None without joint values.
        fmax: Force drawn ``arrow_length`` long, N, or None without forces.
        arrow_length: Length of the longest force arrow, m.
    """

    joint_label: str
    vmax: float | None
    fmax: float | None
    arrow_length: float


def start_server() -> meshcat.Visualizer:
    """A Meshcat server subprocess (killed when this process exits); its URL names 127.0.0.1,
    though Meshcat's web server listens on every interface (meshcat 0.3 gives no option)."""
    with contextlib.redirect_stdout(io.StringIO()):  # meshcat prints the URL itself
        return meshcat.Visualizer()


def _check_array(name: str, value: Any, shape: tuple[int, ...], meaning: str) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InvalidParameterError(name, value, f"a numeric array of shape {shape} "
                                    f"({meaning})") from None
    if arr.shape != shape:
        raise InvalidParameterError(name, f"array of shape {arr.shape}",
                                    f"shape {shape} ({meaning})")
    if not np.all(np.isfinite(arr)):
        k = int(np.argwhere(~np.isfinite(arr.reshape(shape[0], -1)))[0, 0])
        raise InvalidParameterError(name, f"NaN/inf at sample {k}", "finite values")
    return arr


def _ground(motion: Motion) -> float:
    """Ground height, m: the median height of the feet in stance, else the lowest foot."""
    z = motion.feet[..., 2]
    return float(np.median(z[motion.stance])) if motion.stance.any() else float(z.min())


def _add_scene(viewer: meshcat.Visualizer, motion: Motion, ground_z: float) -> None:
    """Ground plane, grid at ground height and a camera looking at the motion."""
    base = motion.q[:, :3]
    centre = np.array([*(base[:, :2].min(0) + base[:, :2].max(0)) / 2, ground_z])
    side = 2.0 + float(np.ptp(base[:, :2], axis=0).max())
    viewer["ground"].set_object(mg.Box([side, side, 0.002]),
                                mg.MeshLambertMaterial(color=_GROUND_COLOR))
    viewer["ground"].set_transform(pin.SE3(np.eye(3), centre - [0, 0, 0.0011]).homogeneous)
    # Meshcat's own 20 m grid shows as a band at the horizon: replace it by a 0.1 m grid on the
    # ground plane, which also makes the base's travel visible.
    viewer["/Grid"].set_property("visible", False)
    viewer["/Axes"].set_property("visible", False)
    ticks = np.arange(-side / 2, side / 2 + 1e-9, 0.1)
    ends = np.full_like(ticks, side / 2)
    segments = np.concatenate([
        np.stack([ticks, -ends, ticks, ends], axis=1),    # lines along y
        np.stack([-ends, ticks, ends, ticks], axis=1),    # lines along x
    ]).reshape(-1, 2)
    points = np.column_stack([segments, np.zeros(len(segments))]) + centre
    viewer["ground_grid"].set_object(mg.LineSegments(
        mg.PointsGeometry(points.T.astype(np.float32)), mg.LineBasicMaterial(color=_GRID_COLOR)))
    # Camera: looking at the middle of the travel from the front right, at a distance that
    # scales with the robot (its feet's reach from the base plus the base's height).
    height = float(base[0, 2] - ground_z)
    size = float(np.linalg.norm(motion.feet[0, :, :2] - base[0, :2], axis=1).max()) + height
    travel = float(np.ptp(base[:, :2], axis=0).max())
    target = centre + np.array([0.0, 0.0, 0.5 * height])
    viewer["/Cameras/default"].set_transform(pin.SE3(np.eye(3), target).homogeneous)
    # The camera sits in Meshcat's y-up "rotated" frame: world (x, y, z) is (x, z, -y) there.
    eye = np.array([1.3, -1.07, 0.86]) * (size + 0.5 * travel)
    viewer["/Cameras/default/rotated/<object>"].set_property(
        "position", [float(eye[0]), float(eye[2]), float(-eye[1])])


def _add_robot(viewer: meshcat.Visualizer, tracks: Tracks, robot: Robot,
               fr: Frames) -> MeshcatVisualizer:
    """The robot's visual model, each geometry's placement tracked over the keyframes."""
    viz = MeshcatVisualizer(robot.model, None, robot.visual_model)
    viz.initViewer(viewer=viewer)
    viz.loadViewerModel(rootNodeName="pinocchio")
    viz.setBackgroundColor("gray")
    viz.display(fr.q[0])
    geom_data = viz.visual_data
    poses = np.empty((len(fr.q), len(robot.visual_model.geometryObjects), 7))
    for j, q in enumerate(fr.q):
        pin.forwardKinematics(robot.model, viz.data, q)
        pin.updateGeometryPlacements(robot.model, viz.data, robot.visual_model, geom_data)
        poses[j] = [pin.SE3ToXYZQUAT(M) for M in geom_data.oMg]
    for g, obj in enumerate(robot.visual_model.geometryObjects):
        node = viewer[viz.getViewerNodeName(obj, pin.GeometryType.VISUAL)]
        tracks.set(node, "position", poses[:, g, :3])
        tracks.set(node, "quaternion", poses[:, g, 3:])
        tracks.set(node, "scale", np.tile(obj.meshScale, (len(fr.q), 1)))  # as viz.display
    return viz


def _add_forces(viewer: meshcat.Visualizer, tracks: Tracks, robot: Robot, fr: Frames,
                fmax: float, arrow_length: float) -> None:
    """Force arrows at the feet, ``arrow_length`` long for a force of ``fmax`` N."""
    assert fr.forces is not None
    mags = np.linalg.norm(fr.forces, axis=-1)
    radius = arrow_length / 30
    head = 4 * radius
    feet = np.empty(fr.forces.shape)
    for j, q in enumerate(fr.q):
        feet[j] = robot.foot_positions(q)
    for i, leg in enumerate(robot.legs):
        node = viewer["forces"][leg.name]
        node["shaft"].set_object(mg.Cylinder(1.0, radius),
                                 mg.MeshLambertMaterial(color=_ARROW_COLOR))
        node["head"].set_object(mg.Cylinder(head, radiusTop=0.0, radiusBottom=2.2 * radius),
                                mg.MeshLambertMaterial(color=_ARROW_COLOR))
        f = fr.forces[:, i]
        length = arrow_length * mags[:, i] / fmax if fmax > 0 else np.zeros(len(f))
        quat = np.array([pin.Quaternion.FromTwoVectors(_Y, fk).coeffs() if m > 0 else [0, 0, 0, 1]
                         for fk, m in zip(f, mags[:, i], strict=True)])
        tracks.set(node, "visible", mags[:, i] > 1e-6 * fmax if fmax > 0 else length > 0)
        tracks.set(node, "position", feet[:, i])
        tracks.set(node, "quaternion", quat)
        zeros = np.zeros_like(length)
        tracks.set(node["shaft"], "position", np.stack([zeros, length / 2, zeros], axis=1))
        tracks.set(node["shaft"], "scale",
                   np.stack([zeros + 1, np.maximum(length, 1e-6), zeros + 1], axis=1))
        tracks.set(node["head"], "position", np.stack([zeros, length + head / 2, zeros], axis=1))


def _add_joint_markers(viewer: meshcat.Visualizer, tracks: Tracks, robot: Robot,
                       fr: Frames, vmax: float, radius: float) -> None:
    """Spheres at the joints coloured by value on the scale [−vmax, vmax] (binned)."""
    assert fr.joint_values is not None
    bins = value_bins(fr.joint_values, vmax)
    bin_colours = colours()
    data = robot.model.createData()
    ids = [robot.model.getJointId(name) for name in robot.joint_names]
    origins = np.empty((len(fr.q), robot.nj, 3))
    for j, q in enumerate(fr.q):
        pin.forwardKinematics(robot.model, data, q)
        origins[j] = [data.oMi[i].translation for i in ids]
    for c, name in enumerate(robot.joint_names):
        node = viewer["joint_values"][name]
        tracks.set(node, "position", origins[:, c])
        for b in range(N_LEVELS):
            rgb = (np.round(bin_colours[b] * 255)).astype(int)
            node[f"bin{b}"].set_object(mg.Sphere(radius), mg.MeshLambertMaterial(
                color=int(rgb[0]) << 16 | int(rgb[1]) << 8 | int(rgb[2])))
            tracks.set(node[f"bin{b}"], "visible", bins[:, c] == b)


def draw_motion(robot: Robot, motion: Motion, viewer: meshcat.Visualizer, *, forces: Any,
                joint_values: Any, joint_label: str, fps: float, arrow_length: float,
                marker_radius: float) -> tuple[MeshcatVisualizer, Legend]:
    """Draw a motion into a Meshcat viewer as a looping animation (a still scene for one sample).

    Args:
        robot: The robot the motion belongs to.
        motion: The motion, T samples.
        viewer: The Meshcat visualiser to draw into (a server's, or a page's recording window).
        forces: World-frame foot forces, shape (T, n_legs, 3), N, legs in ``robot.legs``
            order; or None for no arrows.
        joint_values: Values that colour the joints, shape (T, nj), columns in
            ``robot.joint_names`` order; or None for no markers.
        joint_label: What ``joint_values`` are, with units (for the legend).
        fps: Keyframes per second of motion time, > 0.
        arrow_length: Length of the longest force arrow, m.
        marker_radius: Radius of the joint markers, m.

    Returns:
        The Pinocchio visualiser driving the scene, and the legend of its scales (the true
        maxima of the samples).

    Raises:
        InvalidParameterError: ``forces`` or ``joint_values`` has the wrong shape (the message
            names the expected one) or non-finite entries, or ``motion`` does not fit the robot.
    """
    T = motion.n_samples
    nq, nv = robot.model.nq, robot.model.nv
    if motion.q.shape[1:] != (nq,) or motion.v.shape[1:] != (nv,):
        raise InvalidParameterError("motion", f"q {motion.q.shape}, v {motion.v.shape}",
                                    f"q (T, {nq}) and v (T, {nv}) for robot {robot.name}")
    if forces is not None:
        forces = _check_array("forces", forces, (T, len(robot.legs), 3),
                              "(T, n_legs, 3): world-frame force on each foot, N")
    if joint_values is not None:
        joint_values = _check_array("joint_values", joint_values, (T, robot.nj),
                                    "(T, nj): one value per actuated joint, Pinocchio order")
    fr = resample(robot, motion, fps, forces, joint_values)
    tracks = Tracks(fr.frames)
    viz = _add_robot(viewer, tracks, robot, fr)
    _add_scene(viewer, motion, _ground(motion))
    # Scales from the samples themselves, so the legend reports their true maxima.
    fmax = vmax = None
    if forces is not None:
        fmax = float(np.linalg.norm(forces, axis=-1).max())
        _add_forces(viewer, tracks, robot, fr, fmax, arrow_length)
    if joint_values is not None:
        vmax = float(np.abs(joint_values).max())
        _add_joint_markers(viewer, tracks, robot, fr, vmax, marker_radius)
    tracks.apply_first(viewer)
    if len(fr.frames) > 1:
        viewer.set_animation(tracks.animation(fps), play=True, repetitions=math.inf)
    return viz, Legend(joint_label, vmax, fmax, arrow_length)
