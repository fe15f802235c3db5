"""Dynamic balance through single support: a ZMP walking pattern for gaits on one foot.

One point foot pushes no moment about itself, so a sample on one foot has contact forces only if
the moment about the foot of gravity and of the robot's momentum rate vanishes — all three of
its components; two point feet push none about the line through them. A gait whose cycle has
one-foot samples (a biped's walk, a quadruped's crawl at a duty factor below 0.5) is balanced by
moving the body: a horizontal sway (along the base's x and y) puts the zero-moment point (ZMP;
Vukobratović & Borovac, "Zero-moment point — thirty five years of its life", Int. J. Humanoid
Robotics 1(1), 2004) on the stance foot, and a yaw turn ψ(t) cancels the moment about the
vertical that the swinging legs' momentum needs.

The ZMP reference (:func:`zmp_reference`): on a one-foot sample the foot; on a run of two-foot
samples the point moving linearly in time from the feet that stood before the run to those that
stand after it (Kajita et al., "Biped walking pattern generation by using preview control of
zero-moment point", ICRA 2003, §II: in double support the ZMP moves from one foot to the next);
samples on three or more feet have no reference (their feet share any moment).

:func:`balance_steps` is the iteration of :func:`hexaleg.motion.balance.balance_sway` in three
coordinates. It computes the exact moment M (base frame) the contacts would have to push about
each sample's reference (RNEA's base rows), then adds the periodic linear-inverted-pendulum sway
that cancels its horizontal part, ``g δx − h δẍ = M_y / m`` and ``g δy − h δÿ = −M_x / m`` on
the referenced samples and 0 on the others (:func:`hexaleg.motion.balance.periodic_lip_sway`),
and the turn whose yaw acceleration cancels the vertical part on the one-foot samples,
``I_z δψ̈ = −M_z`` (I_z the robot's inertia about the base's vertical axis at the stand pose,
from CRBA). Two feet can push a moment about the vertical, but only with friction forces that a
foot near the end of its load cannot give, so the turn also cancels it on the two-foot samples
as closely as a periodic ψ allows: there, and on samples on more feet, δψ̈ is shifted by the
one constant that gives it zero mean (the least-squares shift that keeps ψ periodic).
Anderson acceleration combines the iterates. It stops when every referenced moment is at most
:data:`hexaleg.motion.balance.BALANCE_TOL` · m g h. A gait on one foot at every sample (a biped
at duty factor 0.5) has no two-foot sample to carry the vertical moment's cycle mean, which a
periodic ψ cannot cancel (ψ̈ has zero mean): a robot whose sides are not exact mirror images
(ODRI's Bolt: 3e-6 N·m) is refused naming that mean and a duty factor with two-foot phases.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg.errors import InfeasibleForcesError
from hexaleg.motion.balance import (
    ANDERSON_DEPTH,
    BALANCE_MAX_ITER,
    BALANCE_TOL,
    Sway,
    Turn,
    anderson,
    periodic_lip_sway,
)
from hexaleg.motion.params import GaitParams
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot

AXES = np.eye(3)
"""The sway directions (base x, base y) and the turn's axis (base z)."""


