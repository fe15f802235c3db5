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

* where the stance feet stand on one line (a trot's diagonal pair: two point feet push no moment
  about the line through them), the base rolled about that line by the angle its dynamics
  asks (:mod:`~hexaleg.optimal.support_line`): zero at the phase's ends, so the base still
  passes through the knots there, and faded in and out over half of each neighbouring phase,
  whose feet push any moment. A collinear phase next to another (no phase to fade in) is left
  as splined and named in ``info["unbalanced two-point phases"]``; a robot with soles (flat
  feet push moments) is not rolled.

A stance phase covers knots ``[k_td, k_lo)`` of the problem, so the rebuilt foot is on its
foothold for ``t ∈ [t_td, t_lo]`` and the sample at ``t`` takes the stance of knot
``⌊t/dt⌋``. hexaleg's pipeline (RNEA and the force program) then predicts the rebuilt motion's
energy as it predicts a parametric gait's, and the simulation plays it as planned.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pinocchio as pin
from scipy.interpolate import CubicSpline

from hexaleg.checks import integer
from hexaleg.errors import InvalidParameterError, UnreachableTargetError
from hexaleg.motion.body import Body, in_base_frame
from hexaleg.motion.kinematics import leg_ik
from hexaleg.motion.legged import sole_turn
from hexaleg.motion.trajectory import Motion
from hexaleg.optimal.periodic import cycle_displacement
from hexaleg.optimal.support_line import Moment, balance, blend, phases, roll
from hexaleg.robot.model import Robot

DIFFERENCE_STEP = 1e-5
"""Half the step of the central difference that gives the base's angular acceleration, in
units of the knot spacing (a spline's third derivative is bounded: the error is O(step²))."""


BasePath = Callable[[np.ndarray], Body]
"""The base's spline motion at given times, s."""

FeetPath = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]
"""Every foot's world position, velocity and acceleration at given times, each (T, n_legs, 3)."""


def _base_path(q: np.ndarray, dt: float, displacement: np.ndarray) -> BasePath:
    """The base's spline motion (module docstring) from the knots' ``q`` (N, nq)."""
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

    def path(t: np.ndarray) -> Body:
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

    return path


