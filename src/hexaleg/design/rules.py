"""Spring designs derived from a motion: the paper's rules carried over to any joint of the robot.

The paper places the dead zone symmetrically about the joint's trajectory (eq. 8 with ±θ_k about
the sinusoid's centre B = 0, eq. 25) and picks the stiffness k_M = ω² (m l² + I) / α (eq. 19).
For a joint of the walking robot hexaleg carries that over as a *centred* design:

- neutral = the centre of the joint's range of motion in the gait, (max q + min q) / 2;
- θ_k = r · (max q − min q) / 2 with the paper's ratio r = θ_k / A = 7.32° / 0.3 rad
  (Section 4.2 and eq. 25);
- k_M = ω² J / α (eq. 19 in consistent SI units), with ω = 2π / period and J the joint's
  apparent inertia ``M[v, v]`` (Pinocchio CRBA, base fixed) at the gait's mean posture — the
  "m l² + I" of everything the joint moves.

These are starting points, not optima: :mod:`hexaleg.sweep.runner` finds the optimum for a
metric.
"""

from __future__ import annotations

import math

from hexaleg.checks import positive
from hexaleg.dynamics.inertia import apparent_inertia, joint_range
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import DeadZoneSpring, SpringSet
from hexaleg.units import deg_to_rad

PAPER_THETA_K: float = float(deg_to_rad(7.32))
"""The paper's contact angle θ_k of the dead-zone spring (eq. 8), rad: 7.32° (Section 4.2)."""
PAPER_AMPLITUDE: float = 0.3
"""A of the paper's trajectory A sin(ωt + φ) + B (eq. 16), rad: 0.3 (eq. 25)."""
PAPER_OMEGA: float = 2.0
"""ω of the paper's trajectory A sin(ωt + φ) + B (eq. 16), rad/s: 2 (eq. 25)."""
PAPER_DEAD_ZONE_RATIO: float = PAPER_THETA_K / PAPER_AMPLITUDE
"""θ_k / A of the paper's experiment: θ_k = 7.32° (Section 4.2), A = 0.3 rad (eq. 25); ≈ 0.426."""
PAPER_ALPHA: float = 1.05
"""The paper's angle conversion factor α (Section 4.2)."""


STILL = 1e-9
"""A joint whose range of motion is at most this, rad, does not move (no dead zone to centre)."""


def k_M(robot: Robot, motion: Motion, joint: str, alpha: float = PAPER_ALPHA) -> float:
    """The paper's torque-optimal stiffness for ``joint``: ω² J / α (eq. 19, SI), N·m/rad.

    Eq. 19 is derived with the paper's spring torque k α Δ (eq. 14), so this is the stiffness of
    a ``convention="eq14"`` spring; the torque per radian it gives is ω² J whatever α is.

    Args:
        robot: The robot.
        motion: A periodic motion (ω = 2π / period).
        joint: Joint name.
        alpha: α of eq. 19.
    """
    positive("alpha", alpha)
    omega = 2 * math.pi / motion.period
    return omega**2 * apparent_inertia(robot, motion, joint) / alpha


def centred_spring(robot: Robot, motion: Motion, joint: str, stiffness: float, *,
                   dead_zone: float = PAPER_DEAD_ZONE_RATIO, alpha: float = 1.0,
                   convention: str = "eq7") -> DeadZoneSpring:
    """A symmetric dead-zone spring centred on ``joint``'s range of motion in ``motion``.

    Args:
        robot: The robot.
        motion: The motion.
        joint: Joint name.
        stiffness: k, N·m/rad, ≥ 0.
        dead_zone: θ_k as a fraction of the half range of motion, in (0, 1) (default the
            paper's 0.426); at 1 or more the spring would never engage, and a dead zone needs
            θ⁻ < θ⁺.
        alpha: α (eq. 7).
        convention: Spring α convention (see :mod:`hexaleg.robot.springs`).

    Raises:
        InvalidParameterError: ``dead_zone`` outside (0, 1), or a joint that does not move in
            ``motion`` (no range to centre a dead zone on).
    """
    if not (isinstance(dead_zone, (int, float)) and 0 < dead_zone < 1):
        raise InvalidParameterError("dead_zone", dead_zone,
                                    "a fraction of the half range of motion in (0, 1)")
    lo, hi = joint_range(robot, motion, joint)
    if not hi - lo > STILL:
        raise InvalidParameterError(
            f"centred spring on {joint}", f"a joint that does not move (range [{lo:.6g}, "
            f"{hi:.6g}] rad in this motion)", "a joint that moves: a dead zone centred on no "
            "motion has no width; spring another joint, or give the spring its reference angle "
            "explicitly (LinearSpring, PreloadedSpring)")
    return DeadZoneSpring(stiffness=stiffness, theta_k=dead_zone * (hi - lo) / 2,
                          neutral=(hi + lo) / 2, alpha=alpha, convention=convention)


def centred_springs(robot: Robot, motion: Motion, spec: str, stiffness: float, *,
                    dead_zone: float = PAPER_DEAD_ZONE_RATIO, alpha: float = 1.0,
                    convention: str = "eq7") -> SpringSet:
    """:func:`centred_spring` on every joint named by ``spec`` (a class such as ``"femur"``, or a
    joint), each centred on its own range of motion."""
    return SpringSet({j: centred_spring(robot, motion, j, stiffness, dead_zone=dead_zone,
                                        alpha=alpha, convention=convention)
                      for j in robot.joints(spec)})


def paper_style_springs(robot: Robot, motion: Motion, spec: str = "femur") -> SpringSet:
    """The paper's design on every joint of ``spec``: centred dead zone with θ_k / A = 0.426 and
    α = 1.05 (Section 4.2), stiffness k_M of eq. 19 (SI) for that joint, in the paper's eq. 14
    convention (so the torque per radian beyond θ_k is ω² J)."""
    return SpringSet({j: centred_spring(robot, motion, j, k_M(robot, motion, j),
                                        alpha=PAPER_ALPHA, convention="eq14")
                      for j in robot.joints(spec)})
