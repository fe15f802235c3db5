"""Browser visualisation of a :class:`~hexaleg.motion.trajectory.Motion` with Meshcat.

The robot's visual model is drawn by Pinocchio's :class:`pinocchio.visualize.MeshcatVisualizer`;
on top of it this module adds a ground plane, ground-reaction-force arrows at the feet and a
colour-coded marker at every joint. The whole motion is sent to the viewer as one Meshcat
animation (three.js keyframe tracks played by the browser), so the same scene can be

* shown live by a Meshcat server on localhost (:func:`serve`, ``hexaleg view``), or
* written to one self-contained HTML page that plays offline (:func:`export_html`,
  ``hexaleg view --html FILE``): the viewer JavaScript is inlined from the installed ``meshcat``
  package and the scene is embedded as base64 MessagePack commands, so the page fetches nothing.

Only position/quaternion/scale/visibility tracks of scene *groups* are animated. Meshcat's server
replays its scene tree to a newly connected browser root first, i.e. the animation before the
objects; animating a mesh's material would bind to a placeholder that the mesh later replaces,
whereas a group created by the animation is kept. Joint colours are therefore drawn as a stack of
pre-coloured spheres per joint of which one is visible at a time (a binned colour map).

Sources: Meshcat (meshcat-python 0.3 and its three.js viewer) for the scene and animation
protocol; Pinocchio's ``MeshcatVisualizer`` for the robot geometry; the diverging cool-warm colour
map of K. Moreland, "Diverging Color Maps for Scientific Visualization", ISVC 2009 (its end and
mid colours, interpolated linearly in RGB).
"""

from __future__ import annotations

import base64
import contextlib
import html
import io
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import meshcat
import meshcat.geometry as mg
import numpy as np
import pinocchio as pin
import umsgpack
from meshcat.animation import Animation, AnimationClip, AnimationTrack
from pinocchio.visualize import MeshcatVisualizer

from hexaleg.errors import InvalidParameterError, OutputError
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot

N_LEVELS = 11
"""Number of colour bins of the joint markers (odd, so that the middle bin is centred on 0)."""

_COOL = np.array([0.230, 0.299, 0.754])
_NEUTRAL = np.array([0.865, 0.865, 0.865])
_WARM = np.array([0.706, 0.016, 0.150])
_GROUND_COLOR = 0xE8E4DA
_GRID_COLOR = 0xB8B2A6
_ARROW_COLOR = 0x00B140
_Y = np.array([0.0, 1.0, 0.0])


