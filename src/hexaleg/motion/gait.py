"""Whole-robot motions: the periodic leg-group gait (tripod), joint sinusoids, hexapod → sphere.

* :func:`tripod_gait` — the body moves with a constant twist (forward speed, optional yaw rate);
  legs move in groups (default the two tripods {LF, RM, LH} and {RF, LM, RH}); stance feet stay
  fixed on the ground, swing feet follow :func:`swing_curve`; joint angles, velocities and
  accelerations come from the leg inverse kinematics (:mod:`hexaleg.motion.kinematics`) with exact
  derivatives. The foot-placement and timing logic is generic in the legs and groups (a trot on a
  quadruped is two groups of two legs); a gait standing on two feet is balanced by a periodic
  body sway (:mod:`hexaleg.motion.balance`, ``GaitParams.balance``).
* :func:`joint_motion` — chosen joints follow the paper's sinusoid (eq. 16) on a fixed base; the
  paper's single-joint experiment embedded in the robot.
* :func:`transform_motion` — from ``stand`` to ``sphere``: the body sits down on its feet, then
  rests on the ground while the legs fold.

All outputs are :class:`~hexaleg.motion.trajectory.Motion` objects in Pinocchio's conventions: base
velocity and acceleration in the LOCAL base frame, ``a = dv/dt``.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg.config import from_mapping, load_toml
from hexaleg.errors import InfeasibleForcesError, InvalidParameterError, UnknownNameError
from hexaleg.motion.balance import Sway, crossing, periodic_lip_sway, support_moment, sway_direction
from hexaleg.motion.kinematics import leg_ik
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.units import rad_to_deg

MIN_SAMPLES = 20
"""Fewest samples per period (or per motion) a motion may have."""

TRIPODS: tuple[tuple[str, ...], ...] = (("LF", "RM", "LH"), ("RF", "LM", "RH"))
"""The hexapod's two tripods, the default leg groups; group 0 touches down at t = 0."""

BALANCE_MODES: tuple[str, ...] = ("auto", "none")
"""``GaitParams.balance``: ``"auto"`` sways the body (:mod:`hexaleg.motion.balance`) when some
sample stands on exactly two feet and none on fewer; ``"none"`` keeps the constant-twist body."""
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


# --------------------------------------------------------------------------- swing curves


