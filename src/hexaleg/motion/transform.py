"""The hexapod → sphere transformation: sit the body down on its feet, then fold on the ground.

:func:`transform_motion` goes from ``stand`` to ``sphere``: the body sits down on its feet, then
rests on the ground while the legs fold; no geometry may pass below the ground on the way
(:func:`_ground_clearance`, the ground-clearance rule).

The output is a :class:`~hexaleg.motion.trajectory.Motion` in Pinocchio's conventions: base
velocity and acceleration in the LOCAL base frame, ``a = dv/dt``.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from hexaleg.checks import real, typed
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.kinematics import leg_ik
from hexaleg.motion.limits import check_joint_limits, check_samples
from hexaleg.motion.profiles import smoothstep
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot


@typed
def transform_motion(robot: Robot, duration: float = 2.0, samples: int = 1000,
                     start: str = "stand", end: str = "sphere", sit_fraction: float = 0.25,
                     rest_height: float | None = None) -> Motion:
    """The hexapod → sphere transformation: sit the body down on the feet, then fold on the ground.

    1. **Sit**, ``0 ≤ t < t_s = sit_fraction · duration``: the feet stay where they stand in
       ``start`` (on the ground, in stance) and carry the body down vertically,
       h(t) = h₀ + (h_r − h₀) σ(t / t_s), from the standing height h₀ (the lowest foot at z = 0)
       to the resting height h_r; the leg joints follow from the leg inverse kinematics with
       exact derivatives, like the gait.
    2. **Fold**, ``t_s ≤ t ≤ duration``: the body rests on the ground at h_r
       (``Motion.supported``: the ground carries the base, no foot is loaded) and every joint
       moves from the seated pose q_s to ``end`` as q = q_s + (q₁ − q_s) σ((t − t_s) / t_f),
       t_f = duration − t_s.

    σ is the :func:`~hexaleg.motion.profiles.smoothstep`, so velocities and accelerations are
    zero at t = 0, on both sides of t_s and at the end: q, v and a are continuous across the
    phase switch; only the load moves from the feet to the body at t_s, at rest. The resting
    height h_r is by default where the ``end`` pose rests on its lowest point (for the built-in
    robot the lower body dome, 0.0835 m below the base, so the body sits 7.8 mm lower than it
    stands), and no geometry may pass below the ground while the legs fold (checked, exactly for
    the primitive shapes, at every sample; ``info["clearance"]`` reports the smallest height of
    any geometry over the fold).

    Args:
        robot: The robot.
        duration: Duration, s (> 0).
        samples: Number of samples including both ends (≥ ``MIN_SAMPLES``, and at least two in
            each phase).
        start: Initial pose name; its lowest feet are the stance feet of the sit phase.
        end: Final pose name.
        sit_fraction: Share of ``duration`` spent sitting down, in (0, 1).
        rest_height: Height of the base above the ground with the body resting, m, in
            (0, h₀]; default as described above.

    Returns:
        Motion with t = linspace(0, duration, samples), q (T, nq), v (T, nv), a (T, nv),
        stance (T, n_legs) (the standing feet while sitting, none while folding), supported (T,)
        (the fold), feet (T, n_legs, 3) world foot positions; ``periodic`` False, ``period`` =
        duration, ``distance`` 0.

    Raises:
        UnknownNameError: a pose name is unknown.
        InvalidParameterError: bad duration, samples, sit fraction or resting height; a geometry
            would pass below the ground while folding (names it and the time).
        UnreachableTargetError: a leg cannot keep its foot in place while the body sits.
    """
    real("duration", duration, low=0.0, low_open=True, allowed="a finite number > 0 (s)")
    samples = check_samples(samples)
    real("sit_fraction", sit_fraction, low=0.0, high=1.0, low_open=True, high_open=True,
         allowed="a number in (0, 1)")
    q0, q1, stand_feet, h0 = _start_and_end(robot, start, end)
    if rest_height is None:
        rest_height = -float(_ground_clearance(robot, q1[None], robot.foot_positions(q1)[None])
                             [0][0])
    real("rest_height", rest_height, low=0.0, high=h0 + 1e-12, low_open=True,
         allowed=f"a finite number in (0, {h0:.4f}] m (the {start} height: the body sits down "
         "on its feet, it cannot rise)")
    t = np.linspace(0.0, duration, samples)
    t_sit = sit_fraction * duration
    sit = t < t_sit
    n_sit = int(sit.sum())
    if n_sit < 2 or samples - n_sit < 2:
        raise InvalidParameterError("samples", samples, f"enough for two samples in each phase "
                                    f"(sit {n_sit}, fold {samples - n_sit}); raise samples or "
                                    "bring sit_fraction away from 0 and 1")
    q = np.empty((samples, robot.model.nq))
    v, a = np.empty((samples, robot.model.nv)), np.empty((samples, robot.model.nv))
    q[:n_sit], v[:n_sit], a[:n_sit], seated = _sit(robot, q0, stand_feet, rest_height, t[sit],
                                                    t_sit)
    q1[2] = rest_height  # the base poses of `seated` and `end` are now equal
    q[n_sit:], v[n_sit:], a[n_sit:] = _fold(robot, seated, q1, t[~sit] - t_sit,
                                            duration - t_sit)
    check_joint_limits(robot, q, t)

    feet = np.stack([robot.foot_positions(qk) for qk in q])
    z, names = _ground_clearance(robot, q[n_sit:], feet[n_sit:])
    k_low = n_sit + int(np.argmin(z))
    clearance, where = float(z[k_low - n_sit]), names[k_low - n_sit]
    if clearance < -1e-9:
        raise InvalidParameterError(
            "rest_height", f"{rest_height:.4f} m ({where} reaches {-clearance * 1e3:.2f} mm "
            f"below the ground at t = {t[k_low]:.4f} s while folding)",
            "a resting height at which no geometry passes below the ground")
    stance = np.zeros((samples, len(robot.legs)), dtype=bool)
    stance[:n_sit] = stand_feet[:, 2] < 1e-9  # the feet on the ground
    info = {"source": "transform_motion", "start": start, "end": end, "stand_height": h0,
            "rest_height": rest_height, "sit_time": t_sit, "clearance": clearance,
            "clearance_geometry": where, "clearance_t": float(t[k_low])}
    return Motion(t=t, q=q, v=v, a=a, stance=stance, feet=feet, period=duration,
                  distance=0.0, periodic=False, fixed_base=False, info=info, supported=~sit)


def _start_and_end(robot: Robot, start: str, end: str
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """The start pose standing on the ground z = 0, base over the origin (nq,); the end pose,
    base at the origin (nq,); the start's world foot positions (n_legs, 3) m and its base
    height h₀ m (the lowest foot on the ground)."""
    q0, q1 = robot.pose(start), robot.pose(end)
    q0[:7] = q1[:7] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0)
    stand_feet = robot.foot_positions(q0)  # base at the origin
    h0 = -float(stand_feet[:, 2].min())
    q0[2] = h0
    stand_feet[:, 2] += h0  # world: the lowest feet on the ground z = 0
    return q0, q1, stand_feet, h0


def _sit(robot: Robot, q0: np.ndarray, stand_feet: np.ndarray, rest_height: float,
         t: np.ndarray, t_sit: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The sit phase at times ``t`` (N,) < ``t_sit``: q (N, nq), v (N, nv), a (N, nv) and the
    seated pose q_s (nq,) at ``t_sit``. The base goes down from h₀ = ``q0[2]`` to
    ``rest_height`` as h(t) = h₀ + (h_r − h₀) σ(t / t_s); the feet stay at ``stand_feet``."""
    h0, n_sit, nv = float(q0[2]), len(t), robot.model.nv
    # Base (0, 0, h(t)) with identity orientation, so LOCAL = world and the foot's base-frame
    # position, velocity and acceleration are p − base, −v_base, −a_base.
    sigma, d_sigma, dd_sigma = smoothstep(np.append(t / t_sit, 1.0))
    height = h0 + (rest_height - h0) * sigma
    q = np.tile(q0, (n_sit, 1))
    v, a = np.zeros((n_sit, nv)), np.zeros((n_sit, nv))
    q[:, 2] = height[:-1]
    v[:, 2] = (rest_height - h0) * d_sigma[:-1] / t_sit
    a[:, 2] = (rest_height - h0) * dd_sigma[:-1] / t_sit**2
    seated = q0.copy()
    seated[2] = rest_height
    t_ik = np.append(t, t_sit)
    for i, leg in enumerate(robot.legs):
        rel = stand_feet[i] - np.column_stack([np.zeros((n_sit + 1, 2)), height])
        rel_d = -np.column_stack([np.zeros((n_sit + 1, 2)), (rest_height - h0) * d_sigma / t_sit])
        rel_dd = -np.column_stack([np.zeros((n_sit + 1, 2)),
                                   (rest_height - h0) * dd_sigma / t_sit**2])
        q_leg, qd_leg, qdd_leg, _ = leg_ik(robot, leg, rel, rel_d, rel_dd, t=t_ik)
        q[:, leg.q_index], v[:, leg.v_index] = q_leg[:-1], qd_leg[:-1]
        a[:, leg.v_index] = qdd_leg[:-1]
        seated[leg.q_index] = q_leg[-1]
    return q, v, a, seated


