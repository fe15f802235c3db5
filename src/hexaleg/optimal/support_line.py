"""A two-point support's balance: the body's roll about the line through its feet, by dynamics.

Two point feet (a trot's diagonal pair) push any force through the line joining them but no
moment about it: the whole robot's angular momentum about that line changes only by gravity's
moment and the inertial moments of its own moving parts. So the body's rotation about the
support line is not the planner's to choose between the knots — it follows from the
centroidal dynamics (Orin, Goswami and Lee, *Centroidal dynamics of a humanoid robot*, Auton.
Robots 35, 2013). On flat ground it is the zero-moment point held on a support polygon that has
collapsed to the segment between the two feet (Kajita et al., *Introduction to Humanoid
Robotics*, Springer 2014, ch. 3): no moment about the line. Here it is written with the
whole-body inverse dynamics the force program uses: with ``f = RNEA(q, v, a)[:6]`` the wrench
the feet must supply to the base (Featherstone, *Rigid Body Dynamics Algorithms*, §5.3) and
``u`` the support line's unit direction through its point ``c``, the condition is

    m(t) = u · (n_O(f) − c × f_O(f)) = 0           (the moment about the line, world axes)

at every instant of the phase. A spline through the knots does not meet it between them.

The fix rolls the body about the support line by an angle ``θ(t)``: the base's placement
``M' = S(θ) M`` with ``S(θ) = (Q, c − Q c)``, ``Q = exp(θ [u]×)`` (:func:`roll`), the feet (on
the line, or on their own world paths) unmoved, the legs by their inverse kinematics. ``m`` is
affine in ``θ̈`` (the RNEA is affine in the acceleration; its coefficient is the whole body's
inertia about the line), so ``m(θ, θ̇, θ̈) = 0`` is a second-order ODE in ``θ``; with ``θ = 0``
at both ends of the phase (the body through the knots where the phase starts and ends) it is a
two-point boundary-value problem, solved by finite differences and Newton's method
(:func:`balance`). The roll's rate and acceleration at the phase's two ends are then brought to
the spline's in the neighbouring phases, whose support is not collinear and can push any
moment, by a quintic in ``θ`` over half of each (:func:`blend`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np
import pinocchio as pin
from scipy.linalg import solve_banded

from hexaleg.errors import InfeasibleForcesError
from hexaleg.motion.body import Body

COLLINEAR_TOL = 1e-6
"""Stance footholds are collinear when each lies within this distance of the line through the
two farthest apart, m."""

MOMENT_TOL = 1e-9
"""The moment about the support line left at a sample, N·m (the force program accepts a base
wrench whose unreachable part is below 1e-8 × (1 + its largest entry):
:data:`hexaleg.dynamics.reduction.REACH_TOL`)."""

NEWTON_ITERATIONS = 12
"""Newton steps of :func:`balance` at most."""

STEP = 1e-6
"""Forward-difference step of the partial derivatives ``∂m/∂θ`` (rad) and ``∂m/∂θ̇`` (rad/s)."""


class Phase(NamedTuple):
    """A phase of the cycle: one set of stance feet.

    Attributes:
        start: The phase's first knot.
        end: The knot after its last (the next phase's first; beyond N when the phase runs
            into the next cycle).
        point: A point of the support line (a stance foothold), world, (3,), m; None when the
            stance feet are not on one line (or fewer than two).
        axis: The line's unit direction, world, (3,); None likewise.
    """

    start: int
    end: int
    point: np.ndarray | None
    axis: np.ndarray | None


def _line(pts: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """The line through ``pts`` (k, 3) if k ≥ 2 and they lie on one (:data:`COLLINEAR_TOL`)."""
    if len(pts) < 2:
        return None
    d = np.linalg.norm(pts[:, None] - pts[None], axis=2)
    i, j = np.unravel_index(int(np.argmax(d)), d.shape)
    u = (pts[j] - pts[i]) / d[i, j]
    if np.linalg.norm(np.cross(pts - pts[i], u), axis=1).max() > COLLINEAR_TOL:
        return None
    return pts[i].copy(), u


def phases(stance: np.ndarray, footholds: np.ndarray) -> list[Phase]:
    """The cycle's phases in order, each with its support line when its stance feet (two or
    more) stand on one.

    Args:
        stance: Which legs stand at each knot, (N, n_legs) bool.
        footholds: Each stance foot's foothold at each knot, (N, n_legs, 3), m.

    Returns:
        The phases, the first starting at the cycle's first change of stance (none for a cycle
        whose stance never changes).
    """
    n = len(stance)
    changes = [k for k in range(n) if not np.array_equal(stance[k], stance[k - 1])]
    out = []
    for a, start in enumerate(changes):
        end = changes[(a + 1) % len(changes)]
        end = end + n if end <= start else end
        line = _line(footholds[start, stance[start]])
        out.append(Phase(start, end, *(line if line is not None else (None, None))))
    return out


def roll(body: Body, point: np.ndarray, axis: np.ndarray, th: np.ndarray, thd: np.ndarray,
         thdd: np.ndarray) -> Body:
    """``body`` rolled by ``θ(t)`` about the line through ``point`` along ``axis`` (module
    docstring): ``p' = c + Q (p − c)``, ``R' = Q R``, and with ``r' = p' − c``

    ``ṗ' = Q ṗ + θ̇ u × r'``, ``ω' = Q ω + θ̇ u``,
    ``p̈' = Q p̈ + θ̈ u × r' + θ̇ u × (θ̇ u × r') + 2 θ̇ u × Q ṗ``,
    ``ω̇' = Q ω̇ + θ̈ u + θ̇ u × Q ω`` (world axes; the derivatives of ``Q(θ(t))`` by
    ``Q̇ = θ̇ [u]× Q``), returned in the base's LOCAL frame as :class:`Body` holds them.

    Args:
        body: The body at T samples (level or not; LOCAL velocities).
        point: A point of the line, world, (3,) or (T, 3), m.
        axis: The line's unit direction, world, (3,) or (T, 3).
        th: ``θ`` at the samples, (T,), rad.
        thd: ``θ̇`` at the samples, (T,), rad/s.
        thdd: ``θ̈`` at the samples, (T,), rad/s².
    """
    n = len(body.base)
    u = np.broadcast_to(axis, (n, 3))
    c = np.broadcast_to(point, (n, 3))
    rot = body.rot
    v = np.broadcast_to(body.v, (n, 3))
    w = np.broadcast_to(body.w, (n, 3))
    acc = np.broadcast_to(body.a, (n, 3))
    alpha = np.zeros((n, 3)) if body.alpha is None else body.alpha
    q_rot = np.array([pin.exp3(x) for x in th[:, None] * u])
    pd = np.einsum("nij,nj->ni", rot, v)
    pdd = np.einsum("nij,nj->ni", rot, acc + np.cross(w, v))
    ow, owd = np.einsum("nij,nj->ni", rot, w), np.einsum("nij,nj->ni", rot, alpha)
    base = c + np.einsum("nij,nj->ni", q_rot, body.base - c)
    r = base - c
    qpd = np.einsum("nij,nj->ni", q_rot, pd)
    qow = np.einsum("nij,nj->ni", q_rot, ow)
    ud, udd = thd[:, None] * u, thdd[:, None] * u
    pd2 = qpd + np.cross(ud, r)
    pdd2 = (np.einsum("nij,nj->ni", q_rot, pdd) + np.cross(udd, r)
            + np.cross(ud, np.cross(ud, r)) + 2.0 * np.cross(ud, qpd))
    ow2 = qow + ud
    owd2 = np.einsum("nij,nj->ni", q_rot, owd) + udd + np.cross(ud, qow)
    rot2 = np.einsum("nij,njk->nik", q_rot, rot)
    v2 = np.einsum("nji,nj->ni", rot2, pd2)
    w2 = np.einsum("nji,nj->ni", rot2, ow2)
    a2 = np.einsum("nji,nj->ni", rot2, pdd2) - np.cross(w2, v2)
    alpha2 = np.einsum("nji,nj->ni", rot2, owd2)
    yaw = np.arctan2(rot2[:, 1, 0], rot2[:, 0, 0])
    return Body(base=base, yaw=yaw, rot=rot2, v=v2, w=w2, a=a2, ground=body.ground, alpha=alpha2)


Moment = Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]
"""``m(θ, θ̇, θ̈)``: at each of a phase's samples, the base wrench's moment about the support
line of the body rolled by ``θ``, N·m (module docstring); each argument (S,)."""


def _root(moment: Moment, th: np.ndarray, thd: np.ndarray) -> np.ndarray:
    """``θ̈`` that zeroes the moment about the line at ``θ``, ``θ̇`` (``m`` affine in ``θ̈``)."""
    m0 = moment(th, thd, np.zeros_like(th))
    return -m0 / (moment(th, thd, np.ones_like(th)) - m0)


def _rates(th: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
    """``θ̇``, ``θ̈`` by second-order differences (central inside, one-sided at the ends)."""
    thd = np.gradient(th, h, edge_order=2)
    thdd = np.zeros_like(th)
    thdd[1:-1] = (th[2:] - 2.0 * th[1:-1] + th[:-2]) / h**2
    return thd, thdd


def balance(moment: Moment, samples: int, h: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The roll ``θ`` of a phase on its S samples ``h`` apart that zeroes the moment about the
    line and is zero at both ends (module docstring): the two-point boundary-value problem
    ``m(θ, θ̇, θ̈) = 0`` by finite differences (``θ̇``, ``θ̈`` central, second order) solved by
    Newton's method, its tridiagonal Jacobian from the partial derivatives ``∂m/∂θ``,
    ``∂m/∂θ̇`` (forward differences) and ``∂m/∂θ̈`` (exact: ``m`` is affine in it); Ascher,
    Mattheij and Russell, *Numerical Solution of Boundary Value Problems for ODEs*, §5.1. At
    the two end samples ``θ̈`` is the dynamics' own (the moment's root at the end's ``θ̇``).

    Returns:
        ``θ``, ``θ̇``, ``θ̈`` at the samples, (S,) each: the moment about the line is within
        :data:`MOMENT_TOL` of zero at every one.

    Raises:
        InfeasibleForcesError: Newton's method not within :data:`MOMENT_TOL` after
            :data:`NEWTON_ITERATIONS` steps.
    """
    th = np.zeros(samples)
    inner = slice(1, samples - 1)
    for _ in range(NEWTON_ITERATIONS):
        thd, thdd = _rates(th, h)
        m = moment(th, thd, thdd)
        if np.abs(m[inner]).max(initial=0.0) <= MOMENT_TOL:
            break
        d_th = (moment(th + STEP, thd, thdd) - m) / STEP
        d_thd = (moment(th, thd + STEP, thdd) - m) / STEP
        d_thdd = moment(th, thd, thdd + 1.0) - m
        a, b, c = d_thdd / h**2 - d_thd / (2 * h), d_th - 2 * d_thdd / h**2, \
            d_thdd / h**2 + d_thd / (2 * h)
        bands = np.zeros((3, samples - 2))
        bands[0, 1:] = c[1:-2]  # above the diagonal: ∂r_i/∂θ_{i+1}
        bands[1] = b[inner]
        bands[2, :-1] = a[2:-1]  # below: ∂r_i/∂θ_{i−1}
        try:
            th[inner] -= solve_banded((1, 1), bands, m[inner])
        except np.linalg.LinAlgError as err:
            raise InfeasibleForcesError(
                "the body's roll about a two-point support line cannot be solved for: its "
                f"moment does not depend on the roll ({err}; a body with no inertia about the "
                "line?)") from err
    else:
        raise InfeasibleForcesError(
            f"the body's roll about a two-point support line does not balance its moment: "
            f"{np.abs(m[inner]).max():.3g} N·m left after {NEWTON_ITERATIONS} Newton steps "
            f"(allowed {MOMENT_TOL:g})")
    thd, thdd = _rates(th, h)
    ends = [0, samples - 1]
    thdd[ends] = _root(moment, th, thd)[ends]
    return th, thd, thdd