def smoothstep(s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The degree-7 smoothstep σ(s) = 35s⁴ − 84s⁵ + 70s⁶ − 20s⁷ and its first two derivatives.

    σ rises from 0 to 1 on [0, 1] with zero first, second and third derivatives at both ends
    (the lowest-degree polynomial with that property). Source: the "smootherstep" family of
    Hermite polynomials, e.g. Ebert et al., *Texturing & Modeling*, 3rd ed., 2003, ch. 2.

    Args:
        s: Normalised time, any shape, in [0, 1].

    Returns:
        σ, dσ/ds, d²σ/ds², each the shape of ``s``.
    """
    s = np.asarray(s, dtype=float)
    s3 = s**3
    value = s3 * s * (35.0 + s * (-84.0 + s * (70.0 - 20.0 * s)))
    d1 = 140.0 * s3 * (1.0 - s) ** 3
    d2 = 420.0 * s * s * (1.0 - s) ** 2 * (1.0 - 2.0 * s)
    return value, d1, d2


def swing_bump(s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The lift profile b(s) = 256 s⁴ (1 − s)⁴ and its first two derivatives.

    b is 0 at s = 0 and 1, peaks at b(½) = 1, and has zero first, second and third derivatives
    at both ends. Source: chosen here (symmetric polynomial with the end conditions above).

    Args:
        s: Normalised time, any shape, in [0, 1].

    Returns:
        b, db/ds, d²b/ds², each the shape of ``s``.
    """
    s = np.asarray(s, dtype=float)
    u = s * (1.0 - s)
    du = 1.0 - 2.0 * s
    value = 256.0 * u**4
    d1 = 1024.0 * u**3 * du
    d2 = 3072.0 * u**2 * du**2 - 2048.0 * u**3
    return value, d1, d2


def swing_curve(s: np.ndarray, lift_off: np.ndarray, touch_down: np.ndarray, height: float
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A swing foot's path: straight ground track by :func:`smoothstep`, lift by :func:`swing_bump`.

    ``p(s) = p₀ + (p₁ − p₀) σ(s) + h b(s) ẑ``: the foot leaves ``lift_off`` and lands on
    ``touch_down`` with zero velocity, acceleration and jerk, so contact switches are impact-free
    and the joint accelerations (and inverse-dynamics torques) stay continuous across them.

    Args:
        s: Normalised swing time, shape (N,), in [0, 1].
        lift_off: Lift-off points, shape (N, 3) or (3,), m.
        touch_down: Touch-down points, shape (N, 3) or (3,), m.
        height: Apex height above the straight line between them, m.

    Returns:
        p (N, 3) m, dp/ds (N, 3) m, d²p/ds² (N, 3) m.
    """
    sigma, d_sigma, dd_sigma = smoothstep(s)
    bump, d_bump, dd_bump = swing_bump(s)
    delta = np.asarray(touch_down, dtype=float) - np.asarray(lift_off, dtype=float)
    up = np.array([0.0, 0.0, height])
    p = lift_off + sigma[:, None] * delta + bump[:, None] * up
    return p, d_sigma[:, None] * delta + d_bump[:, None] * up, \
        dd_sigma[:, None] * delta + dd_bump[:, None] * up


# --------------------------------------------------------------------------- parameters


def _finite(name: str, value: float, allowed: str, ok: bool) -> None:
    if not (isinstance(value, (int, float)) and not isinstance(value, bool)
            and math.isfinite(value) and ok):
        raise InvalidParameterError(name, value, allowed)


@dataclass(frozen=True)
class GaitParams:
    """Parameters of a periodic leg-group gait (SI).

    Attributes:
        period: Cycle duration, s (> 0).
        duty_factor: β, the fraction of the cycle each foot is in stance, in [0.5, 1).
        stride_length: Body travel per cycle, m (≥ 0); also each foot's travel per swing. The
            stance stroke of a foot relative to the body is β · stride.
        speed: Forward speed, m/s. When given (not None) it **wins** over ``stride_length``:
            the stride becomes ``speed · period``. Default None: speed = stride / period.
        step_height: Apex height of the swing foot above the ground, m (> 0).
        body_height: Height of the base above the ground, m (> 0); None: the depth of the feet
            below the base in the robot's ``stand`` pose (0.0913 m for hexaleg).
        foot_radius: Horizontal distance of each nominal foothold from the base's z axis (stance
            width), m (> 0); None: the footholds of the ``stand`` pose (0.1889 m for hexaleg).
        yaw_rate: Turning rate about the vertical, rad/s; the body then follows a circular arc.
        samples: Samples per cycle (≥ ``MIN_SAMPLES``).
        groups: Legs that move together; group i touches down at t = i · period / len(groups)
            and every leg of the robot must be in exactly one group.
        balance: ``"auto"`` (default): when the gait stands on exactly two feet at some sample
            (a trot, a pace) and never on fewer, the body sways horizontally so that the two
            feet can carry the motion (see :func:`sample_gait`); gaits with three or more feet
            always (the hexapod's tripod) are unchanged. ``"none"``: never sway (the rigid
            constant-twist body, whose two-foot samples have no contact forces).
    """

    period: float = 1.0
    duty_factor: float = 0.5
    stride_length: float = 0.06
    speed: float | None = None
    step_height: float = 0.03
    body_height: float | None = None
    foot_radius: float | None = None
    yaw_rate: float = 0.0
    samples: int = 1000
    groups: tuple[tuple[str, ...], ...] = TRIPODS
    balance: str = "auto"

    def __post_init__(self) -> None:
        _finite("period", self.period, "a finite number > 0 (s)", self.period > 0)
        _finite("duty_factor", self.duty_factor, "β in [0.5, 1)",
                0.5 <= self.duty_factor < 1.0)
        _finite("stride_length", self.stride_length, "a finite number ≥ 0 (m)",
                self.stride_length >= 0)
        if self.speed is not None:
            _finite("speed", self.speed, "None or a finite number ≥ 0 (m/s)", self.speed >= 0)
        _finite("step_height", self.step_height, "a finite number > 0 (m)",
                self.step_height > 0)
        for name in ("body_height", "foot_radius"):
            value = getattr(self, name)
            if value is not None:
                _finite(name, value, "None or a finite number > 0 (m)", value > 0)
        _finite("yaw_rate", self.yaw_rate, "a finite number (rad/s)", True)
        if isinstance(self.samples, bool) or not isinstance(self.samples, (int, np.integer)) \
                or self.samples < MIN_SAMPLES:
            raise InvalidParameterError("samples", self.samples,
                                        f"an integer ≥ {MIN_SAMPLES} samples per period")
        object.__setattr__(self, "samples", int(self.samples))
        groups = tuple(tuple(g) for g in self.groups)
        legs = [leg for g in groups for leg in g]
        if not groups or any(not g for g in groups) or len(set(legs)) != len(legs) \
                or not all(isinstance(leg, str) for leg in legs):
            raise InvalidParameterError("groups", self.groups,
                                        "non-empty groups of leg names, each leg in one group")
        object.__setattr__(self, "groups", groups)
        if self.balance not in BALANCE_MODES:
            raise InvalidParameterError("balance", self.balance, " or ".join(BALANCE_MODES))

    @property
    def stride(self) -> float:
        """Body travel per cycle, m (``speed · period`` when ``speed`` is given)."""
        return self.speed * self.period if self.speed is not None else self.stride_length

    @property
    def velocity(self) -> float:
        """Forward speed, m/s (``stride / period`` unless ``speed`` is given)."""
        return self.stride / self.period

    @classmethod
    def from_toml(cls, source: str | Path | Mapping[str, Any]) -> GaitParams:
        """Gait parameters from a TOML file or an already parsed table.

        Args:
            source: A TOML file (its ``[gait]`` table, or the top level when it has none) or a
                mapping of field names to values.

        Returns:
            The parameters; missing keys take their defaults.

        Raises:
            ConfigError: the file cannot be read, or a value has the wrong type.
            UnknownNameError: a key is not a field (the message lists the fields).
            InvalidParameterError: a value is out of range.
        """
        if isinstance(source, Mapping):
            return from_mapping(cls, source, "gait")
        data = load_toml(source)
        table = data.get("gait", data)
        return from_mapping(cls, table, f"{source} [gait]" if "gait" in data else str(source))

    def updated(self, table: Mapping[str, Any], where: str = "gait") -> GaitParams:
        """This gait with the keys of a TOML table on top (e.g. a file's ``[gait]`` over a
        robot's own gait); keys the table does not set keep this gait's values.

        Raises:
            UnknownNameError, ConfigError, InvalidParameterError: as :meth:`from_toml`.
        """
        given = from_mapping(type(self), table, where)
        return dataclasses.replace(self, **{k: getattr(given, k) for k in table})


@dataclass(frozen=True)
class Sinusoid:
    """The paper's joint trajectory f(t) = A sin(ωt + φ) + B (eq. 16), an absolute joint angle.

    Attributes:
        amplitude: A, rad.
        omega: ω, rad/s.
        phase: φ, rad.
        offset: B, rad.
    """

    amplitude: float
    omega: float
    phase: float = 0.0
    offset: float = 0.0

    def __post_init__(self) -> None:
        for name in ("amplitude", "omega", "phase", "offset"):
            _finite(f"Sinusoid.{name}", getattr(self, name), "a finite number", True)

    def __call__(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Angle, angular velocity and acceleration at times ``t`` (eq. 16 and its derivatives).

        Args:
            t: Times, any shape, s.

        Returns:
            f (rad), ḟ = Aω cos(ωt + φ) (rad/s), f̈ = −Aω² sin(ωt + φ) (rad/s²), shape of ``t``.
        """
        arg = self.omega * np.asarray(t, dtype=float) + self.phase
        s, c = np.sin(arg), np.cos(arg)
        a = self.amplitude
        return a * s + self.offset, a * self.omega * c, -a * self.omega**2 * s


# --------------------------------------------------------------------------- the gait


def _resolve_groups(robot: Robot, gait: GaitParams) -> np.ndarray:
    """Touch-down phase offset (fraction of the period) of each robot leg, shape (n_legs,)."""
    names = robot.leg_names
    offset = {}
    for i, group in enumerate(gait.groups):
        for leg in group:
            if leg not in names:
                raise UnknownNameError("leg", leg, names)
            offset[leg] = i / len(gait.groups)
    missing = [leg for leg in names if leg not in offset]
    if missing:
        raise InvalidParameterError("groups", gait.groups,
                                    f"every leg of the robot in a group; missing {missing}")
    return np.array([offset[leg] for leg in names])


def _reference(robot: Robot) -> np.ndarray:
    """The ``stand`` pose (or the neutral configuration), base at the origin, shape (nq,)."""
    q = robot.pose("stand") if "stand" in robot.poses else pin.neutral(robot.model)
    q[:7] = pin.neutral(robot.model)[:7]
    return q


def nominal_footholds(robot: Robot, gait: GaitParams) -> np.ndarray:
    """Mid-stance foot positions in the base frame, shape (n_legs, 3), m.

    Horizontally the footholds of the robot's ``stand`` pose (scaled to ``foot_radius`` from the
    base z axis when given); vertically ``−body_height`` (default the stand pose's mean foot
    depth), so the feet are on the ground z = 0 when the base is at ``body_height``.

    Args:
        robot: The robot.
        gait: Gait parameters.

    Returns:
        Footholds in the base frame, legs in ``robot.legs`` order.
    """
    feet = robot.foot_positions(_reference(robot))
    height = -float(feet[:, 2].mean()) if gait.body_height is None else gait.body_height
    if gait.foot_radius is not None:
        radial = np.linalg.norm(feet[:, :2], axis=1, keepdims=True)
        feet[:, :2] *= gait.foot_radius / radial
    feet[:, 2] = -height
    return feet


def _body_pose(t: np.ndarray, speed: float, yaw_rate: float, height: float
               ) -> tuple[np.ndarray, np.ndarray]:
    """Base position (N, 3) m and yaw (N,) rad of the constant-twist body motion at times t."""
    yaw = yaw_rate * t
    if yaw_rate == 0.0:
        x, y = speed * t, np.zeros_like(t)
    else:
        x, y = speed / yaw_rate * np.sin(yaw), speed / yaw_rate * (1.0 - np.cos(yaw))
    return np.stack([x, y, np.full_like(t, height)], axis=-1), yaw


def _rotz(yaw: np.ndarray) -> np.ndarray:
    c, s = np.cos(yaw), np.sin(yaw)
    rot = np.zeros((*np.shape(yaw), 3, 3))
    rot[..., 0, 0], rot[..., 0, 1], rot[..., 1, 0], rot[..., 1, 1] = c, -s, s, c
    rot[..., 2, 2] = 1.0
    return rot


def _support_margin(points: np.ndarray, c: np.ndarray) -> float:
    """Signed distance of ``c`` (2,) inside the convex hull of ``points`` (n, 2), m.

    Positive inside (distance to the nearest edge), negative outside; −inf for fewer than three
    points or a degenerate hull. Hull by Andrew's monotone chain.
    """
    pts = sorted(map(tuple, points))
    if len(pts) < 3:
        return -math.inf

    def cross(o: tuple, a: tuple, b: tuple) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    hull: list[tuple] = []
    for seq in (pts, pts[::-1]):
        start = len(hull)
        for pt in seq:
            while len(hull) >= start + 2 and cross(hull[-2], hull[-1], pt) <= 0:
                hull.pop()
            hull.append(pt)
        hull.pop()
    if len(hull) < 3:
        return -math.inf
    dists = []
    for a, b in zip(hull, hull[1:] + hull[:1], strict=True):
        edge = math.hypot(b[0] - a[0], b[1] - a[1])
        dists.append(cross(a, b, tuple(c)) / edge)
    return min(dists)


def _stance_counts(gait: GaitParams, offsets: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Number of stance feet at times t, shape (T,) (the stance rule of :func:`sample_gait`)."""
    tau = t[:, None] / gait.period - offsets[None, :]
    return ((tau - np.floor(tau)) < gait.duty_factor).sum(axis=1)


def sample_gait(robot: Robot, gait: GaitParams | None = None,
                t: np.ndarray | None = None) -> Motion:
    """Evaluate the periodic leg-group gait at given times (the machinery of :func:`tripod_gait`).

    The base moves with the constant twist (local linear velocity ``[speed, 0, 0]``, angular
    velocity ``[0, 0, yaw_rate]``) at ``body_height``, starting at the origin with zero yaw, plus
    the balancing sway below. A leg of group i is in stance for the phase
    φ = (t/period − i/n_groups) mod 1 < β (so at a switching instant the group touching down is
    in stance and the one lifting off is not), its foot fixed at the world image of its nominal
    foothold at mid-stance; in swing it moves on :func:`swing_curve` from that point to the next
    mid-stance image (one stride ahead). The foot targets are taken into the base frame with the
    exact rotating-frame derivatives ``ṗ_b = −ω × p_b + Rᵀ ṗ − v`` and
    ``p̈_b = −ω × ṗ_b − ω × Rᵀ ṗ + Rᵀ p̈ − v̇`` and solved by
    :func:`hexaleg.motion.kinematics.leg_ik`.

    **Balance on two feet** (``gait.balance == "auto"`` and some sample of the cycle grid stands
    on exactly two feet, none on fewer — a trot: with β = 0.5 always exactly two, switching at
    t = 0 and t = period / 2; with β > 0.5 four-foot phases of (β − ½) · period after each
    switch). Two point feet cannot push a moment about the line through them, so the base is
    displaced by ``d(t) e`` along a horizontal direction e (:func:`hexaleg.motion.balance.
    sway_direction`: lateral for a trot), with d a trigonometric polynomial on the cycle grid
    (exact derivatives: the base velocity gains ``e ḋ + ω ẑ × e d`` and the acceleration
    ``e d̈ + ω ẑ × e ḋ``). d is the fixed point of: compute the exact moment M_k about each
    two-foot sample's support line from RNEA (:func:`hexaleg.motion.balance.support_moment`), add
    the periodic linear-inverted-pendulum sway that cancels it, ``g δd − h δd̈ = −M / (m s)`` on the
    two-foot samples and 0 on the others (:func:`hexaleg.motion.balance.periodic_lip_sway`, Kajita
    et al. ICRA 2003; h the mean CoM height, s the crossing factor), and re-sample the gait; it
    stops when ``max |M_k| ≤ BALANCE_TOL · m g h``. The stance feet stay at rest (the footholds
    do not move with the sway) and the swing feet follow the same world curves. At times ``t``
    off the cycle grid the sway is the same trigonometric polynomial (balanced on the grid).

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
            1-D array of finite times, or a support line is (nearly) parallel to every sway
            direction.
        UnreachableTargetError: a foot target is out of reach (names leg, time, distance).
        InfeasibleForcesError: the sway iteration does not converge (the gait is too fast or
            its support lines too short to balance).
    """
    gait = GaitParams() if gait is None else gait
    cycle_grid = t is None
    grid = np.arange(gait.samples) * (gait.period / gait.samples)
    t = grid if t is None else np.asarray(t, dtype=float)
    if t.ndim != 1 or len(t) == 0 or not np.all(np.isfinite(t)):
        raise InvalidParameterError("t", f"array of shape {t.shape}",
                                    "a non-empty 1-D array of finite times (s)")
    offsets = _resolve_groups(robot, gait)
    counts = _stance_counts(gait, offsets, grid)
    if gait.balance == "none" or counts.min() != 2:
        return _sample(robot, gait, t, cycle_grid, None, {"mode": "none"})
    motion, sway, report = _balance(robot, gait, grid)
    if cycle_grid:
        return motion
    return _sample(robot, gait, t, False, sway, report)


def _balance(robot: Robot, gait: GaitParams, grid: np.ndarray
             ) -> tuple[Motion, Sway, dict[str, Any]]:
    """The sway fixed point of :func:`sample_gait` on the cycle grid: (motion, sway, report)."""
    motion = _sample(robot, gait, grid, True, None, {"mode": "none"})
    moment, mask, axes = support_moment(robot, motion)
    direction = sway_direction(np.unique(np.round(axes[mask], 12), axis=0))
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
        d = _anderson(history[-ANDERSON_DEPTH - 1:])
        sway = Sway.from_samples(direction, gait.period, d)
        report = {"mode": "sway", "direction": direction.tolist(), "height": height,
                  "iterations": len(residuals), "amplitude": sway.amplitude}
        motion = _sample(robot, gait, grid, True, sway, report)
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


def _anderson(history: list[tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
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


def _sample(robot: Robot, gait: GaitParams, t: np.ndarray, periodic: bool,
            sway: Sway | None, balance: dict[str, Any]) -> Motion:
    """The gait at times ``t`` with an optional body sway (see :func:`sample_gait`)."""
    offsets = _resolve_groups(robot, gait)
    nominal = nominal_footholds(robot, gait)
    height = -float(nominal[0, 2])
    speed, beta, period, omega = gait.velocity, gait.duty_factor, gait.period, gait.yaw_rate
    n, n_legs = len(t), len(robot.legs)

    base, yaw = _body_pose(t, speed, omega, height)
    rot = _rotz(yaw)
    v_local = np.array([speed, 0.0, 0.0])
    w_local = np.array([0.0, 0.0, omega])
    a_local = np.zeros(3)
    if sway is not None:
        d, dd, ddd = sway(t)
        e, e_perp = sway.direction, np.cross(w_local, sway.direction)
        base = base + np.einsum("nij,j->ni", rot, e) * d[:, None]
        v_local = v_local + e * dd[:, None] + e_perp * d[:, None]
        a_local = e * ddd[:, None] + e_perp * dd[:, None]

    q = np.tile(_reference(robot), (n, 1))
    q[:, :3] = base
    q[:, 5], q[:, 6] = np.sin(yaw / 2), np.cos(yaw / 2)
    v = np.zeros((n, robot.model.nv))
    v[:, :3], v[:, 3:6] = v_local, w_local
    a = np.zeros((n, robot.model.nv))
    a[:, :3] = a_local
    stance = np.zeros((n, n_legs), dtype=bool)
    feet = np.zeros((n, n_legs, 3))
    solvers = {}

    def foothold(t_mid: np.ndarray, leg: int) -> np.ndarray:
        pos, psi = _body_pose(t_mid, speed, omega, height)
        return pos + np.einsum("nij,j->ni", _rotz(psi), nominal[leg])

    for i, leg in enumerate(robot.legs):
        tau = t / period - offsets[i]
        cycle = np.floor(tau)
        phase = tau - cycle
        on = phase < beta
        t_mid = (cycle + offsets[i] + beta / 2) * period
        p_w = foothold(t_mid, i)
        pd_w = np.zeros((n, 3))
        pdd_w = np.zeros((n, 3))
        sw = ~on
        if sw.any():
            s = (phase[sw] - beta) / (1.0 - beta)
            t_swing = (1.0 - beta) * period
            p_s, dp_s, ddp_s = swing_curve(s, p_w[sw], foothold(t_mid[sw] + period, i),
                                           gait.step_height)
            p_w[sw], pd_w[sw], pdd_w[sw] = p_s, dp_s / t_swing, ddp_s / t_swing**2
        stance[:, i], feet[:, i] = on, p_w

        rel = np.einsum("nji,nj->ni", rot, p_w - base)
        rt_pd = np.einsum("nji,nj->ni", rot, pd_w)
        rel_d = -np.cross(w_local, rel) + rt_pd - v_local
        rel_dd = -np.cross(w_local, rel_d) - np.cross(w_local, rt_pd) \
            + np.einsum("nji,nj->ni", rot, pdd_w) - a_local
        q_leg, qd_leg, qdd_leg, solvers[leg.name] = leg_ik(robot, leg, rel, rel_d, rel_dd, t=t)
        q[:, leg.q_index], v[:, leg.v_index], a[:, leg.v_index] = q_leg, qd_leg, qdd_leg

    margins = np.full(n, -math.inf)
    data = robot.model.createData()
    for k in range(n):
        com = pin.centerOfMass(robot.model, data, q[k])
        margins[k] = _support_margin(feet[k, stance[k], :2], com[:2])
    worst = int(np.argmin(margins))
    info = {
        "source": "tripod_gait",
        "gait": {f.name: getattr(gait, f.name) for f in dataclasses.fields(gait)},
        "stride_length": gait.stride, "speed": speed, "body_height": height,
        "foot_radius": float(np.linalg.norm(nominal[:, :2], axis=1).mean()),
        "min_stance_feet": int(stance.sum(axis=1).min()),
        "static_margin": float(margins[worst]) if math.isfinite(margins[worst]) else None,
        "static_margin_t": float(t[worst]),
        "ik": solvers,
        "balance": balance,
    }
    return Motion(t=t, q=q, v=v, a=a, stance=stance, feet=feet, period=period,
                  distance=gait.stride, periodic=periodic, fixed_base=False, info=info)


def tripod_gait(robot: Robot, gait: GaitParams | None = None) -> Motion:
    """One cycle of the periodic leg-group gait (default: the hexapod's alternating tripod).

    Args:
        robot: The robot (e.g. ``load_robot()``).
        gait: Gait parameters; default ``GaitParams()`` (period 1 s, β = 0.5, stride 0.06 m,
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
        unswayed gait)``}``.

    Raises:
        UnknownNameError: a leg in ``gait.groups`` is not a leg of the robot.
        InvalidParameterError: a leg of the robot is in no group, or a support line cannot be
            crossed by a horizontal sway.
        UnreachableTargetError: a foot target is out of reach (names leg, time, distance).
        InfeasibleForcesError: the balancing sway does not converge.
    """
    return sample_gait(robot, gait)


def gait_summary(robot: Robot, motion: Motion) -> str:
    """A human-readable summary of a gait motion: parameters, margin, joint ranges and peaks.

    Args:
        robot: The robot the motion was made for.
        motion: A motion from :func:`tripod_gait` or :func:`sample_gait`.

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
        f"groups: {' | '.join(' '.join(group) for group in g['groups'])}",
        f"stance feet per sample: min {info['min_stance_feet']}; static margin "
        + (f"{margin:.4f} m (at t = {info['static_margin_t']:g} s)" if margin is not None
           else "n/a (fewer than 3 stance feet at some sample)"),
        *([f"balance: body sway ±{1e3 * sway['amplitude']:.2f} mm along "
           f"{np.round(sway['direction'], 3).tolist()} (base frame), support-line moment "
           f"{sway['residual']:.1e} m g h after {sway['iterations']} iterations"]
          if (sway := info.get("balance", {})).get("mode") == "sway" else []),
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


# --------------------------------------------------------------------------- joint-space motions


def _base_pose(robot: Robot, base: str | np.ndarray) -> np.ndarray:
    if isinstance(base, str):
        return robot.pose(base)
    q = np.asarray(base, dtype=float)
    if q.shape != (robot.model.nq,) or not np.all(np.isfinite(q)):
        raise InvalidParameterError("base", f"array of shape {q.shape}",
                                    f"a pose name ({', '.join(robot.poses)}) or a finite "
                                    f"configuration of shape ({robot.model.nq},)")
    return q.copy()


def _check_samples(samples: object) -> int:
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) \
            or samples < MIN_SAMPLES:
        raise InvalidParameterError("samples", samples, f"an integer ≥ {MIN_SAMPLES}")
    return int(samples)


def _check_joint_limits(robot: Robot, q: np.ndarray, t: np.ndarray) -> None:
    lo, hi = robot.model.lowerPositionLimit[7:], robot.model.upperPositionLimit[7:]
    bad = (q[:, 7:] < lo) | (q[:, 7:] > hi)
    if bad.any():
        k, j = (int(i) for i in np.argwhere(bad)[0])
        raise InvalidParameterError(
            f"trajectory of joint {robot.joint_names[j]}", f"{q[k, 7 + j]:.4f} rad at t = "
            f"{t[k]:.6g} s", f"angles within the joint limits [{lo[j]:.4f}, {hi[j]:.4f}] rad")


def _feet(robot: Robot, q: np.ndarray) -> np.ndarray:
    return np.stack([robot.foot_positions(qk) for qk in q])


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
    samples = _check_samples(samples)
    omegas = sorted({abs(s.omega) for s in trajectories.values()})
    if period is None:
        if len(omegas) != 1 or omegas[0] == 0.0:
            raise InvalidParameterError("period", None, "a duration > 0 (s) when the sinusoids "
                                        f"do not share one |ω| > 0 (|ω| = {omegas})")
        period = 2.0 * math.pi / omegas[0]
    _finite("period", period, "a finite number > 0 (s)", period > 0)
    t = np.arange(samples) * (period / samples)
    q = np.tile(_base_pose(robot, base), (samples, 1))
    v = np.zeros((samples, robot.model.nv))
    a = np.zeros((samples, robot.model.nv))
    for name, traj in trajectories.items():
        joint = robot.model.joints[robot.model.getJointId(name)]
        q[:, joint.idx_q], v[:, joint.idx_v], a[:, joint.idx_v] = traj(t)
    _check_joint_limits(robot, q, t)
    cycles = [w * period / (2.0 * math.pi) for w in omegas]
    periodic = all(abs(c - round(c)) < 1e-9 for c in cycles)
    info = {"source": "joint_motion", "base": base if isinstance(base, str) else "custom",
            "trajectories": {k: dataclasses.asdict(s) for k, s in trajectories.items()}}
    return Motion(t=t, q=q, v=v, a=a, stance=np.zeros((samples, len(robot.legs)), dtype=bool),
                  feet=_feet(robot, q), period=period, distance=0.0, periodic=periodic,
                  fixed_base=True, info=info)


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

    σ is the :func:`smoothstep`, so velocities and accelerations are zero at t = 0, on both sides
    of t_s and at the end: q, v and a are continuous across the phase switch; only the load moves
    from the feet to the body at t_s, at rest. The resting height h_r is by default where the
    ``end`` pose rests on its lowest point (for the built-in robot the lower body dome, 0.0835 m
    below the base, so the body sits 7.8 mm lower than it stands), and no geometry may pass below
    the ground while the legs fold (checked, exactly for the primitive shapes, at every sample;
    ``info["clearance"]`` reports the smallest height of any geometry over the fold).

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
    _finite("duration", duration, "a finite number > 0 (s)", duration > 0)
    samples = _check_samples(samples)
    _finite("sit_fraction", sit_fraction, "a number in (0, 1)", 0.0 < sit_fraction < 1.0)
    q0, q1 = robot.pose(start), robot.pose(end)
    q0[:7] = q1[:7] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0)
    stand_feet = robot.foot_positions(q0)  # base at the origin
    h0 = -float(stand_feet[:, 2].min())
    q0[2] = h0
    stand_feet[:, 2] += h0  # world: the lowest feet on the ground z = 0
    if rest_height is None:
        rest_height = -float(_ground_clearance(robot, q1[None], robot.foot_positions(q1)[None])
                             [0][0])
    _finite("rest_height", rest_height, f"a finite number in (0, {h0:.4f}] m (the {start} "
            "height: the body sits down on its feet, it cannot rise)",
            0.0 < rest_height <= h0 + 1e-12)
    t = np.linspace(0.0, duration, samples)
    t_sit = sit_fraction * duration
    sit = t < t_sit
    n_sit = int(sit.sum())
    if n_sit < 2 or samples - n_sit < 2:
        raise InvalidParameterError("samples", samples, f"enough for two samples in each phase "
                                    f"(sit {n_sit}, fold {samples - n_sit}); raise samples or "
                                    "bring sit_fraction away from 0 and 1")
    on_ground = stand_feet[:, 2] < 1e-9
    nv = robot.model.nv

    # Sit: base (0, 0, h(t)) with identity orientation, so LOCAL = world and the foot's base-frame
    # position, velocity and acceleration are p − base, −v_base, −a_base.
    sigma, d_sigma, dd_sigma = smoothstep(np.append(t[sit] / t_sit, 1.0))
    height = h0 + (rest_height - h0) * sigma
    q = np.tile(q0, (samples, 1))
    v, a = np.zeros((samples, nv)), np.zeros((samples, nv))
    q[:n_sit, 2] = height[:-1]
    v[:n_sit, 2] = (rest_height - h0) * d_sigma[:-1] / t_sit
    a[:n_sit, 2] = (rest_height - h0) * dd_sigma[:-1] / t_sit**2
    seated = q0.copy()
    seated[2] = rest_height
    t_ik = np.append(t[sit], t_sit)
    for i, leg in enumerate(robot.legs):
        rel = stand_feet[i] - np.column_stack([np.zeros((n_sit + 1, 2)), height])
        rel_d = -np.column_stack([np.zeros((n_sit + 1, 2)), (rest_height - h0) * d_sigma / t_sit])
        rel_dd = -np.column_stack([np.zeros((n_sit + 1, 2)),
                                   (rest_height - h0) * dd_sigma / t_sit**2])
        q_leg, qd_leg, qdd_leg, _ = leg_ik(robot, leg, rel, rel_d, rel_dd, t=t_ik)
        q[:n_sit, leg.q_index], v[:n_sit, leg.v_index] = q_leg[:-1], qd_leg[:-1]
        a[:n_sit, leg.v_index] = qdd_leg[:-1]
        seated[leg.q_index] = q_leg[-1]

    # Fold: the base rests at rest_height; the joints interpolate from the seated pose to `end`.
    q1[2] = rest_height
    delta = pin.difference(robot.model, seated, q1)  # joints only: the base poses are equal
    t_fold = duration - t_sit
    sigma, d_sigma, dd_sigma = smoothstep((t[~sit] - t_sit) / t_fold)
    q[n_sit:] = [pin.integrate(robot.model, seated, sk * delta) for sk in sigma]
    v[n_sit:] = d_sigma[:, None] * delta / t_fold
    a[n_sit:] = dd_sigma[:, None] * delta / t_fold**2
    _check_joint_limits(robot, q, t)

    feet = _feet(robot, q)
    z, names = _ground_clearance(robot, q[n_sit:], feet[n_sit:])
    k_low = n_sit + int(np.argmin(z))
    clearance, where = float(z[k_low - n_sit]), names[k_low - n_sit]
    if clearance < -1e-9:
        raise InvalidParameterError(
            "rest_height", f"{rest_height:.4f} m ({where} reaches {-clearance * 1e3:.2f} mm "
            f"below the ground at t = {t[k_low]:.4f} s while folding)",
            "a resting height at which no geometry passes below the ground")
    stance = np.zeros((samples, len(robot.legs)), dtype=bool)
    stance[:n_sit] = on_ground
    info = {"source": "transform_motion", "start": start, "end": end, "stand_height": h0,
            "rest_height": rest_height, "sit_time": t_sit, "clearance": clearance,
            "clearance_geometry": where, "clearance_t": float(t[k_low])}
    return Motion(t=t, q=q, v=v, a=a, stance=stance, feet=feet, period=duration,
                  distance=0.0, periodic=False, fixed_base=False, info=info, supported=~sit)