def _fold(robot: Robot, seated: np.ndarray, q1: np.ndarray, tau: np.ndarray, t_fold: float
          ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The fold at times ``tau`` (N,) after its start: q (N, nq), v (N, nv), a (N, nv). The base
    rests (``seated`` and ``q1`` share it); the joints go from ``seated`` to ``q1`` as
    q = q_s + (q₁ − q_s) σ(τ / t_f)."""
    delta = pin.difference(robot.model, seated, q1)  # joints only: the base poses are equal
    sigma, d_sigma, dd_sigma = smoothstep(tau / t_fold)
    q = np.array([pin.integrate(robot.model, seated, sk * delta) for sk in sigma])
    return q, d_sigma[:, None] * delta / t_fold, dd_sigma[:, None] * delta / t_fold**2


def _ground_clearance(robot: Robot, q: np.ndarray, feet: np.ndarray
                      ) -> tuple[np.ndarray, list[str]]:
    """Lowest height of the robot at each sample of ``q`` (T, nq), m, and what reaches it.

    The feet are point contacts at the foot frames (``feet``, (T, n_legs, 3) world positions);
    their balls are drawn around them — a tilted ball dips r (1 − cos tilt) below its point,
    microns here — so the feet count by their points and every other shape by its exact lowest
    point (:meth:`~hexaleg.robot.model.Robot.lowest_points`).
    """
    foot_links = [robot.model.frames[leg.foot_frame_id].name for leg in robot.legs]
    z, names = robot.lowest_points(q, ignore=foot_links)
    leg = np.argmin(feet[..., 2], axis=1)
    foot_z = feet[np.arange(len(q)), leg, 2]
    lower = foot_z < z
    return (np.where(lower, foot_z, z),
            [foot_links[i] if low else name for i, low, name in zip(leg, lower, names,
                                                                      strict=True)])