def _feet_path(stance: np.ndarray, feet: np.ndarray, footholds: np.ndarray, dt: float,
               stride: np.ndarray) -> FeetPath:
    """Every leg's world path (module docstring), from the knots' ``stance`` (N, n_legs),
    ``feet`` and ``footholds`` (N, n_legs, 3)."""
    n, legs = stance.shape
    period = n * dt
    swings: list[list[tuple[int, int, CubicSpline]]] = []
    for j in range(legs):
        on = stance[:, j]
        mine = []
        for lo in np.flatnonzero(~on & np.roll(on, 1)):  # first swing knot of each swing
            td = lo
            while not on[td % n]:
                td += 1
            idx = np.arange(lo, td + 1)
            pts = feet[idx % n, j] + np.outer(idx // n, stride)
            pts[0] = footholds[(lo - 1) % n, j] + np.floor((lo - 1) / n) * stride
            pts[-1] = footholds[td % n, j] + (td // n) * stride
            mine.append((int(lo), int(td), CubicSpline(idx * dt, pts, bc_type="clamped")))
        swings.append(mine)

    def path(t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        p = np.zeros((len(t), legs, 3))
        pd, pdd = np.zeros_like(p), np.zeros_like(p)
        cycle = np.floor(t / period)
        k = np.floor(np.round(t / dt, 9)).astype(int) % n
        for j in range(legs):
            down = stance[k, j]
            p[down, j] = footholds[k[down], j] + np.outer(cycle[down], stride)
            for lo, td, spline in swings[j]:
                for c in (-1, 0, 1):  # the swing may reach into the next cycle
                    s = t - c * period
                    sel = (s >= lo * dt) & (s <= td * dt) & ~down
                    if sel.any():
                        p[sel, j] = spline(s[sel]) + c * stride
                        pd[sel, j], pdd[sel, j] = spline(s[sel], 1), spline(s[sel], 2)
        return p, pd, pdd

    return path


class _Whole:
    """The whole robot's ``q``, ``v``, ``a`` from the base's and the feet's motion: the legs by
    their inverse kinematics, a joint on no leg by a periodic spline through its knots."""

    def __init__(self, robot: Robot, knots: Motion) -> None:
        self.robot = robot
        self.template = knots.q[0]
        self.period = knots.period
        n, dt = knots.n_samples, knots.dt
        on_legs = {int(i) for leg in robot.legs
                   for i in np.atleast_1d(np.arange(robot.model.nv)[leg.v_index])}
        other = [(j.idx_q, j.idx_v) for j in list(robot.model.joints)[2:]
                 if j.idx_v not in on_legs and j.nq == j.nv == 1]  # joints on no leg: splined
        self.other: tuple[np.ndarray, np.ndarray, CubicSpline] | None = None
        if other:
            iq, iv = (np.array(x) for x in zip(*other, strict=True))
            self.other = (iq, iv, CubicSpline(np.arange(n + 1) * dt,
                                              np.vstack([knots.q[:, iq], knots.q[:1, iq]]),
                                              bc_type="periodic"))

    def __call__(self, t: np.ndarray, body: Body, p: np.ndarray, pd: np.ndarray,
                 pdd: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        robot = self.robot
        m = len(t)
        q = np.tile(self.template, (m, 1))
        q[:, :3] = body.base
        q[:, 3:7] = np.array([pin.Quaternion(r).coeffs() for r in body.rot])
        v = np.zeros((m, robot.model.nv))
        a = np.zeros((m, robot.model.nv))
        v[:, :3], v[:, 3:6], a[:, :3] = body.v, body.w, body.a
        if body.alpha is not None:
            a[:, 3:6] = body.alpha
        if self.other is not None:
            iq, iv, spline = self.other
            tt = t % self.period
            q[:, iq], v[:, iv], a[:, iv] = spline(tt), spline(tt, 1), spline(tt, 2)
        for j, leg in enumerate(robot.legs):
            rel, rel_d, rel_dd = in_base_frame(body, p[:, j], pd[:, j], pdd[:, j])
            q[:, leg.q_index], v[:, leg.v_index], a[:, leg.v_index], _ = leg_ik(
                robot, leg, rel, rel_d, rel_dd, t=t,
                turn=sole_turn(body) if leg.name in robot.soles else None)
        return q, v, a


def _moment(robot: Robot, whole: _Whole, t: np.ndarray, body: Body,
            feet: tuple[np.ndarray, np.ndarray, np.ndarray], point: np.ndarray,
            axis: np.ndarray) -> Moment:
    """The base wrench's moment about the support line (:data:`~hexaleg.optimal.support_line
    .Moment`) at times ``t`` of the ``body`` and ``feet`` paths there, the body rolled about
    the line: hexaleg's RNEA (Pinocchio's, gravity included) at the rolled motion; its
    free-flyer rows are the wrench the feet must supply in the base frame, taken to world axes
    and to the line's point."""
    data = robot.model.createData()

    def moment(th: np.ndarray, thd: np.ndarray, thdd: np.ndarray) -> np.ndarray:
        rolled = roll(body, point, axis, th, thd, thdd)
        q, v, a = whole(t, rolled, *feet)
        out = np.zeros(len(t))
        for i in range(len(t)):
            tau = pin.rnea(robot.model, data, q[i], v[i], a[i])
            world = pin.SE3(rolled.rot[i], rolled.base[i]).act(pin.Force(tau[:6]))
            out[i] = axis @ (world.angular - np.cross(point, world.linear))
        return out

    return moment


def _balanced(robot: Robot, whole: _Whole, base: BasePath, feet: FeetPath, stance: np.ndarray,
              footholds: np.ndarray, dt: float, per_knot: int, stride: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, list[str]]:
    """Each sample's roll about its support line (:mod:`~hexaleg.optimal.support_line`): ``θ``,
    ``θ̇``, ``θ̈`` (M,), the line's point and axis (M, 3), and the phases left unbalanced (a
    collinear phase next to another: no room to bring the roll back to the spline's)."""
    n = len(stance)
    m = n * per_knot
    h = dt / per_knot
    th, thd, thdd = np.zeros(m), np.zeros(m), np.zeros(m)
    point, axis = np.zeros((m, 3)), np.tile([1.0, 0.0, 0.0], (m, 1))
    cycle = phases(stance, footholds)
    skipped = []

    def put(first: int, values: tuple[np.ndarray, ...], c: np.ndarray, u: np.ndarray) -> None:
        idx = first + np.arange(len(values[0]))
        back = np.where(idx >= m, 1.0, 0.0) - np.where(idx < 0, 1.0, 0.0)
        idx %= m
        th[idx], thd[idx], thdd[idx] = values
        point[idx] = c - np.outer(back, stride)
        axis[idx] = u

    for i, ph in enumerate(cycle):
        if ph.point is None or ph.axis is None:
            continue
        before, after = cycle[i - 1], cycle[(i + 1) % len(cycle)]
        room = ((before.end - before.start) * per_knot // 2,
                (after.end - after.start) * per_knot // 2)
        if before.point is not None or after.point is not None or min(room) < 1:
            skipped.append(f"{ph.start * dt:.4f} s")
            continue
        tt = (ph.start * per_knot + np.arange((ph.end - ph.start) * per_knot + 1)) * h
        values = balance(_moment(robot, whole, tt, base(tt), feet(tt), ph.point, ph.axis),
                         len(tt), h)
        put(ph.start * per_knot, values, ph.point, ph.axis)
        s = np.arange(room[1] + 1) * h  # fade out over the next phase's first half
        put(ph.end * per_knot, blend(s, values[1][-1], values[2][-1]), ph.point, ph.axis)
        s = np.arange(room[0] + 1) * h  # fade in over the previous phase's second half
        fade, fade_d, fade_dd = blend(s, -values[1][0], values[2][0])
        put(ph.start * per_knot - room[0], (fade[::-1], -fade_d[::-1], fade_dd[::-1]),
            ph.point, ph.axis)
    return th, thd, thdd, point, axis, skipped


def _between_knots(err: UnreachableTargetError, robot: Robot, knots: Motion
                   ) -> UnreachableTargetError:
    """The rebuild's out-of-reach foot target ``err`` (a leg's inverse kinematics) said of the
    optimal cycle: the knots the sample lies between, whether its leg stands or swings there
    (the swing's lift-off and touch-down knots), and why the knots can reach where the cycle
    through them cannot — the problem bounds a leg's reach at its knots only, and between
    them the rebuild's base spline carries the body on while a foot rests at its lift-off and
    touch-down or holds its foothold. The fields (leg, time, target, distance) are ``err``'s."""
    names = [leg.name for leg in robot.legs]
    if err.t is None or err.leg not in names:
        return err
    n, dt = knots.n_samples, knots.dt
    at = err.t / dt
    k = int(np.floor(round(at, 9)))
    on = np.asarray(knots.stance, dtype=bool)[:, names.index(err.leg)]
    if on[k % n]:
        phase = "holds its foothold (a stance knot)"
    else:
        lift, down = k, k
        while not on[(lift - 1) % n]:
            lift -= 1
        while not on[down % n]:
            down += 1
        phase = (f"swings (its swing from knot {lift % n}, its lift-off at "
                 f"{lift * dt % knots.period:.4g} s, to knot {down % n}, its touch-down)")
    return UnreachableTargetError(
        f"the optimal cycle rebuilt in task space: {err} — at {at - k:.2f} of the way from "
        f"knot {k % n} to knot {(k + 1) % n} ({dt * 1e3:.4g} ms apart), where leg {err.leg} "
        f"{phase}. Every knot reaches its feet (it is a configuration); the cycle through "
        "them does not: the optimal-control problem bounds a leg's reach at its knots only, "
        "and between them the base moves on while the foot rests at its lift-off or "
        "touch-down or holds its foothold (a leg stretched to within a fraction of a "
        "millimetre at a knot is then out of reach)",
        leg=err.leg, t=err.t, index=err.index, target=err.target, distance=err.distance)


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
        UnreachableTargetError: a foot target no leg reaches within its joint limits; the
            message says between which knots and in which phase of the leg.
        InfeasibleForcesError: a two-point phase whose roll cannot be brought back to the knots
            (:func:`~hexaleg.optimal.support_line.balance`).
    """
    per_knot = integer("per_knot", per_knot, low=1)
    n = knots.n_samples
    if footholds.shape != (n, len(robot.legs), 3):
        raise InvalidParameterError("footholds.shape", footholds.shape,
                                    f"({n}, {len(robot.legs)}, 3)")
    displacement = cycle_displacement(knots)
    stride = displacement[:3, 3]
    dt = knots.dt
    m = n * per_knot
    t = np.arange(m) * (dt / per_knot)
    base = _base_path(knots.q, dt, displacement)
    feet = _feet_path(knots.stance, knots.feet, footholds, dt, stride)
    whole = _Whole(robot, knots)
    point_feet = not any(leg.name in robot.soles for leg in robot.legs)
    try:
        th, thd, thdd, point, axis, skipped = (
            _balanced(robot, whole, base, feet, knots.stance, footholds, dt, per_knot, stride)
            if point_feet else (np.zeros(m),) * 3 + (np.zeros((m, 3)),) * 2 + ([],))
        body = roll(base(t), point, axis, th, thd, thdd)
        p, pd, pdd = feet(t)
        q, v, a = whole(t, body, p, pd, pdd)
    except UnreachableTargetError as err:
        raise _between_knots(err, robot, knots) from err
    info = {k: val for k, val in knots.info.items() if k != "integrator"}
    info |= {"rebuilt": "task space", "per_knot": per_knot,
             "largest roll about a support line": float(np.abs(th).max())}
    if skipped:
        info["unbalanced two-point phases"] = skipped
    return Motion(t=t, q=q, v=v, a=a, stance=knots.stance[np.arange(m) // per_knot], feet=p,
                  period=knots.period, distance=knots.distance, periodic=True, info=info)
