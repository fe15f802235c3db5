"""The periodic gait (default: the hexapod's alternating tripod on level ground).

:func:`gait` (also :func:`tripod_gait`) — the body moves with a constant twist (speed along the
walking direction, optional yaw rate); each leg touches down at its phase offset (a named
pattern, custom phases or leg groups: :mod:`hexaleg.motion.patterns`); stance feet stay fixed on
the ground, swing feet follow :func:`~hexaleg.motion.profiles.swing_curve`; joint angles,
velocities and accelerations come from the leg inverse kinematics
(:mod:`hexaleg.motion.kinematics`) with exact derivatives. A gait standing on two feet is
balanced by a periodic body sway (:mod:`hexaleg.motion.balance`), one on three or more short of
its static margin is shifted over its support polygons (:mod:`hexaleg.motion.shift`;
``GaitParams.balance``); the body's motion is in :mod:`hexaleg.motion.body`, the inclined
ground in :mod:`hexaleg.motion.ground`.

All outputs are :class:`~hexaleg.motion.trajectory.Motion` objects in Pinocchio's conventions: base
velocity and acceleration in the LOCAL base frame, ``a = dv/dt``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import Any

import numpy as np

from hexaleg.checks import typed
from hexaleg.errors import HexalegError, InvalidParameterError, UnreachableTargetError
from hexaleg.motion.balance import Sway, balance_sway
from hexaleg.motion.body import (
    Body,
    base_state,
    body_height,
    body_motion,
    body_pose,
    gait_ground,
    heading,
    in_base_frame,
    nominal_footholds,
    rotz,
    swing_other_joints,
    walk_direction,
)
from hexaleg.motion.ground import Ground
from hexaleg.motion.kinematics import leg_ik
from hexaleg.motion.params import GaitParams
from hexaleg.motion.patterns import groups_of, leg_offsets
from hexaleg.motion.profiles import swing_curve
from hexaleg.motion.reach import explain
from hexaleg.motion.shift import required_margin, static_shift
from hexaleg.motion.support import static_margins, switch_margin
from hexaleg.motion.trajectory import Motion
from hexaleg.motion.zmp import balance_steps
from hexaleg.robot.model import Robot

PHASE_TOL = 1e-9
"""Phases within this fraction of a period of a switch count as at the switch (touch-down:
stance; lift-off: swing), so rounding in ``t / period − offset`` never splits a switch."""
Sways = Sway | tuple[Sway, ...] | None
"""The body's periodic displacement: a two-foot sway, the two components of a crawl's shift,
or none (:func:`hexaleg.motion.body.body_motion`)."""


def sample_gait(robot: Robot, gait: GaitParams | None = None,
                t: np.ndarray | None = None) -> Motion:
    """Evaluate the periodic gait at given times (the machinery of :func:`gait`).

    The base moves with the constant twist (local linear velocity ``speed · h`` along the
    walking direction h: the robot's heading, :attr:`hexaleg.robot.model.Robot.heading`, turned
    by ``gait.heading``; angular velocity ``[0, 0, yaw_rate]``) at ``body_height``, starting at
    the origin with zero yaw, plus the balancing sway or shift below; on a slope all of it in the
    ground's frame (:mod:`hexaleg.motion.ground`). A leg with touch-down offset o
    (:func:`hexaleg.motion.patterns.leg_offsets`) is in stance for the phase
    φ = (t/period − o) mod 1 < β (so at a switching instant the leg touching down is in stance
    and the one lifting off is not), its foot fixed at the world image of its nominal
    foothold at mid-stance; in swing it moves on :func:`~hexaleg.motion.profiles.swing_curve` from
    that point to the next mid-stance image (one stride ahead). The foot targets are taken into
    the base frame with the exact rotating-frame derivatives ``ṗ_b = −ω × p_b + Rᵀ ṗ − v`` and
    ``p̈_b = −ω × ṗ_b − ω × Rᵀ ṗ + Rᵀ p̈ − v̇`` and solved by
    :func:`hexaleg.motion.kinematics.leg_ik`.

    **Balance on two feet** (``gait.balance == "auto"`` and some sample of the cycle grid stands
    on exactly two feet, none on fewer — a trot: with β = 0.5 always exactly two, switching at
    t = 0 and t = period / 2; with β > 0.5 four-foot phases of (β − ½) · period after each
    switch). Two point feet cannot push a moment about the line through them, so the base is
    displaced by ``d(t) e`` along a horizontal direction e
    (:func:`hexaleg.motion.balance.sway_direction`: lateral for a trot), with d a trigonometric
    polynomial on the cycle grid
    (exact derivatives: the base velocity gains ``e ḋ + ω ẑ × e d`` and the acceleration
    ``e d̈ + ω ẑ × e ḋ``). d is the fixed point of: compute the exact moment M_k about each
    two-foot sample's support line from RNEA (:func:`hexaleg.motion.balance.support_moment`), add
    the periodic linear-inverted-pendulum sway that cancels it, ``g δd − h δd̈ = −M / (m s)`` on the
    two-foot samples and 0 on the others (:func:`hexaleg.motion.balance.periodic_lip_sway`, Kajita
    et al. ICRA 2003; h the mean CoM height, s the crossing factor), and re-sample the gait; it
    stops when ``max |M_k| ≤ BALANCE_TOL · m g h`` (:func:`hexaleg.motion.balance.balance_sway`).
    The stance feet stay at rest (the footholds do not move with the sway) and the swing feet
    follow the same world curves. At times ``t`` off the cycle grid the sway is the same
    trigonometric polynomial (balanced on the grid).

    Args:
        robot: The robot; joints outside the legs are held at the ``stand`` pose.
        gait: Gait parameters; default ``GaitParams()``.
        t: Times, shape (T,), s; default the cycle grid ``k · period / samples``.

    Returns:
        The motion (see :func:`tripod_gait` for the fields and ``info``); ``periodic`` is True
        only for the default cycle grid.

    Raises:
        UnknownNameError: a leg in ``gait.groups`` is not a leg of the robot.
        InvalidParameterError: a leg of the robot is in no group, ``t`` is not a non-empty
            1-D array of finite times, a support line is (nearly) parallel to every sway
            direction, or the robot's heading is not a horizontal vector.
        GaitReachError: a foot target is out of reach (an ``UnreachableTargetError``): names
            the leg, the time and phase, the target and its distance out of reach, the gait
            parameter most likely responsible and a value that works
            (:func:`hexaleg.motion.reach.explain`).
        InfeasibleForcesError: the sway iteration does not converge (the gait is too fast or
            its support lines too short to balance).
        StaticMarginError: the body shift cannot keep the required static margin (as
            :func:`gait`).
    """
    return _sample_gait(robot, GaitParams() if gait is None else gait, t, diagnose=True)


def _sample_gait(robot: Robot, gait: GaitParams, times: np.ndarray | None, *, diagnose: bool
                 ) -> Motion:
    """:func:`sample_gait`; ``diagnose``: explain an IK failure (:mod:`hexaleg.motion.reach`),
    checking its suggestion by generating the gait again without a diagnosis."""
    cycle_grid = times is None
    grid = np.arange(gait.samples) * (gait.period / gait.samples)
    t = grid if times is None else np.asarray(times, dtype=float)
    if t.ndim != 1 or len(t) == 0 or not np.all(np.isfinite(t)):
        raise InvalidParameterError("t", f"array of shape {t.shape}",
                                    "a non-empty 1-D array of finite times (s)")
    verify = (lambda other: _works(robot, other, times)) if diagnose else None
    offsets = _offsets(robot, gait)
    fewest = int(_stance_counts(gait, offsets, grid).min())
    mode = gait.balance_mode(fewest)

    def on_grid(sway: Sways, report: dict[str, Any]) -> Motion:
        return _sample(robot, gait, grid, True, sway, report, verify)

    sways: Sways
    if mode == "sway":
        motion, sways, report = balance_sway(robot, gait, grid, on_grid, heading(robot))
    elif mode == "zmp":
        motion, sways, report = balance_steps(robot, gait, grid, on_grid)
    elif mode == "shift":
        target = required_margin(robot, gait, nominal_footholds(robot, gait))
        motion = on_grid(None, {"mode": "none"})
        if gait.balance == "auto" and switch_margin(robot, motion) >= target:
            sways, report = None, {"mode": "none"}
        else:
            motion, sways, report = static_shift(robot, gait, motion, target, on_grid)
    else:
        return _sample(robot, gait, t, cycle_grid, None, {"mode": "none"}, verify)
    if cycle_grid:
        return motion
    return _sample(robot, gait, t, False, sways, report, verify)


def _works(robot: Robot, gait: GaitParams, times: np.ndarray | None) -> bool:
    """Whether the gait can be generated (at ``times``, as :func:`sample_gait`)."""
    try:
        _sample_gait(robot, gait, times, diagnose=False)
    except HexalegError:
        return False
    return True


@typed
def tripod_gait(robot: Robot, gait: GaitParams | None = None) -> Motion:
    """:func:`gait` under the name of its default, the hexapod's alternating tripod: one cycle
    of whatever gait ``gait`` describes (kept for the scripts that call it).

    Args:
        robot: The robot (e.g. ``load_robot()``).
        gait: Gait parameters; default ``GaitParams()``.

    Returns:
        ``gait(robot, gait)``.

    Raises:
        UnknownNameError, InvalidParameterError, GaitReachError, InfeasibleForcesError: as
            :func:`gait`.
    """
    return sample_gait(robot, gait)


@typed
def gait(robot: Robot, params: GaitParams | None = None) -> Motion:
    """One cycle of a periodic gait: any pattern, heading, slope (default: the hexapod's
    alternating tripod on level ground).

    Args:
        robot: The robot (e.g. ``load_robot()``).
        params: Gait parameters; default ``GaitParams()`` (period 1 s, β = 0.5, stride 0.06 m,
            step height 0.03 m, the ``stand`` height and footprint, 1000 samples, tripods).

    Returns:
        Motion with t (T,) = k · period / T (endpoint excluded), q (T, nq), v (T, nv) and
        a (T, nv) in Pinocchio's conventions (base velocity/acceleration in the LOCAL base
        frame), stance (T, n_legs) bool and the world foot targets feet (T, n_legs, 3) m, legs
        in ``robot.legs`` order; ``distance`` = stride, ``periodic`` True, ``fixed_base``
        False. ``info`` holds ``gait`` (the parameters), ``stride_length`` m, ``speed`` m/s,
        ``body_height`` m, ``foot_radius`` m, ``min_stance_feet``, ``static_margin`` m (the
        smallest distance of the CoM's ground projection inside the stance feet's support
        polygon over the cycle; None if some sample has fewer than 3 stance feet) and
        ``static_margin_t`` s (where it occurs), ``ik`` (solver per leg) and ``balance``:
        ``{"mode": "none"}``, or for a gait balanced on two feet (see :func:`sample_gait`)
        ``{"mode": "sway", "direction"`` (base frame, 3 floats), ``"amplitude"`` m (half the
        peak-to-peak sway), ``"height"`` m (the LIP height), ``"iterations"``, ``"residual"``
        (largest support-line moment / m g h) and ``"residuals"`` (per iteration, from the
        unswayed gait)``}``; for a crawl shifted over its support polygon
        (:func:`hexaleg.motion.shift.static_shift`) ``{"mode": "shift", "target"`` m,
        ``"margin"`` m, ``"amplitude"`` m, ``"iterations"}``. Also ``pattern`` (name or None),
        ``phases`` (leg → touch-down offset), ``groups`` (legs with equal offsets),
        ``heading`` rad, ``direction`` (walking direction, base frame), and on a slope
        ``ground`` (``slope``, ``cross_slope``, ``attitude``, ``normal``).

    Raises:
        UnknownNameError: a leg in ``gait.groups`` is not a leg of the robot.
        InvalidParameterError: a leg of the robot is in no group, ``phases`` has the wrong
            length, the pattern does not fit the robot's legs, or a support line cannot be
            crossed by a horizontal sway.
        GaitReachError: a foot target is out of reach (an ``UnreachableTargetError``; names
            the leg, the time and phase, the parameter to change and a value that works).
        InfeasibleForcesError: the balancing sway does not converge.
        StaticMarginError: the body shift cannot keep the required static margin (names the
            largest margin the gait allows, before any force program runs).
    """
    return sample_gait(robot, params)


def _offsets(robot: Robot, gait: GaitParams) -> np.ndarray:
    """Touch-down phase offset (fraction of the period) of each robot leg, shape (n_legs,)
    (:func:`hexaleg.motion.patterns.leg_offsets`)."""
    return leg_offsets(robot.leg_names, gait.pattern, gait.phases, gait.groups)


def _phase(t: np.ndarray, period: float, offset: float | np.ndarray
           ) -> tuple[np.ndarray, np.ndarray]:
    """Cycle number and phase in [0, 1) of a leg with touch-down ``offset`` at times ``t``
    (:data:`PHASE_TOL` puts a phase just short of a touch-down at the touch-down)."""
    tau = t / period - offset
    cycle = np.floor(tau + PHASE_TOL)
    return cycle, tau - cycle


def _foot_targets(t: np.ndarray, gait: GaitParams, offset: float, nominal: np.ndarray,
                  height: float, direction: np.ndarray | None = None,
                  ground: Ground | None = None
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """One foot's world target at times ``t`` (T,) (the stance and swing rule of
    :func:`sample_gait`): stance flags (T,), p (T, 3) m, ṗ (T, 3) m/s, p̈ (T, 3) m/s².

    Args:
        t: Times, s.
        gait: Gait parameters.
        offset: The leg's touch-down phase offset (fraction of the period).
        nominal: The leg's nominal foothold in the base frame, shape (3,), m.
        height: Body height, m (on a slope: the base's distance from the plane).
        direction: The heading the body travels along (base frame); default ``[1, 0, 0]``.
        ground: The inclined ground (the targets are made in its frame, the swing lifting
            along its normal, and rotated into the world), or None on level ground.
    """
    speed, beta, period, omega = gait.velocity, gait.duty_factor, gait.period, gait.yaw_rate
    local = nominal if ground is None else ground.tilt @ nominal

    def foothold(t_mid: np.ndarray) -> np.ndarray:
        pos, psi = body_pose(t_mid, speed, omega, height, direction)
        return pos + np.einsum("nij,j->ni", rotz(psi), local)

    cycle, phase = _phase(t, period, offset)
    on = phase < beta - PHASE_TOL
    t_mid = (cycle + offset + beta / 2) * period
    p_w = foothold(t_mid)
    pd_w = np.zeros((len(t), 3))
    pdd_w = np.zeros((len(t), 3))
    sw = ~on
    if sw.any():
        s = (phase[sw] - beta) / (1.0 - beta)
        t_swing = (1.0 - beta) * period
        p_s, dp_s, ddp_s = swing_curve(s, p_w[sw], foothold(t_mid[sw] + period), gait.step_height)
        p_w[sw], pd_w[sw], pdd_w[sw] = p_s, dp_s / t_swing, ddp_s / t_swing**2
    if ground is not None:
        rot = ground.rotation
        p_w, pd_w, pdd_w = p_w @ rot.T, pd_w @ rot.T, pdd_w @ rot.T
    return on, p_w, pd_w, pdd_w


def _stance_counts(gait: GaitParams, offsets: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Number of stance feet at times t, shape (T,) (the stance rule of :func:`sample_gait`)."""
    _, phase = _phase(t[:, None], gait.period, offsets[None, :])
    return (phase < gait.duty_factor - PHASE_TOL).sum(axis=1)


def _geometry(robot: Robot, gait: GaitParams
              ) -> tuple[np.ndarray, float, np.ndarray, Ground | None]:
    """Nominal footholds (n_legs, 3) in the base frame, the base's height above the ground
    (along its normal on a slope), the walking direction and the ground."""
    nominal = nominal_footholds(robot, gait)
    ground = gait_ground(robot, gait)
    if ground is None:
        return nominal, -float(nominal[0, 2]), walk_direction(robot, gait), None
    height = ground.base_distance(body_height(robot, gait))
    return nominal, height, walk_direction(robot, gait), ground


def _sample(robot: Robot, gait: GaitParams, t: np.ndarray, periodic: bool,
            sway: Sways, balance: dict[str, Any],
            verify: Callable[[GaitParams], bool] | None = None) -> Motion:
    """The gait at times ``t`` with an optional body sway (see :func:`sample_gait`); an IK
    failure is explained when ``verify`` (whether another gait works) is given."""
    offsets = _offsets(robot, gait)
    nominal, height, direction, ground = _geometry(robot, gait)
    body = body_motion(t, gait.velocity, gait.yaw_rate, height, sway, direction, ground)
    q, v, a = base_state(robot, body)
    swing_other_joints(robot, gait.period, t, q, v, a)
    n, n_legs = len(t), len(robot.legs)
    stance = np.zeros((n, n_legs), dtype=bool)
    feet = np.zeros((n, n_legs, 3))
    solvers = {}
    for i, leg in enumerate(robot.legs):
        on, p_w, pd_w, pdd_w = _foot_targets(t, gait, offsets[i], nominal[i], height, direction,
                                             ground)
        stance[:, i], feet[:, i] = on, p_w
        rel, rel_d, rel_dd = in_base_frame(body, p_w, pd_w, pdd_w)
        try:
            q_leg, qd_leg, qdd_leg, solvers[leg.name] = leg_ik(
                robot, leg, rel, rel_d, rel_dd, t=t,
                turn=sole_turn(body) if leg.name in robot.soles else None)
        except UnreachableTargetError as err:
            if verify is None:
                raise
            raise explain(robot, gait, err, i, t, on, _leg_targets(robot, offsets, t, sway),
                          verify) from err
        q[:, leg.q_index], v[:, leg.v_index], a[:, leg.v_index] = q_leg, qd_leg, qdd_leg

    margins = static_margins(robot, q, feet, stance)
    worst = int(np.argmin(margins))
    info = {
        "source": "tripod_gait",
        "gait": {f.name: getattr(gait, f.name) for f in dataclasses.fields(gait)},
        "stride_length": gait.stride, "speed": gait.velocity,
        "body_height": height if ground is None else body_height(robot, gait),
        "foot_radius": float(np.linalg.norm(nominal[:, :2], axis=1).mean()),
        "min_stance_feet": int(stance.sum(axis=1).min()),
        "static_margin": float(margins[worst]) if math.isfinite(margins[worst]) else None,
        "static_margin_t": float(t[worst]),
        "ik": solvers,
        "balance": balance,
        "pattern": gait.pattern,
        "phases": dict(zip(robot.leg_names, offsets.tolist(), strict=True)),
        "groups": groups_of(robot.leg_names, offsets),
        "heading": gait.heading, "direction": direction.tolist(),
        "cycle": _cycle(gait, height, direction, ground).tolist(),
    }
    if ground is not None:
        info["ground"] = {"slope": ground.slope, "cross_slope": ground.cross_slope,
                          "attitude": ground.attitude, "normal": ground.normal.tolist()}
    return Motion(t=t, q=q, v=v, a=a, stance=stance, feet=feet, period=gait.period,
                  distance=gait.stride, periodic=periodic, fixed_base=False, info=info,
                  normal=None if ground is None else ground.normal)


def sole_turn(body: Body) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """How a sole flat on level ground turns in the base frame under a body that yaws by ψ:
    θ = (0, 0, −ψ), θ̇ = (0, 0, −ψ̇), θ̈ = (0, 0, −ψ̈), each (N, 3), rad (the foot keeps its
    world orientation, the stand's; :func:`~hexaleg.motion.leg_ik.newton_leg_ik`'s ``turn``).

    Raises:
        InvalidParameterError: a body on a slope (soles walk level ground only).
    """
    if body.ground is not None:
        raise InvalidParameterError("[gait] slope with soles", "a slope",
                                    "level ground (a robot with soles walks level ground only)")
    n = len(body.yaw)
    out = np.zeros((3, n, 3))
    out[0, :, 2] = -body.yaw
    out[1, :, 2] = -np.broadcast_to(body.w, (n, 3))[:, 2]
    if body.alpha is not None:
        out[2, :, 2] = -body.alpha[:, 2]
    return out[0], out[1], out[2]


def _cycle(gait: GaitParams, height: float, direction: np.ndarray, ground: Ground | None
           ) -> np.ndarray:
    """The rigid motion of one cycle, world, 4 × 4: the constant-twist body's pose at
    t = period times its inverse at t = 0 (a sway or shift is periodic and drops out)."""
    body = body_motion(np.array([0.0, gait.period]), gait.velocity, gait.yaw_rate, height, None,
                       direction, ground)
    rot = body.rot[1] @ body.rot[0].T
    out = np.eye(4)
    out[:3, :3], out[:3, 3] = rot, body.base[1] - rot @ body.base[0]
    return out


def _leg_targets(robot: Robot, offsets: np.ndarray, t: np.ndarray, sway: Sways
                 ) -> Callable[[GaitParams, int, np.ndarray],
                               tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """``targets(gait, leg, index)``: leg ``leg``'s base-frame targets p, ṗ, p̈ at the samples
    ``t[index]`` of the gait ``gait`` (same sway), as :func:`_sample` solves them — what
    :func:`hexaleg.motion.reach.explain` tries other parameters on."""
    def targets(gait: GaitParams, leg: int, index: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        nominal, height, direction, ground = _geometry(robot, gait)
        body = body_motion(t[index], gait.velocity, gait.yaw_rate, height, sway, direction,
                           ground)
        _, p_w, pd_w, pdd_w = _foot_targets(t[index], gait, offsets[leg], nominal[leg], height,
                                            direction, ground)
        return in_base_frame(body, p_w, pd_w, pdd_w)
    return targets