def blend(s: np.ndarray, rate: float, acceleration: float) -> tuple[np.ndarray, np.ndarray,
                                                                  np.ndarray]:
    """The quintic ``θ(s)`` on ``s ∈ [0, L]`` (``s`` the time from a collinear phase's end) with
    ``θ(0) = 0``, ``θ̇(0) = rate``, ``θ̈(0) = acceleration`` and ``θ = θ̇ = θ̈ = 0`` at ``L``
    (``s[-1]``): a roll that fades out while the support can push any moment; ``θ``, ``θ̇``,
    ``θ̈`` at ``s``. Run backwards in time (``s`` from a phase's start, ``rate`` negated) it
    fades one in."""
    length = float(s[-1])
    x = s / length
    # θ = c1 x + c2 x² + c3 x³ + c4 x⁴ + c5 x⁵ in x = s/L; c3…c5 from the three conditions at x = 1
    c1, c2 = rate * length, 0.5 * acceleration * length**2
    rhs = np.array([-c1 - c2, -c1 - 2 * c2, -2 * c2])
    lhs = np.array([[1.0, 1.0, 1.0], [3.0, 4.0, 5.0], [6.0, 12.0, 20.0]])
    c3, c4, c5 = np.linalg.solve(lhs, rhs)
    th = c1 * x + c2 * x**2 + c3 * x**3 + c4 * x**4 + c5 * x**5
    thd = (c1 + 2 * c2 * x + 3 * c3 * x**2 + 4 * c4 * x**3 + 5 * c5 * x**4) / length
    thdd = (2 * c2 + 6 * c3 * x + 12 * c4 * x**2 + 20 * c5 * x**3) / length**2
    return th, thd, thdd
