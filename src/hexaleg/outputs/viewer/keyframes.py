"""A motion at the viewer's keyframe times, and keyframe tracks sent as one Meshcat animation.

The motion is resampled at ``fps`` keyframes per second (configurations interpolated on the
configuration manifold with Pinocchio, per-sample arrays linearly); the browser interpolates
between keyframes. Only position/quaternion/scale/visibility tracks of scene *groups* are
animated: Meshcat's server replays its scene tree to a newly connected browser root first, i.e.
the animation before the objects, and a group created by the animation is kept where a mesh's
material would be replaced.

Source: Meshcat (meshcat-python 0.3 and its three.js viewer) for the animation protocol.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import meshcat
import numpy as np
import pinocchio as pin
from meshcat.animation import Animation, AnimationClip, AnimationTrack

from hexaleg.checks import MEMORY_BUDGET, count
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot

KEYFRAME_BYTES = 96 * 1024
"""Memory one keyframe costs while a view is built, B: the growth of the tracemalloc peak of
``export_html`` of the hexapod's gait between 30 and 240 keyframes per second, per keyframe,
with a margin."""
MAX_FPS = MEMORY_BUDGET // KEYFRAME_BYTES
"""Most keyframes per second of motion: the keyframes of one second that fill
:data:`hexaleg.checks.MEMORY_BUDGET` (a longer motion is bounded by its keyframe count)."""


@dataclass(frozen=True)
class Frames:
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


def resample(robot: Robot, motion: Motion, fps: float, forces: np.ndarray | None,
             joint_values: np.ndarray | None) -> Frames:
    """Resample a motion (and per-sample arrays) at ``fps`` keyframes per second.

    A periodic motion is closed by a keyframe at ``t = period``: the last sample integrated over
    one step with its velocity (``pin.integrate``), so the base has travelled one cycle; the
    per-sample arrays wrap to sample 0 there.

    Args:
        robot: The robot the motion belongs to.
        motion: The motion, T samples.
        fps: Keyframes per second of motion time.
        forces: Foot forces, shape (T, n_legs, 3), N, or None.
        joint_values: Joint values, shape (T, nj), or None.

    Returns:
        The keyframes; a single-sample motion gives one keyframe.
    """
    model = robot.model
    t, q = motion.t, motion.q
    extra = [a for a in (forces, joint_values) if a is not None]
    if motion.periodic and motion.n_samples > 1:
        t = np.append(t, t[0] + motion.period)
        q = np.vstack([q, pin.integrate(model, q[-1], motion.v[-1] * motion.dt)])
        extra = [np.concatenate([a, a[:1]]) for a in extra]
    duration = float(t[-1] - t[0])
    n = count("keyframes (fps × motion duration)", math.floor(duration * fps + 1e-9) + 1,
              item_bytes=KEYFRAME_BYTES, item="one keyframe",
              fix=f"lower fps ({fps:g} per s over {duration:g} s of motion)")
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
    return Frames(frames=(times - t[0]) * fps, q=q_out,
                  forces=next(it) if forces is not None else None,
                  joint_values=next(it) if joint_values is not None else None)


class Tracks:
    """Keyframe tracks of scene groups, emitted both as a Meshcat animation and as the scene's
    static state at the first keyframe."""

    def __init__(self, frames: np.ndarray) -> None:
        self.frames = [float(f) for f in frames]
        self.groups: dict[Any, dict[str, np.ndarray]] = {}

    def set(self, node: meshcat.Visualizer, prop: str, values: np.ndarray) -> None:
        """Track ``prop`` (position, quaternion, scale or visible) of ``node``, one value per
        keyframe."""
        self.groups.setdefault(node.path, {})[prop] = np.asarray(values)

    def animation(self, fps: float) -> Animation:
        """The tracks as one Meshcat animation at ``fps`` frames per second."""
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
