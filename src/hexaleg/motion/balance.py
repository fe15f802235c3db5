"""Dynamic balance on two point feet: the support-line moment and the periodic body sway.

Two point contacts push only along lines through the two contact points, so their forces have no
moment about the line joining the feet. A motion whose whole-body Newton–Euler equations need such
a moment (gravity on a centre of mass off the line, the swinging legs' momentum) has no contact
forces. :func:`support_moment` measures that moment exactly from Pinocchio's RNEA;
:func:`periodic_lip_sway` gives the periodic horizontal body sway that cancels a prescribed moment
in the linear inverted pendulum model; :func:`balance_sway` iterates the two (with Anderson
acceleration) until the exact moment vanishes at every two-foot sample, for
:func:`hexaleg.motion.legged.sample_gait` (``GaitParams.balance``).

The linear inverted pendulum (LIP): a point mass m at constant height h above the ground whose
horizontal offset from a support line is d (along the line's horizontal normal) needs the moment
``m (g d − h d̈)`` about that line from the contacts (Kajita et al., "Biped walking pattern
generation by using preview control of zero-moment point", ICRA 2003, eq. 1–4: the ZMP
``p = x − (z_c/g) ẍ``; the moment about the support line is ``m g`` times the ZMP's distance
from it). For a body displaced by ``d(t) e`` along a horizontal direction e, only the component
of ``e`` across the support line (direction u) matters: ``s = u · (e × ẑ)``, and the moment is
``m s (g d − h d̈)``. Given a required correction ``M(t)`` the sway solves
``g d − h d̈ = f(t) = −M(t) / (m s)``; its periodic solution is unique because ``g + h (nω)² > 0``
for every harmonic n: per Fourier coefficient ``D_n = F_n / (g + h (nω)²)`` (equivalently
``D_n = −(F_n / h) / ((nω)² + g/h)`` for ``d̈ − (g/h) d = −f/h``).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg.checks import positive
from hexaleg.errors import InfeasibleForcesError, InvalidParameterError
from hexaleg.motion.params import GaitParams
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.units import G

BALANCE_TOL = 1e-10
"""The sway iteration stops when every two-foot sample's support-line moment is at most this
fraction of m g h (the weight's moment at the CoM height)."""
BALANCE_MAX_ITER = 60
"""Sway iterations allowed before the gait is declared impossible to balance."""
ANDERSON_DEPTH = 3
"""Previous iterates the sway iteration's Anderson acceleration combines."""
MIN_CROSSING = 0.2
"""Smallest |sin| of the angle between the sway direction and a support line (below it the
sway would have to be more than five times the needed CoM shift)."""


@dataclass(frozen=True, eq=False)
class Sway:
    """A periodic horizontal body sway ``d(t) e``: a real trigonometric polynomial along ``e``.

    ``d(t) = Re Σ_n c_n exp(i n ω t)`` over the one-sided spectrum of :func:`numpy.fft.rfft`
    (``c_0`` and, for an even number of samples, the Nyquist term counted once, the others twice),
    so ``d`` interpolates the samples it was made from and its derivatives are exact.

    Attributes:
        direction: Horizontal unit vector of the sway in the base frame, shape (3,) (z = 0).
        period: Period, s.
        coefficients: One-sided Fourier coefficients ``rfft(d_k) / N``, shape (N // 2 + 1,), m.
        samples: N, the number of samples per period the sway interpolates.
    """

    direction: np.ndarray
    period: float
    coefficients: np.ndarray
    samples: int

    @classmethod
    def from_samples(cls, direction: np.ndarray, period: float, d: np.ndarray) -> Sway:
        """The trigonometric interpolant of sway samples ``d[k] = d(k · period / N)``.

        Args:
            direction: Horizontal unit vector of the sway in the base frame, shape (3,).
            period: Period, s.
            d: Sway samples on the cycle grid, shape (N,), m.

        Returns:
            The sway.
        """
        d = np.asarray(d, dtype=float)
        return cls(np.asarray(direction, dtype=float), float(period),
                   np.fft.rfft(d) / len(d), len(d))

    def __call__(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Sway, its velocity and acceleration at times ``t``.

        Args:
            t: Times, shape (T,), s (any, not only the grid).

        Returns:
            d (T,) m, ḋ (T,) m/s, d̈ (T,) m/s² (exact derivatives of the trigonometric
            polynomial).
        """
        t = np.asarray(t, dtype=float)
        n = np.arange(len(self.coefficients))
        weight = np.where((n == 0) | (2 * n == self.samples), 1.0, 2.0)
        omega = 2.0 * math.pi / self.period * n
        phase = np.exp(1j * np.outer(t, omega))
        c = weight * self.coefficients
        terms = phase * c
        return (terms.real.sum(axis=1), (terms * (1j * omega)).real.sum(axis=1),
                (terms * -(omega**2)).real.sum(axis=1))

    @property
    def amplitude(self) -> float:
        """Half the peak-to-peak sway on the grid, m."""
        d = np.fft.irfft(self.coefficients * self.samples, n=self.samples)
        return float(np.ptp(d) / 2.0)


@dataclass(frozen=True, eq=False)
class Turn(Sway):
    """A periodic yaw ψ(t) of the body about its vertical (the ground's normal), rad: the
    trigonometric polynomial of :class:`Sway` (its samples, exact derivatives ψ̇, ψ̈), applied
    as a rotation (:func:`hexaleg.motion.body.body_motion`); ``direction`` is the turn's axis in
    the base frame."""


def periodic_lip_sway(f: np.ndarray, period: float, height: float,
                      gravity: float = G) -> np.ndarray:
    """The periodic solution of the linear inverted pendulum ``g d − h d̈ = f`` on the cycle grid.

    Per Fourier harmonic n (ω = 2π / period): ``D_n = F_n / (g + h (nω)²)`` (Kajita et al., ICRA
    2003, the LIP/cart-table model; see the module docstring). The equation then holds exactly at
    every sample for the trigonometric interpolant :class:`Sway` of the result, the Nyquist term
    included.

    Args:
        f: Right-hand side on the grid ``t_k = k · period / N``, shape (N,), m²/s².
        period: Period, s (> 0).
        height: Pendulum height h, m (> 0).
        gravity: g, m/s² (> 0); default :data:`hexaleg.units.G` (standard gravity; the exact
            moments of :func:`support_moment` use the model's gravity).

    Returns:
        Sway samples d_k, shape (N,), m.

    Raises:
        InvalidParameterError: a non-positive period, height or gravity.
    """
    for name, value in (("period", period), ("height", height), ("gravity", gravity)):
        positive(name, value)
    f = np.asarray(f, dtype=float)
    omega = 2.0 * math.pi / period * np.arange(len(f) // 2 + 1)
    return np.fft.irfft(np.fft.rfft(f) / (gravity + height * omega**2), n=len(f))


def support_lines(motion: Motion) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The line through the two stance feet of every two-foot sample, in the world frame.

    Args:
        motion: A motion with ``stance`` (T, n_legs) and ``feet`` (T, n_legs, 3).

    Returns:
        ``mask`` (T,) bool, the samples with exactly two stance feet; ``point`` (T, 3) m, the
        first stance foot (legs in robot order); ``axis`` (T, 3), the unit vector from it to the
        second. Rows outside ``mask`` are zero.
    """
    mask = motion.stance.sum(axis=1) == 2
    point = np.zeros((motion.n_samples, 3))
    axis = np.zeros((motion.n_samples, 3))
    for k in np.flatnonzero(mask):
        i, j = np.flatnonzero(motion.stance[k])
        delta = motion.feet[k, j] - motion.feet[k, i]
        point[k], axis[k] = motion.feet[k, i], delta / np.linalg.norm(delta)
    return mask, point, axis


def support_moment(robot: Robot, motion: Motion) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The moment about the support line that the contacts would have to supply, per sample.

    The base rows of RNEA, ``b_base = (M a + h)[:6]`` (force f_b and moment m_b about the base
    origin, in the base frame), are the wrench the stance feet must push on the robot (whole-body
    Newton–Euler). Its moment about the line through the two stance feet (point p, unit axis u,
    in the base frame) is ``u · (m_b − p × f_b)``; two point feet can only supply zero.

    Args:
        robot: The robot.
        motion: The motion (floating base).

    Returns:
        ``moment`` (T,) N·m (0 where the sample does not have exactly two stance feet), ``mask``
        (T,) bool (the two-foot samples) and ``axis_base`` (T, 3), the support line's unit axis
        in the base frame (0 outside ``mask``).
    """
    mask, point, axis = support_lines(motion)
    model, data = robot.model, robot.model.createData()
    moment = np.zeros(motion.n_samples)
    axis_base = np.zeros((motion.n_samples, 3))
    for k in np.flatnonzero(mask):
        q = motion.q[k]
        wrench = pin.rnea(model, data, q, motion.v[k], motion.a[k])[:6]
        rot = pin.Quaternion(q[3:7]).toRotationMatrix()
        p = rot.T @ (point[k] - q[:3])
        u = rot.T @ axis[k]
        f = wrench[:3]  # p × f written out: numpy's cross of two 3-vectors, the same products
        # and differences, spends more in its checks than in them (a sixth of the making of
        # a gait on Solo-12, profiled)
        moment[k] = u @ (wrench[3:] - np.array([p[1] * f[2] - p[2] * f[1],
                                                 p[2] * f[0] - p[0] * f[2],
                                                 p[0] * f[1] - p[1] * f[0]]))
        axis_base[k] = u
    return moment, mask, axis_base


def sway_direction(axes: np.ndarray, heading: np.ndarray | None = None) -> np.ndarray:
    """The horizontal sway direction that best crosses every support line: lateral if possible.

    Chooses the unit vector e in the base frame's horizontal plane that maximises the smallest
    ``|s| = |u · (e × ẑ)|`` (the sine of the angle between e and a support line u) over the given
    lines, trying directions at 1° steps from the lateral axis (ẑ × heading: the base's y axis
    for the default heading x); ties keep the one closest to lateral. For a trot (two diagonals
    mirrored about the heading) that is lateral; for a bound (lines across the body) it is
    along the heading.

    Args:
        axes: Support line directions in the base frame, shape (L, 3).
        heading: The robot's heading, a horizontal unit vector in the base frame, shape (3,);
            default ``[1, 0, 0]``.

    Returns:
        e, shape (3,).
    """
    offsets = [0.0, *(sign * k for k in range(1, 90) for sign in (1.0, -1.0)), -90.0]
    angles = np.deg2rad(90.0 + np.array(offsets))  # lateral first, then ever further from it
    if heading is not None and not (heading[0] == 1.0 and heading[1] == 0.0):
        angles = angles + math.atan2(heading[1], heading[0])
    candidates = np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)], axis=1)
    candidates[np.abs(candidates) < 1e-15] = 0.0  # exactly lateral/longitudinal at 90°, 0°
    cross = np.cross(candidates, [0.0, 0.0, 1.0])  # e × ẑ
    score = np.abs(cross @ np.asarray(axes, dtype=float).T).min(axis=1)
    best = int(np.flatnonzero(score >= score.max() - 1e-12)[0])
    return candidates[best]


def leg_plane(robot: Robot) -> np.ndarray | None:
    """The horizontal direction (base frame, unit, shape (3,)) in which every leg's foot can move
    when every leg has two joints turning about parallel axes (a planar hip–knee leg, its foot in
    the plane normal to them, :mod:`hexaleg.motion.leg_chain`) and the legs' planes are parallel
    and vertical: ``ẑ × n``, n their axis at the zero configuration (its sign towards the
    heading's side, +x first). None otherwise (a leg that steps sideways, or legs in planes that
    share no horizontal direction)."""
    if any(len(leg.joint_names) != 2 for leg in robot.legs):
        return None
    model, data = robot.model, robot.model.createData()
    pin.computeJointJacobians(model, data, pin.neutral(model))
    normal: np.ndarray | None = None
    for leg in robot.legs:
        axes = [pin.getJointJacobian(model, data, j, pin.LOCAL_WORLD_ALIGNED)[3:, idx]
                for j, idx in zip(leg.joint_ids, leg.v_index, strict=True)]
        n = axes[0] / np.linalg.norm(axes[0])
        if np.linalg.norm(np.cross(n, axes[1] / np.linalg.norm(axes[1]))) > 1e-6 or \
                abs(n[2]) > 1e-6:
            return None
        if normal is None:
            normal = n
        elif np.linalg.norm(np.cross(normal, n)) > 1e-6:
            return None
    if normal is None:
        return None
    e = np.cross([0.0, 0.0, 1.0], normal)
    e /= np.linalg.norm(e)
    return -e if (e[0], e[1]) < (0.0, 0.0) else e


def crossing(axis_base: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """``s = u · (e × ẑ)`` per sample: how much a sway along e moves the CoM across line u.

    Args:
        axis_base: Support line axes in the base frame, shape (T, 3).
        direction: Sway direction e in the base frame, shape (3,).

    Returns:
        s, shape (T,), in [−1, 1].
    """
    return axis_base @ np.cross(direction, [0.0, 0.0, 1.0])


def balance_sway(robot: Robot, gait: GaitParams, grid: np.ndarray,
                 sample: Callable[[Sway | None, dict[str, Any]], Motion],
                 heading: np.ndarray | None = None) -> tuple[Motion, Sway, dict[str, Any]]:
    """The body sway that balances a two-foot gait on its cycle grid: a fixed-point iteration.

    ``d`` is the fixed point of: compute the exact moment M_k about each two-foot sample's
    support line (:func:`support_moment`), add the periodic linear-inverted-pendulum sway that
    cancels it, ``g δd − h δd̈ = −M / (m s)`` on the two-foot samples and 0 on the others
    (:func:`periodic_lip_sway`, Kajita et al. ICRA 2003; h the mean CoM height, s the crossing
    factor), and re-sample the gait; the iterates are combined by Anderson acceleration
    (:func:`anderson`). It stops when ``max |M_k| ≤ BALANCE_TOL · m g h``.

    Args:
        robot: The robot.
        gait: The gait's parameters (period, groups for the messages).
        grid: The cycle grid ``k · period / samples``, shape (N,), s.
        sample: The gait on ``grid`` with a sway (None: the constant-twist body) and the
            ``info["balance"]`` report to store (:func:`hexaleg.motion.legged.sample_gait`).
        heading: The robot's heading in the base frame (:func:`sway_direction`); default x.

    Returns:
        The balanced motion, its sway and the report (``mode``, ``direction``, ``height``,
        ``iterations``, ``amplitude``, ``residual``, ``residuals``).

    Raises:
        InvalidParameterError: a support line is (nearly) parallel to the sway direction.
        InfeasibleForcesError: the iteration does not converge in ``BALANCE_MAX_ITER`` steps.
    """
    motion = sample(None, {"mode": "none"})
    moment, mask, axes = support_moment(robot, motion)
    plane = leg_plane(robot)  # planar legs sway in their planes, where their feet can move
    direction = (plane if plane is not None else
                 sway_direction(np.unique(np.round(axes[mask], 12), axis=0), heading))
    model, data = robot.model, robot.model.createData()
    height = float(np.mean([pin.centerOfMass(model, data, q)[2] for q in motion.q]))
    mass, g = robot.mass, float(np.linalg.norm(model.gravity.linear))
    scale = mass * g * height
    d = np.zeros(len(grid))
    history: list[tuple[np.ndarray, np.ndarray]] = []
    residuals = [float(np.abs(moment).max() / scale)]
    for _ in range(BALANCE_MAX_ITER):
        s = crossing(axes, direction)
        if np.abs(s[mask]).min() < MIN_CROSSING:
            k = int(np.flatnonzero(mask)[np.argmin(np.abs(s[mask]))])
            raise InvalidParameterError(
                "groups", gait.groups, f"two-foot support lines that a horizontal body sway can "
                f"cross; at t = {grid[k]:.4g} s the line has |sin| = {abs(s[k]):.3g} < "
                f"{MIN_CROSSING} with the sway direction {np.round(direction, 3).tolist()}")
        f = np.zeros(len(grid))
        f[mask] = -moment[mask] / (mass * s[mask])
        step = periodic_lip_sway(f, gait.period, height, g)
        history.append((d + step, step))
        d = anderson(history[-ANDERSON_DEPTH - 1:])
        sway = Sway.from_samples(direction, gait.period, d)
        report = {"mode": "sway", "direction": direction.tolist(), "height": height,
                  "iterations": len(residuals), "amplitude": sway.amplitude}
        motion = sample(sway, report)
        moment, mask, axes = support_moment(robot, motion)
        residuals.append(float(np.abs(moment).max() / scale))
        report["residual"] = residuals[-1]
        report["residuals"] = residuals
        if residuals[-1] <= BALANCE_TOL:
            return motion, sway, report
    raise InfeasibleForcesError(
        f"the body sway that balances the two-foot phases did not converge in "
        f"{BALANCE_MAX_ITER} iterations: support-line moment {residuals[-1]:.3g} m g h "
        f"(allowed {BALANCE_TOL:g}); a slower gait, a smaller stride or balance = 'none'")


def anderson(history: list[tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
    """Anderson-accelerated next iterate from ``(G(d_i), r_i = G(d_i) − d_i)``, oldest first.

    ``d⁺ = G(d_k) − ΔG γ`` with γ minimising ``‖r_k − ΔR γ‖`` over the differences of the last
    iterates (Walker & Ni, "Anderson acceleration for fixed-point iterations", SIAM J. Numer.
    Anal. 49(4), 2011, Algorithm AA); with one entry it is the plain fixed-point step.
    """
    g_k, r_k = history[-1]
    if len(history) == 1:
        return g_k
    d_g = np.stack([b[0] - a[0] for a, b in itertools.pairwise(history)], axis=1)
    d_r = np.stack([b[1] - a[1] for a, b in itertools.pairwise(history)], axis=1)
    gamma = np.linalg.lstsq(d_r, r_k, rcond=None)[0]
    return g_k - d_g @ gamma
