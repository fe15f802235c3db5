"""Joints following the paper's sinusoid (eq. 16) on a fixed base: the single-joint experiment.

:func:`joint_motion` — chosen joints follow f(t) = A sin(ωt + φ) + B
(:class:`~hexaleg.motion.profiles.Sinusoid`) while the base is held by a fixture; the paper's
single-joint experiment (eq. 25: f(t) = 0.3 sin 2t) embedded in the robot.

The output is a :class:`~hexaleg.motion.trajectory.Motion` in Pinocchio's conventions.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

import numpy as np

from hexaleg.checks import real, typed
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.limits import check_joint_limits, check_samples
from hexaleg.motion.profiles import Sinusoid
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot


@typed
def joint_motion(robot: Robot, trajectories: Mapping[str, Sinusoid],
                 base: str | np.ndarray = "stand", samples: int = 1000,
                 period: float | None = None) -> Motion:
    """Joints following the paper's sinusoid f(t) = A sin(ωt + φ) + B (eq. 16) on a fixed base.

    This embeds the paper's single-joint experiment (eq. 25: f(t) = 0.3 sin 2t) in the robot:
    each named joint's angle is its :class:`Sinusoid` (absolute angle, rad) with exact
    derivatives; every other joint is held at the ``base`` pose; the base is held by a fixture.

    Args:
        robot: The robot.
        trajectories: Joint name → sinusoid; names from ``robot.joint_names``.
        base: Pose name (``stand``, ``sphere``, ``zero``) or a configuration (nq,).
        samples: Samples per period T (endpoint excluded).
        period: Duration, s; default 2π/|ω| when all sinusoids share |ω| > 0.

    Returns:
        Motion with t (T,), q (T, nq), v (T, nv), a (T, nv), stance (T, n_legs) all False, feet
        (T, n_legs, 3) from forward kinematics; ``fixed_base`` True, ``distance`` 0,
        ``periodic`` True when every ω · period is a multiple of 2π.

    Raises:
        UnknownNameError: a joint name is not an actuated joint.
        InvalidParameterError: no trajectories, bad samples or period, no common period, or a
            joint leaves its limits.
    """
    if not trajectories:
        raise InvalidParameterError("trajectories", dict(trajectories),
                                    "at least one joint name → Sinusoid")
    for name, traj in trajectories.items():
        robot.column(name)
        if not isinstance(traj, Sinusoid):
            raise InvalidParameterError(f"trajectories[{name!r}]", traj, "a Sinusoid")
    samples = check_samples(samples)
    omegas = sorted({abs(s.omega) for s in trajectories.values()})
    if period is None:
        if len(omegas) != 1 or omegas[0] == 0.0:
            raise InvalidParameterError("period", None, "a duration > 0 (s) when the sinusoids "
                                        f"do not share one |ω| > 0 (|ω| = {omegas})")
        period = 2.0 * math.pi / omegas[0]
    real("period", period, low=0.0, low_open=True, allowed="a finite number > 0 (s)")
    t = np.arange(samples) * (period / samples)
    q = np.tile(_base_pose(robot, base), (samples, 1))
    v = np.zeros((samples, robot.model.nv))
    a = np.zeros((samples, robot.model.nv))
    for name, traj in trajectories.items():
        joint = robot.model.joints[robot.model.getJointId(name)]
        q[:, joint.idx_q], v[:, joint.idx_v], a[:, joint.idx_v] = traj(t)
    check_joint_limits(robot, q, t)
    cycles = [w * period / (2.0 * math.pi) for w in omegas]
    periodic = all(abs(c - round(c)) < 1e-9 for c in cycles)
    info = {"source": "joint_motion", "base": base if isinstance(base, str) else "custom",
            "trajectories": {k: dataclasses.asdict(s) for k, s in trajectories.items()}}
    feet = np.stack([robot.foot_positions(qk) for qk in q])
    return Motion(t=t, q=q, v=v, a=a, stance=np.zeros((samples, len(robot.legs)), dtype=bool),
                  feet=feet, period=period, distance=0.0, periodic=periodic, fixed_base=True,
                  info=info)


def _base_pose(robot: Robot, base: str | np.ndarray) -> np.ndarray:
    """The configuration (nq,) the joints not moved are held at: a pose name or a copy of q."""
    if isinstance(base, str):
        return robot.pose(base)
    q = np.asarray(base, dtype=float)
    if q.shape != (robot.model.nq,) or not np.all(np.isfinite(q)):
        raise InvalidParameterError("base", f"array of shape {q.shape}",
                                    f"a pose name ({', '.join(robot.poses)}) or a finite "
                                    f"configuration of shape ({robot.model.nq},)")
    return q.copy()