def zmp_reference(motion: Motion) -> tuple[np.ndarray, np.ndarray]:
    """The ZMP reference of every sample on one or two feet, in the world frame.

    Args:
        motion: A periodic motion on its cycle grid, with ``stance`` (T, n_legs) and ``feet``
            (T, n_legs, 3).

    Returns:
        ``mask`` (T,) bool, the samples on one or two feet, and ``points`` (T, 3) m, their
        reference (module docstring; zero outside ``mask``). A two-foot run's reference at its
        j-th of L samples is ``a + (j + 1) / (L + 1) (b − a)``, a the mean of the run's feet in
        stance at the sample before it (all of them if none) and b the same after it, taken at
        that sample (the feet rest in the world while they stand).
    """
    stance, feet = motion.stance, motion.feet
    counts = stance.sum(axis=1)
    n = len(counts)
    points = np.zeros((n, 3))
    one = counts == 1
    points[one] = feet[one, np.argmax(stance[one], axis=1)]
    two = counts == 2
    same = two & np.roll(two, 1) & np.all(stance == np.roll(stance, 1, axis=0), axis=1)
    starts = np.flatnonzero(two & ~same)
    if two.any() and len(starts) == 0:  # every sample on the same two feet
        starts = np.array([0])
    for start in starts:
        length = 1
        while length < n and same[(start + length) % n]:
            length += 1
        idx = (start + np.arange(length)) % n
        legs = stance[start]
        before = legs & stance[(start - 1) % n]
        after = legs & stance[(start + length) % n]
        before = before if before.any() else legs
        after = after if after.any() else legs
        lam = (np.arange(length) + 1.0) / (length + 1.0)
        a = feet[idx][:, before].mean(axis=1)
        b = feet[idx][:, after].mean(axis=1)
        points[idx] = a + lam[:, None] * (b - a)
    return one | two, points


def reference_moments(robot: Robot, motion: Motion, mask: np.ndarray, points: np.ndarray
                      ) -> np.ndarray:
    """The moment the contacts would have to push about each sample's ZMP reference.

    RNEA's base rows ``(M a + h)[:6]`` are the wrench (force f_b, moment m_b about the base
    origin, base frame) the feet must push on the robot (whole-body Newton–Euler); about the
    reference p (base frame) its moment is ``m_b − p × f_b``.

    Args:
        robot: The robot.
        motion: The motion (floating base).
        mask: The samples to evaluate, shape (T,).
        points: Their references in the world frame, shape (T, 3), m.

    Returns:
        Moments in the base frame, shape (T, 3), N·m (0 outside ``mask``).
    """
    model, data = robot.model, robot.model.createData()
    out = np.zeros((motion.n_samples, 3))
    for k in np.flatnonzero(mask):
        q = motion.q[k]
        wrench = pin.rnea(model, data, q, motion.v[k], motion.a[k])[:6]
        rot = pin.Quaternion(q[3:7]).toRotationMatrix()
        p = rot.T @ (points[k] - q[:3])
        out[k] = wrench[3:] - np.cross(p, wrench[:3])
    return out


