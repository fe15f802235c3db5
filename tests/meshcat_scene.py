"""What the viewer sent to Meshcat, decoded, and the synthetic walk the viewer tests draw.

Imported by the tests of :mod:`hexaleg.outputs.viewer` and :mod:`hexaleg.commands.view`
(``tests`` is on the test path, like ``browser.py``).
"""

from __future__ import annotations

import base64
import re
from typing import Any

import meshcat
import numpy as np
import umsgpack

from hexaleg.motion.trajectory import Motion
from hexaleg.outputs.viewer.scene import draw_motion
from hexaleg.robot.model import Robot

T = 40
PERIOD = 1.0
DISTANCE = 0.1
AMP = 0.25
TRIPOD_A = ("LF", "LH", "RM")
ARROW = 0.15
"""Length of the longest force arrow, m (``ViewParams()``'s default, used by :func:`draw`)."""


def synthetic_walk(robot: Robot) -> Motion:
    """One 1 s cycle: base walking 0.1 m along x at the stand height, every joint sinusoidal
    about ``stand`` (tripods in antiphase), exact v and a, tripod stance flags."""
    t = np.arange(T) * PERIOD / T
    w = 2 * np.pi / PERIOD
    q = np.tile(robot.pose("stand"), (T, 1))
    v = np.zeros((T, robot.model.nv))
    a = np.zeros_like(v)
    q[:, 0] = DISTANCE * t / PERIOD
    q[:, 2] = -robot.foot_positions(robot.pose("stand"))[:, 2].min()
    v[:, 0] = DISTANCE / PERIOD
    stance = np.zeros((T, len(robot.legs)), dtype=bool)
    for i, leg in enumerate(robot.legs):
        phase = 0.0 if leg.name in TRIPOD_A else np.pi
        for j, (iq, iv) in enumerate(zip(leg.q_index, leg.v_index, strict=True)):
            q[:, iq] += AMP * np.sin(w * t + phase + j)
            v[:, iv] = AMP * w * np.cos(w * t + phase + j)
            a[:, iv] = -AMP * w**2 * np.sin(w * t + phase + j)
        stance[:, i] = (t < PERIOD / 2) == (leg.name in TRIPOD_A)
    feet = np.array([robot.foot_positions(qk) for qk in q])
    return Motion(t=t, q=q, v=v, a=a, stance=stance, feet=feet, period=PERIOD,
                  distance=DISTANCE)


def synthetic_forces(robot: Robot, motion: Motion) -> np.ndarray:
    """Weight shared by the stance feet, tilted forward on the left legs so arrows are not all
    vertical; shape (T, n_legs, 3), N."""
    f = np.zeros((T, len(robot.legs), 3))
    f[..., 2] = np.where(motion.stance, robot.mass * 9.81 / 3, 0.0)
    left = [i for i, leg in enumerate(robot.legs) if leg.name.startswith("L")]
    f[:, left, 0] = 0.5 * f[:, left, 2]
    return f


class _Recorder:
    """A Meshcat window that keeps the commands sent to it, MessagePack round-tripped."""

    def __init__(self) -> None:
        self.commands: list[dict] = []

    def send(self, command: Any) -> None:
        self.commands.append(umsgpack.unpackb(umsgpack.packb(command.lower())))


def draw(robot: Robot, motion: Motion, *, forces: Any = None, joint_values: Any = None,
         joint_label: str = "", fps: float = 30.0) -> list[dict]:
    """The commands :func:`~hexaleg.outputs.viewer.scene.draw_motion` sends, decoded, in order
    (arrows ``ARROW`` long, markers of ``ViewParams()``'s radius)."""
    window = _Recorder()
    draw_motion(robot, motion, meshcat.Visualizer(window=window), forces=forces,
                joint_values=joint_values, joint_label=joint_label, fps=fps,
                arrow_length=ARROW, marker_radius=0.018)
    return window.commands


def page_commands(page: str) -> list[dict]:
    """The Meshcat commands embedded in an exported page, decoded, in order."""
    block = re.search(r"var commands = \[(.*?)\];", page, re.S).group(1)
    return [umsgpack.unpackb(base64.b64decode(s)) for s in re.findall(r'"([A-Za-z0-9+/=]+)"',
                                                                       block)]


def clips(commands: list[dict]) -> dict[str, dict[str, dict]]:
    """path → track name → {"frames": [...], "values": [...]} of the (single) animation."""
    anims = [c for c in commands if c["type"] == "set_animation"]
    assert len(anims) == 1
    out = {}
    for a in anims[0]["animations"]:
        tracks = {}
        for tr in a["clip"]["tracks"]:
            tracks[tr["name"].lstrip(".")] = {"frames": [k["time"] for k in tr["keys"]],
                                               "values": [k["value"] for k in tr["keys"]]}
        out[a["path"]] = tracks
    return out


def at(track: dict, frame: float) -> Any:
    """Value of a discrete (step) track at ``frame``."""
    i = np.searchsorted(track["frames"], frame, side="right") - 1
    return track["values"][i]