@dataclass(frozen=True)
class ViewParams:
    """How a motion is drawn; the ``[view]`` table of a hexaleg config file.

    Attributes:
        fps: Keyframes per second of motion time; the motion is resampled at this rate
            (configurations interpolated on the configuration manifold, per-sample arrays
            linearly) and the browser interpolates between keyframes.
        arrow_length: Length of the longest ground-reaction-force arrow, m; the others are
            scaled in proportion to the force magnitude.
        marker_radius: Radius of the coloured joint markers, m.
    """

    fps: float = 30.0
    arrow_length: float = 0.15
    marker_radius: float = 0.018

    def __post_init__(self) -> None:
        for name in ("fps", "arrow_length", "marker_radius"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not (math.isfinite(value) and value > 0):
                raise InvalidParameterError(f"ViewParams.{name}", value, "a finite number > 0")


def cool_warm(x: np.ndarray) -> np.ndarray:
    """Diverging cool-warm colour map (Moreland 2009), linear in RGB between its three anchors.

    Args:
        x: Positions in the map, any shape, clipped to [0, 1]; 0 is blue, 0.5 neutral grey,
            1 red.

    Returns:
        RGB colours in [0, 1], shape ``x.shape + (3,)``.
    """
    x = np.clip(np.asarray(x, dtype=float), 0.0, 1.0)[..., None]
    lower = _COOL + (_NEUTRAL - _COOL) * (2 * x)
    upper = _NEUTRAL + (_WARM - _NEUTRAL) * (2 * x - 1)
    return np.where(x <= 0.5, lower, upper)


def value_bins(values: np.ndarray, vmax: float) -> np.ndarray:
    """Colour bin of each value on the symmetric scale [−vmax, vmax] split into N_LEVELS bins.

    Args:
        values: Joint values, any shape.
        vmax: Half-width of the scale (≥ 0); 0 puts every value in the middle (neutral) bin.

    Returns:
        Bin indices in [0, N_LEVELS − 1], same shape as ``values``, int.
    """
    values = np.asarray(values, dtype=float)
    if vmax <= 0:
        return np.full(values.shape, N_LEVELS // 2, dtype=int)
    return np.clip(np.floor((values + vmax) / (2 * vmax) * N_LEVELS), 0, N_LEVELS - 1).astype(int)


@dataclass(frozen=True)
class _Frames:
    """A motion resampled at the keyframe times.

    Attributes:
        frames: Keyframe times in frames (time · fps from the first sample), shape (J,).
        q: Configurations, shape (J, nq).
        forces: Foot forces, shape (J, n_legs, 3), N, or None.
        joint_values: Joint values, shape (J, nj), or None.
    """

    frames: np.ndarray
    q: np.ndarray
    forces: np.ndarray | None
    joint_values: np.ndarray | None


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


def _resample(robot: Robot, motion: Motion, fps: float, forces: np.ndarray | None,
              joint_values: np.ndarray | None) -> _Frames:
    """Resample a motion (and per-sample arrays) at ``fps`` keyframes per second.

    A periodic motion is closed by a keyframe at ``t = period``: the last sample integrated over
    one step with its velocity (``pin.integrate``), so the base has travelled one cycle; the
    per-sample arrays wrap to sample 0 there.
    """
    model = robot.model
    t, q = motion.t, motion.q
    extra = [a for a in (forces, joint_values) if a is not None]
    if motion.periodic and motion.n_samples > 1:
        t = np.append(t, t[0] + motion.period)
        q = np.vstack([q, pin.integrate(model, q[-1], motion.v[-1] * motion.dt)])
        extra = [np.concatenate([a, a[:1]]) for a in extra]
    duration = float(t[-1] - t[0])
    n = math.floor(duration * fps + 1e-9) + 1
    times = t[0] + np.arange(n) / fps
    if times[-1] < t[-1] - 1e-12:
        times = np.append(times, t[-1])
    if len(t) == 1:
        q_out = q[:1].copy()
        out = [a[:1].copy() for a in extra]
    else:
        k = np.clip(np.searchsorted(t, times, side="right") - 1, 0, len(t) - 2)
        alpha = np.clip((times - t[k]) / (t[k + 1] - t[k]), 0.0, 1.0)
        q_out = np.array([pin.interpolate(model, q[i], q[i + 1], a)
                          for i, a in zip(k, alpha, strict=True)])
        out = []
        for a in extra:
            w = alpha.reshape((-1,) + (1,) * (a.ndim - 1))
            out.append((1 - w) * a[k] + w * a[k + 1])
    it = iter(out)
    return _Frames(frames=(times - t[0]) * fps, q=q_out,
                   forces=next(it) if forces is not None else None,
                   joint_values=next(it) if joint_values is not None else None)


class _Tracks:
    """Keyframe tracks of scene groups, emitted both as a Meshcat animation and as the scene's
    static state at the first keyframe."""

    def __init__(self, frames: np.ndarray) -> None:
        self.frames = [float(f) for f in frames]
        self.groups: dict[Any, dict[str, np.ndarray]] = {}

    def set(self, node: meshcat.Visualizer, prop: str, values: np.ndarray) -> None:
        self.groups.setdefault(node.path, {})[prop] = np.asarray(values)

    def animation(self, fps: float) -> Animation:
        anim = Animation(default_framerate=fps)
        for path, props in self.groups.items():
            clip = AnimationClip(fps=fps)
            for prop, values in props.items():
                if prop == "visible":
                    # Discrete track: keep only the frames where visibility changes (and both ends).
                    keep = np.flatnonzero(np.r_[True, values[1:] != values[:-1]])
                    keep = np.union1d(keep, [len(values) - 1])
                    clip.tracks[prop] = AnimationTrack(
                        prop, "boolean", [self.frames[i] for i in keep],
                        [bool(values[i]) for i in keep])
                else:
                    jstype = "quaternion" if prop == "quaternion" else "vector3"
                    clip.tracks[prop] = AnimationTrack(prop, jstype, list(self.frames),
                                                       values.astype(float).tolist())
            anim.clips[path] = clip
        return anim

    def apply_first(self, viewer: meshcat.Visualizer) -> None:
        """Set every group to its state at the first keyframe (for viewers that do not play)."""
        for path, props in self.groups.items():
            node = meshcat.Visualizer.view_into(viewer.window, path)
            if "visible" in props:
                node.set_property("visible", bool(props["visible"][0]))
            if "position" in props:
                M = np.eye(4)
                M[:3, 3] = props["position"][0]
                if "quaternion" in props:
                    M[:3, :3] = pin.Quaternion(props["quaternion"][0]).toRotationMatrix()
                if "scale" in props:
                    M[:3, :3] = M[:3, :3] @ np.diag(props["scale"][0])
                node.set_transform(M)


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


def _add_forces(viewer: meshcat.Visualizer, tracks: _Tracks, robot: Robot, fr: _Frames,
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


def _add_joint_markers(viewer: meshcat.Visualizer, tracks: _Tracks, robot: Robot,
                       fr: _Frames, vmax: float, radius: float) -> None:
    """Spheres at the joints coloured by value on the scale [−vmax, vmax] (binned)."""
    assert fr.joint_values is not None
    bins = value_bins(fr.joint_values, vmax)
    colors = cool_warm((np.arange(N_LEVELS) + 0.5) / N_LEVELS)
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
            rgb = (np.round(colors[b] * 255)).astype(int)
            node[f"bin{b}"].set_object(mg.Sphere(radius), mg.MeshLambertMaterial(
                color=int(rgb[0]) << 16 | int(rgb[1]) << 8 | int(rgb[2])))
            tracks.set(node[f"bin{b}"], "visible", bins[:, c] == b)


@dataclass(frozen=True)
class _Legend:
    """What the colours and arrows mean: joint scale half-width and full-length force."""

    joint_label: str
    vmax: float | None
    fmax: float | None
    arrow_length: float


def _animate(robot: Robot, motion: Motion, viewer: meshcat.Visualizer, *, forces: Any,
             joint_values: Any, joint_label: str, params: ViewParams
             ) -> tuple[MeshcatVisualizer, _Legend]:
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
    fr = _resample(robot, motion, params.fps, forces, joint_values)

    viz = MeshcatVisualizer(robot.model, None, robot.visual_model)
    viz.initViewer(viewer=viewer)
    viz.loadViewerModel(rootNodeName="pinocchio")
    viz.setBackgroundColor("gray")
    viz.display(fr.q[0])
    tracks = _Tracks(fr.frames)
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

    _add_scene(viewer, motion, _ground(motion))
    # Scales from the samples themselves, so the legend reports their true maxima.
    fmax = vmax = None
    if forces is not None:
        fmax = float(np.linalg.norm(forces, axis=-1).max())
        _add_forces(viewer, tracks, robot, fr, fmax, params.arrow_length)
    if joint_values is not None:
        vmax = float(np.abs(joint_values).max())
        _add_joint_markers(viewer, tracks, robot, fr, vmax, params.marker_radius)
    tracks.apply_first(viewer)
    if len(fr.frames) > 1:
        viewer.set_animation(tracks.animation(params.fps), play=True, repetitions=math.inf)
    return viz, _Legend(joint_label, vmax, fmax, params.arrow_length)


def animate(robot: Robot, motion: Motion, *, forces: Any = None, joint_values: Any = None,
            joint_label: str = "", viewer: meshcat.Visualizer | None = None,
            fps: float = 30.0, arrow_length: float = 0.15,
            marker_radius: float = 0.018) -> MeshcatVisualizer:
    """Send a motion to a Meshcat viewer as a looping animation.

    The robot's visual model follows ``motion.q``; a ground plane with a 0.1 m grid is drawn at
    the height of the stance feet. With ``forces``, an arrow at each foot shows its force (hidden
    while the force is zero); with ``joint_values``, a sphere at each joint takes one of
    :data:`N_LEVELS` cool-warm colours on the symmetric scale ±max|value| (blue negative, grey
    ≈ 0, red positive).

    Args:
        robot: The robot the motion belongs to.
        motion: The motion; a periodic motion loops without a jump except the base's return by
            one cycle's displacement.
        forces: Per-sample forces on the feet, world frame, shape (T, n_legs, 3), N, legs in
            ``robot.legs`` order; or None for no arrows.
        joint_values: Per-sample values that colour the joints (e.g. spring torque N·m or
            motor power W), shape (T, nj), columns in ``robot.joint_names`` order; or None.
        joint_label: What ``joint_values`` are, with units (the legend of :func:`export_html`).
        viewer: A ``meshcat.Visualizer`` to draw into; None starts a Meshcat server on
            127.0.0.1 that lives as long as this process (its URL: ``result.viewer.url()``).
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
        viewer = _start_server()
    elif not isinstance(viewer, meshcat.Visualizer):
        raise InvalidParameterError("viewer", viewer, "a meshcat.Visualizer or None")
    viz, _ = _animate(robot, motion, viewer, forces=forces, joint_values=joint_values,
                      joint_label=joint_label, params=params)
    return viz


def _start_server() -> meshcat.Visualizer:
    """A Meshcat server subprocess on 127.0.0.1 (killed when this process exits)."""
    with contextlib.redirect_stdout(io.StringIO()):  # meshcat prints the URL itself
        return meshcat.Visualizer()


def serve(robot: Robot, motion: Motion, *, forces: Any = None, joint_values: Any = None,
          joint_label: str = "", fps: float = 30.0, arrow_length: float = 0.15,
          marker_radius: float = 0.018) -> str:
    """Start a Meshcat server on localhost showing the animated motion.

    The server is a subprocess that lives as long as the calling Python process; a browser
    opened on the URL (also after this function returns, and again after a reload) receives
    the scene and plays it.

    Args:
        robot: The robot.
        motion: The motion.
        forces, joint_values, joint_label, fps, arrow_length, marker_radius: As
            :func:`animate`.

    Returns:
        The viewer's URL, ``http://127.0.0.1:<port>/static/``.

    Raises:
        InvalidParameterError: as :func:`animate`.
    """
    viz = animate(robot, motion, forces=forces, joint_values=joint_values,
                  joint_label=joint_label, fps=fps, arrow_length=arrow_length,
                  marker_radius=marker_radius)
    return str(viz.viewer.url())


class _PageWindow:
    """A stand-in for ``meshcat.visualizer.ViewerWindow`` that records the commands in the order
    they are sent instead of sending them to a server; ``get_scene()`` (what
    ``meshcat.Visualizer.static_html()`` calls) packs them into a self-contained page."""

    def __init__(self, title: str) -> None:
        self.commands: list[bytes] = []
        self.title = title
        self.legend_html = ""

    def send(self, command: Any) -> None:
        self.commands.append(umsgpack.packb(command.lower()))

    def get_scene(self) -> str:
        viewer_js = (Path(meshcat.__file__).parent / "viewer" / "dist" / "main.min.js").read_text()
        commands = ",\n".join(f'"{base64.b64encode(c).decode("ascii")}"' for c in self.commands)
        return _PAGE.format(title=html.escape(self.title), viewer_js=viewer_js,
                            legend=self.legend_html, commands=commands)


_PAGE = """<!DOCTYPE html>
<html>
<head>
<meta charset="utf-8">
<title>{title}</title>
<style>
body {{ margin: 0; }}
#meshcat-pane {{ width: 100vw; height: 100vh; overflow: hidden; }}
#legend {{ position: fixed; left: 8px; bottom: 8px; padding: 6px 8px; font: 12px sans-serif;
  background: rgba(255, 255, 255, 0.85); border-radius: 4px; }}
#legend span.bin {{ display: inline-block; width: 14px; height: 10px; }}
</style>
</head>
<body>
<div id="meshcat-pane"></div>
{legend}
<script>
{viewer_js}
</script>
<script>
var viewer = new MeshCat.Viewer(document.getElementById("meshcat-pane"));
// Scene commands (base64 MessagePack), applied synchronously in the order they were recorded.
var commands = [
{commands}
];
for (const c of commands) {{
  viewer.handle_command_bytearray(Uint8Array.from(atob(c), (ch) => ch.charCodeAt(0)));
}}
</script>
</body>
</html>
"""


def _legend_html(legend: _Legend) -> str:
    lines = []
    if legend.vmax is not None:
        swatches = "".join(
            '<span class="bin" style="background: rgb({}, {}, {})"></span>'.format(
                *(round(255 * v) for v in c))
            for c in cool_warm((np.arange(N_LEVELS) + 0.5) / N_LEVELS))
        label = html.escape(legend.joint_label or "joint value")
        lines.append(f"<div>joints: {label} &nbsp;{-legend.vmax:.3g} {swatches} "
                     f"{legend.vmax:+.3g}</div>")
    if legend.fmax is not None:
        lines.append(f"<div>arrows: foot forces, {legend.arrow_length * 100:.3g} cm = "
                     f"{legend.fmax:.3g} N</div>")
    return f'<div id="legend">{"".join(lines)}</div>' if lines else ""


def export_html(robot: Robot, motion: Motion, path: str | Path, *, forces: Any = None,
                joint_values: Any = None, joint_label: str = "", fps: float = 30.0,
                arrow_length: float = 0.15, marker_radius: float = 0.018) -> Path:
    """Write the animated motion to one self-contained HTML page that plays offline.

    The page inlines Meshcat's viewer JavaScript from the installed ``meshcat`` package and
    embeds the scene and its animation as data; it needs no server and fetches nothing over the
    network. A legend explains the joint colours and the force-arrow scale.

    Args:
        robot: The robot.
        motion: The motion.
        path: Output file; its directory must exist.
        forces, joint_values, joint_label, fps, arrow_length, marker_radius: As
            :func:`animate`.

    Returns:
        The written path.

    Raises:
        OutputError: the file cannot be written (the message names the path and the reason).
        InvalidParameterError: as :func:`animate`.
    """
    path = Path(path)
    params = ViewParams(fps=fps, arrow_length=arrow_length, marker_radius=marker_radius)
    window = _PageWindow(f"hexaleg: {robot.name}" + (f" ({joint_label})" if joint_label else ""))
    viewer = meshcat.Visualizer(window=window)
    _, legend = _animate(robot, motion, viewer, forces=forces, joint_values=joint_values,
                         joint_label=joint_label, params=params)
    window.legend_html = _legend_html(legend)
    try:
        path.write_text(viewer.static_html(), encoding="utf-8")
    except OSError as e:
        raise OutputError(f"cannot write HTML page {path}: {e.strerror or e}") from e
    return path