def periodic_turn(r: np.ndarray, period: float) -> np.ndarray:
    """The periodic ψ (zero mean) whose second derivative on the cycle grid is ``r``.

    Per Fourier harmonic n ≥ 1 (ω = 2π / period): ``Ψ_n = −R_n / (nω)²``; ``Ψ_0 = 0``. ``r``
    must have zero mean (a periodic ψ̇ has ∫ψ̈ = 0).

    Args:
        r: ψ̈ on the grid ``t_k = k · period / N``, shape (N,), rad/s².
        period: Period, s.

    Returns:
        ψ samples, shape (N,), rad.
    """
    omega = 2.0 * math.pi / period * np.arange(len(r) // 2 + 1)
    spectrum = np.fft.rfft(r)
    spectrum[0] = 0.0
    spectrum[1:] = -spectrum[1:] / omega[1:] ** 2
    return np.fft.irfft(spectrum, n=len(r))


def balance_steps(robot: Robot, gait: GaitParams, grid: np.ndarray,
                  sample: Callable[[tuple[Sway, ...] | None, dict[str, Any]], Motion]
                  ) -> tuple[Motion, tuple[Sway, ...], dict[str, Any]]:
    """The body sway and turn that balance a gait with one-foot samples (module docstring).

    Args:
        robot: The robot.
        gait: The gait's parameters (its period).
        grid: The cycle grid ``k · period / samples``, shape (N,), s.
        sample: The gait on ``grid`` with sways (None: the constant-twist body) and the
            ``info["balance"]`` report to store (:func:`hexaleg.motion.legged.sample_gait`).

    Returns:
        The balanced motion, its sways (x, y and the turn) and the report (``mode`` "zmp",
        ``height`` m, ``iterations``, ``amplitude`` m (the larger sway's half peak-to-peak),
        ``sway`` m (both), ``turn`` rad, ``residual`` and ``residuals`` (m g h)).

    Raises:
        InfeasibleForcesError: the iteration does not converge in ``BALANCE_MAX_ITER`` steps.
    """
    motion = sample(None, {"mode": "none"})
    mask, points = zmp_reference(motion)
    one = motion.stance.sum(axis=1) == 1
    model, data = robot.model, robot.model.createData()
    height = float(np.mean([pin.centerOfMass(model, data, q)[2] for q in motion.q]))
    q_ref = motion.q[0].copy()
    q_ref[:7] = pin.neutral(model)[:7]
    inertia = float(pin.crba(model, data, q_ref)[5, 5])
    mass, g = robot.mass, float(np.linalg.norm(model.gravity.linear))
    scale = mass * g * height
    n = len(grid)
    x = np.zeros(3 * n)
    history: list[tuple[np.ndarray, np.ndarray]] = []

    def residual(moment: np.ndarray) -> float:
        return float(max(np.abs(moment[mask, :2]).max(), np.abs(moment[one, 2]).max())
                     / scale)

    moment = reference_moments(robot, motion, mask, points)
    residuals = [residual(moment)]
    for _ in range(BALANCE_MAX_ITER):
        fx, fy, r = np.zeros(n), np.zeros(n), np.zeros(n)
        fx[mask], fy[mask] = moment[mask, 1] / mass, -moment[mask, 0] / mass
        r[mask] = -moment[mask, 2] / inertia
        r[~one] -= r.sum() / max(int((~one).sum()), 1)
        step = np.concatenate([periodic_lip_sway(fx, gait.period, height, g),
                               periodic_lip_sway(fy, gait.period, height, g),
                               height * periodic_turn(r, gait.period)])
        history.append((x + step, step))
        x = anderson(history[-ANDERSON_DEPTH - 1:])
        sways = (Sway.from_samples(AXES[0], gait.period, x[:n]),
                 Sway.from_samples(AXES[1], gait.period, x[n:2 * n]),
                 Turn.from_samples(AXES[2], gait.period, x[2 * n:] / height))
        report = {"mode": "zmp", "height": height, "iterations": len(residuals),
                  "amplitude": max(sways[0].amplitude, sways[1].amplitude),
                  "sway": [sways[0].amplitude, sways[1].amplitude],
                  "turn": sways[2].amplitude}
        motion = sample(sways, report)
        moment = reference_moments(robot, motion, mask, points)
        residuals.append(residual(moment))
        report["residual"] = residuals[-1]
        report["residuals"] = residuals
        if residuals[-1] <= BALANCE_TOL:
            return motion, sways, report
    vertical = float(np.abs(moment[one, 2]).max())
    mean = float(np.mean(moment[:, 2]))
    level = float(np.abs(moment[mask, :2]).max()) <= BALANCE_TOL * scale
    if one.all() and level and vertical <= 2 * abs(mean):
        raise InfeasibleForcesError(
            f"the walking pattern cannot balance this gait: every sample stands on one point "
            f"foot (duty_factor {gait.duty_factor:g} with {len(gait.groups)} groups), which "
            "pushes no moment about the vertical, and the moment the motion needs there has a "
            f"mean of {mean:.3g} N·m over the cycle (a left-right asymmetry of the robot or "
            "its gait) that no periodic turn of the body cancels; raise duty_factor above "
            f"{gait.duty_factor:g} (e.g. 0.6) so that two-foot phases, whose feet push it by "
            "friction, carry it")
    raise InfeasibleForcesError(
        f"the walking pattern that balances the one-foot phases did not converge in "
        f"{BALANCE_MAX_ITER} iterations: moment about the zero-moment point "
        f"{residuals[-1]:.3g} m g h (allowed {BALANCE_TOL:g}); raise duty_factor so that more "
        "feet share the support, or slow the gait (period) or shorten its stride")
