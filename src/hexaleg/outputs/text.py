"""Text summaries for the terminal (``hexaleg gait``).

:func:`gait_summary` — a gait motion's parameters, stance count and static margin, balancing
sway, and per joint the angle range, peak speed against the velocity limit and peak acceleration.
"""

from __future__ import annotations

import math

import numpy as np

from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.units import rad_to_deg


def gait_summary(robot: Robot, motion: Motion) -> str:
    """A human-readable summary of a gait motion: parameters, margin, joint ranges and peaks.

    Args:
        robot: The robot the motion was made for.
        motion: A motion from :func:`hexaleg.motion.legged.tripod_gait` or
            :func:`~hexaleg.motion.legged.sample_gait`.

    Returns:
        Text: the parameters, the stance count and static margin, the balancing sway (when
        there is one), and per joint the angle range (deg), the peak speed against the model's
        velocity limit (rad/s) and the peak acceleration (rad/s²).
    """
    info, g = motion.info, motion.info["gait"]
    margin = info["static_margin"]
    lines = [
        f"gait: period {g['period']:g} s, duty factor {g['duty_factor']:g}, stride "
        f"{info['stride_length']:g} m, speed {info['speed']:g} m/s, step height "
        f"{g['step_height']:g} m, body height {info['body_height']:.4f} m, foot radius "
        f"{info['foot_radius']:.4f} m, yaw rate {g['yaw_rate']:g} rad/s, "
        f"{motion.n_samples} samples",
        f"groups: {' | '.join(' '.join(group) for group in _groups(info))}",
        *_timing_and_ground(info),
        f"stance feet per sample: min {info['min_stance_feet']}; static margin "
        + (f"{margin:.4f} m (at t = {info['static_margin_t']:g} s)" if margin is not None
           else "n/a (fewer than 3 stance feet at some sample)"),
        *([f"balance: body sway ±{1e3 * sway['amplitude']:.2f} mm along "
           f"{np.round(sway['direction'], 3).tolist()} (base frame), support-line moment "
           f"{sway['residual']:.1e} m g h after {sway['iterations']} iterations"]
          if (sway := info.get("balance", {})).get("mode") == "sway" else []),
        *([f"balance: ZMP walking pattern, the body swaying ±{1e3 * zmp['sway'][0]:.2f} mm "
           f"(base x) and ±{1e3 * zmp['sway'][1]:.2f} mm (base y) and turning "
           f"±{math.degrees(zmp['turn']):.2f}° so that one stance foot can carry it: moment "
           f"about the zero-moment point {zmp['residual']:.1e} m g h after {zmp['iterations']} "
           "iterations"] if (zmp := info.get("balance", {})).get("mode") == "zmp" else []),
        *([f"balance: body shifted up to {1e3 * shift['amplitude']:.2f} mm over the support "
           f"polygon to keep a static margin ≥ {shift['target']:.4f} m ({shift['iterations']} "
           "rounds)"] if (shift := info.get("balance", {})).get("mode") == "shift" else []),
        f"{'joint':<14} {'range deg':>17} {'peak |v| rad/s':>15} {'limit':>7} "
        f"{'peak |a| rad/s²':>16}",
    ]
    q, v, a = motion.q[:, 7:], np.abs(motion.v[:, 6:]), np.abs(motion.a[:, 6:])
    limits = robot.model.velocityLimit[6:]
    for j, name in enumerate(robot.joint_names):
        lo, hi = rad_to_deg(q[:, j].min()), rad_to_deg(q[:, j].max())
        lines.append(f"{name:<14} {lo:8.1f} .. {hi:6.1f} {v[:, j].max():15.3f} "
                     f"{limits[j]:7.2f} {a[:, j].max():16.2f}")
    return "\n".join(lines)


def _groups(info: dict) -> list:
    """The leg groups as given, or those of the pattern or phases (legs with equal offsets)."""
    g = info["gait"]
    timed = g.get("pattern") is not None or g.get("phases") is not None
    return list(info["groups"]) if timed else list(g["groups"])


def _timing_and_ground(info: dict) -> list[str]:
    """Lines for a named pattern or custom phases, a heading and an inclined ground (none for
    the default gait)."""
    g, lines = info["gait"], []
    if g.get("pattern") is not None or g.get("phases") is not None:
        phases = ", ".join(f"{leg} {o:.3g}" for leg, o in info["phases"].items())
        lines.append(f"pattern: {g.get('pattern') or 'custom phases'} (touch-down at {phases} "
                     "of the period)")
    if g.get("heading"):
        lines.append(f"heading: {g['heading']:g} rad from the robot's forward axis, walking "
                     f"along {np.round(info['direction'], 3).tolist()} (base frame)")
    if "ground" in info:
        ground = info["ground"]
        lines.append(f"ground: slope {rad_to_deg(ground['slope']):.3g}°, cross slope "
                     f"{rad_to_deg(ground['cross_slope']):.3g}°, body {ground['attitude']}, "
                     f"normal {np.round(ground['normal'], 4).tolist()}")
    return lines
