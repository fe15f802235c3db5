"""An optimal cycle rebuilt in task space: a motion a simulation plays as the solver planned it.

The solver's answer is ``N`` knots of a semi-implicit Euler integration (:mod:`~hexaleg.optimal
.problem`), ``dt = period / N`` apart (45 ms on the default robot). Between two knots nothing is
planned: a servo that interpolates the knots' joint angles (the simulation's cubic Hermite,
:func:`hexaleg.simulation.controllers.reference`) moves the stance feet off their footholds,
and the knots' own energy books a conservative force's work by the left Riemann sum — a linear
spring ``τ = −k q`` gains ``k/2 Σ Δq²`` a cycle from it, energy the motor is then spared in the
plan and not in the simulation.

This module makes the cycle a continuous motion the way hexaleg's parametric gaits are made
(:mod:`hexaleg.motion.legged`): in task space, then by each leg's inverse kinematics
(:func:`hexaleg.motion.kinematics.leg_ik`, exact joint velocities and accelerations), so that
the stance feet are exactly on their footholds at every instant:

* the base: a periodic C² cubic spline (de Boor, *A Practical Guide to Splines*, ch. IV)
  through the knots' base positions with the stride's drift ``(t/T) d`` removed, and one
  through the knots' rotation vectors ``log R_k`` (Pinocchio's ``log3``); ``R = exp(r)``, the
  LOCAL angular velocity ``ω = J_r(r) ṙ`` (the right Jacobian of SO(3), Pinocchio's ``Jexp3``),
  ``v = Rᵀ ṗ`` and ``v̇ = Rᵀ p̈ − ω × v``, ``ω̇`` by a central difference of the spline;
* each stance foot on its foothold (the problem's
  :attr:`~hexaleg.optimal.problem.OptimalProblem.footholds`), at rest;
* each swing foot: a cubic spline through the knots' foot positions of that swing, from the
  foothold it lifts off to the one it lands on, at rest at both ends (the problem's landing
  cost asks for rest at touch-down; lift-off leaves a foothold the contact held still);
* a joint on no leg (a tail, a head: :attr:`Robot.moves <hexaleg.robot.loaded.Robot.moves>`):
  a periodic cubic spline through its knots' angles.

A stance phase covers knots ``[k_td, k_lo)`` of the problem, so the rebuilt foot is on its
foothold for ``t ∈ [t_td, t_lo]`` and the sample at ``t`` takes the stance of knot
``⌊t/dt⌋``. hexaleg's pipeline (RNEA and the force program) then predicts the rebuilt motion's
energy as it predicts a parametric gait's, and the simulation plays it as planned.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
from scipy.interpolate import CubicSpline

from hexaleg.checks import integer
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.body import Body, in_base_frame
from hexaleg.motion.kinematics import leg_ik
from hexaleg.motion.legged import sole_turn
from hexaleg.motion.trajectory import Motion
from hexaleg.optimal.periodic import cycle_displacement
from hexaleg.robot.model import Robot

DIFFERENCE_STEP = 1e-5
"""Half the step of the central difference that gives the base's angular acceleration, in
units of the knot spacing (a spline's third derivative is bounded: the error is O(step²))."""


def _base(q: np.ndarray, t: np.ndarray, dt: float, displacement: np.ndarray) -> Body:
    """The base's spline motion at times ``t`` (module docstring) from the knots' ``q`` (N, nq)."""
    n = len(q)
    if not np.allclose(displacement[:3, :3], np.eye(3), atol=1e-9):
        raise InvalidParameterError("cycle displacement", displacement.tolist(),
                                    "a straight stride (no turn over a cycle)")
    stride = displacement[:3, 3]
    knots = np.arange(n + 1) * dt
    period = n * dt
    pos = np.vstack([q[:, :3], q[:1, :3] + stride])
    pos = pos - np.outer(knots / period, stride)
    rots = [pin.log3(pin.Quaternion(qk[3:7]).toRotationMatrix()) for qk in q]
    rv = np.vstack([rots, rots[:1]])
    ps, rs = CubicSpline(knots, pos, bc_type="periodic"), CubicSpline(knots, rv,
                                                                     bc_type="periodic")

    def angular(time: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        r, rd = rs(time % period), rs(time % period, 1)
        rot = np.array([pin.exp3(x) for x in r])
        w = np.array([pin.Jexp3(x) @ xd for x, xd in zip(r, rd, strict=True)])
        return rot, w

    tt = t % period
    base = ps(tt) + np.outer(t / period, stride)
    pd = ps(tt, 1) + stride / period
    pdd = ps(tt, 2)
    rot, w = angular(t)
    h = DIFFERENCE_STEP * dt
    alpha = (angular(t + h)[1] - angular(t - h)[1]) / (2.0 * h)
    v = np.einsum("nji,nj->ni", rot, pd)
    a = np.einsum("nji,nj->ni", rot, pdd) - np.cross(w, v)
    yaw = np.arctan2(rot[:, 1, 0], rot[:, 0, 0])
    return Body(base=base, yaw=yaw, rot=rot, v=v, w=w, a=a, ground=None, alpha=alpha)


def _foot(j: int, stance: np.ndarray, feet: np.ndarray, footholds: np.ndarray, t: np.ndarray,
          dt: float, stride: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Leg ``j``'s world position, velocity and acceleration at ``t`` (module docstring), from
    the knots' ``stance`` (N, n_legs), ``feet`` and ``footholds`` (N, n_legs, 3)."""
    n = len(stance)
    period = n * dt
    on = stance[:, j]
    p = np.zeros((len(t), 3))
    pd, pdd = np.zeros_like(p), np.zeros_like(p)
    cycle = np.floor(t / period)
    k = np.floor(np.round(t / dt, 9)).astype(int) % n
    if on.all():
        return p + footholds[0, j] + np.outer(cycle, stride), pd, pdd
    down = on[k]
    p[down] = footholds[k[down], j] + np.outer(cycle[down], stride)
    for lo in np.flatnonzero(~on & np.roll(on, 1)):  # first swing knot of each swing
        td = lo
        while not on[td % n]:
            td += 1
        idx = np.arange(lo, td + 1)
        shift = np.outer(idx // n, stride)
        pts = feet[idx % n, j] + shift
        pts[0] = footholds[(lo - 1) % n, j] + np.floor((lo - 1) / n) * stride
        pts[-1] = footholds[td % n, j] + (td // n) * stride
        spline = CubicSpline(idx * dt, pts, bc_type="clamped")
        for c in (-1, 0, 1):  # the swing may reach into the next cycle
            s = t - c * period
            sel = (s >= lo * dt) & (s <= td * dt) & ~down
            if sel.any():
                p[sel] = spline(s[sel]) + c * stride
                pd[sel], pdd[sel] = spline(s[sel], 1), spline(s[sel], 2)
    return p, pd, pdd


def task_space_motion(robot: Robot, knots: Motion, footholds: np.ndarray, *,
                      per_knot: int = 8) -> Motion:
    """The optimal cycle ``knots`` rebuilt in task space (module docstring), ``per_knot``
    samples a knot.

    Args:
        robot: The robot the cycle was solved for.
        knots: The solver's cycle (:attr:`~hexaleg.optimal.solve.OptimalResult.motion`), N
            knots, its stride in ``info["cycle"]``.
        footholds: Each stance foot's foothold at each knot, (N, n_legs, 3), m.
        per_knot: Samples a knot (≥ 1).

    Raises:
        InvalidParameterError: a cycle that turns, footholds of another shape.
        UnreachableTargetError: a foot target no leg reaches within its joint limits.
    """
    per_knot = integer("per_knot", per_knot, low=1)
    n = knots.n_samples
    if footholds.shape != (n, len(robot.legs), 3):
        raise InvalidParameterError("footholds.shape", footholds.shape,
                                    f"({n}, {len(robot.legs)}, 3)")
    displacement = cycle_displacement(knots)
    dt = knots.dt
    m = n * per_knot
    t = np.arange(m) * (dt / per_knot)
    body = _base(knots.q, t, dt, displacement)
    q = np.tile(knots.q[0], (m, 1))
    q[:, :3] = body.base
    q[:, 3:7] = np.array([pin.Quaternion(r).coeffs() for r in body.rot])
    v = np.zeros((m, robot.model.nv))
    a = np.zeros((m, robot.model.nv))
    v[:, :3], v[:, 3:6], a[:, :3], a[:, 3:6] = body.v, body.w, body.a, body.alpha
    on_legs = {int(i) for leg in robot.legs
               for i in np.atleast_1d(np.arange(robot.model.nv)[leg.v_index])}
    other = [(j.idx_q, j.idx_v) for j in list(robot.model.joints)[2:]
             if j.idx_v not in on_legs and j.nq == j.nv == 1]  # joints on no leg: splined
    if other:
        iq, iv = (np.array(x) for x in zip(*other, strict=True))
        spline = CubicSpline(np.arange(n + 1) * dt, np.vstack([knots.q[:, iq], knots.q[:1, iq]]),
                             bc_type="periodic")
        q[:, iq], v[:, iv], a[:, iv] = spline(t), spline(t, 1), spline(t, 2)
    stance = knots.stance[np.arange(m) // per_knot]
    feet = np.zeros((m, len(robot.legs), 3))
    for j, leg in enumerate(robot.legs):
        p, pd, pdd = _foot(j, knots.stance, knots.feet, footholds, t, dt, displacement[:3, 3])
        feet[:, j] = p
        rel, rel_d, rel_dd = in_base_frame(body, p, pd, pdd)
        q[:, leg.q_index], v[:, leg.v_index], a[:, leg.v_index], _ = leg_ik(
            robot, leg, rel, rel_d, rel_dd, t=t,
            turn=sole_turn(body) if leg.name in robot.soles else None)
    info = {k: val for k, val in knots.info.items() if k != "integrator"}
    info |= {"rebuilt": "task space", "per_knot": per_knot}
    return Motion(t=t, q=q, v=v, a=a, stance=stance, feet=feet, period=knots.period,
                  distance=knots.distance, periodic=True, info=info)
