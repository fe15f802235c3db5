"""Foot placement of the balance controller's swing feet (:mod:`hexaleg.simulation.balance`,
4.): where a point foot of a gait on two feet at times is set down for balance.

Raibert, *Legged Robots That Balance*, MIT Press 1986, ch. 2: the foot set down at the neutral
point ``ẋ T_s / 2`` ahead of the hip, plus a velocity feedback ``k (ẋ − ẋ*)``; Di Carlo et al.,
"Dynamic locomotion in the MIT Cheetah 3 through convex model-predictive control", IROS 2018,
§IV, their foot placement: ``p = p_hip + (T_stance/2) v + k (v − v*)``, whose centripetal term
``½ (h/g) v × ω*`` vanishes here: the controller refuses a turning gait. The plan already sets
each foot down at its own neutral point from its planned hip, so the change of the landing point
from the plan's is, horizontally,

    Δx = (p_hip − p*_hip) + (L + k) (v − v*),     L = min(T_stance/2, coth(ω₀ T_stance)/ω₀),
                                                  p_hip = p + R r_hip

(``r_hip`` the leg's first joint in the base frame, ``T_stance`` the stance that follows the
swing, v the base's velocity, ω₀ = √(g/h) of the centre of mass's height h over the feet):
Raibert's and the MIT controllers' ``T_stance/2``, but never past the linear inverted
pendulum's deadbeat step (:func:`lead`), the lead that leaves a velocity error at zero by the
end of the stance. They meet at ω₀ T_stance = 2.07; beyond it ``T_stance/2`` sends the error
back reversed and larger: Solo-12's co-designed trot (duty 0.7, 0.92 s, T_stance = 0.64 s,
ω₀ T_stance = 4.0; ``analysis/bench_logs/newcomers_simulate.log``, block "placement") set its
feet down 15 mm from the plan's on average while its body ran 47 mm/s off its planned
velocity, spent 14.51 J a cycle against the plan's 8.42 (feedforward + PD) and ran short
with the co-design's springs under both servos; at the deadbeat step (0.160 s, half of
``T_stance/2``) it walks near its plan. Every trot with shorter stances keeps ``T_stance/2``
and its figures. Vertically the foot keeps its planned height in the body (a
position servo's body sags by τ/kp: a foot aimed at the ground's planned height from a sagged
body is set down late and pushed down at touchdown, and Laikago fell so). The swing's joint
reference moves by ``Δq = b(φ) J_b⁺ Rᵀ (x̃ − p̃)``, the step from the planned foot carried by
the measured body ``p̃ = p + R R*ᵀ (x* − p*)`` to the landing target ``x̃ = x* + Δx`` (its
height that of p̃), one Newton step of inverse kinematics (J_b the foot's base-frame Jacobian
at the plan's angles; Siciliano et al., *Robotics*, 2009, §3.7), with ``b(φ) = 3φ² − 2φ³`` of
the swing's elapsed share φ (0 at lift-off, 1 at touchdown, zero slope at both: the reference
does not jump, as the MIT controllers' Bézier swing). At touchdown the stance leg keeps that
correction and releases it over the first :data:`HOLD` of its stance by ``1 − b``: a step of
a position reference at contact is a kick (Go2's trot rolled 0.032 rad with the correction
dropped at touchdown, 0.018 rad with it released; HOLD chosen by measurement, not derived).
The gain ``k``: 0 — the body's PD (:mod:`hexaleg.simulation.balance`, 1.) already
regulates the velocity through the stance forces, and the capture point's ``k = √(h/g)``
(Pratt et al., "Capture point", Humanoids 2006) on top of it over-corrects: B1's baseline rolled
0.53 rad and ran untracked (measured without the hold,
``analysis/bench_logs/newcomers_simulate.log``, the block "Raibert's foot placement").

Which feet are placed is :class:`~hexaleg.simulation.balance.Balance`'s: a point foot of a gait
whose fewest stance feet are :data:`FEWEST_PLACED` (the others keep their footholds,
:mod:`hexaleg.simulation.balance`, "Footholds").
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from hexaleg.motion.stands import longest_stand
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot

HOLD = 0.5
"""The share of a stance over which a swing foot's landing correction is released (module
docstring)."""
FEWEST_PLACED = 2
"""A gait whose fewest stance feet are this many (a trot, a pace, a bound) has its point feet
placed for balance (module docstring); on one point foot they keep their footholds."""


class Placement:
    """Raibert's placement of one plan's swing feet (module docstring): the swings' and
    stances' runs, each landing's lead, and each leg's landing correction, held from its swing
    into its stance.

    Args:
        robot: The robot (its legs' first joints are the hips).
        motion: The plan (``stance``, shape (T, n_legs); ``q[0]``).
        placed: Whether each leg's foot is placed, (n_legs,), bool.
        leg_rows: Each leg's joints among the robot's, (n_legs, nj), bool.
        capture: k, s, ≥ 0: the lead per m/s beyond :func:`lead`'s.
    """

    def __init__(self, robot: Robot, motion: Motion, placed: np.ndarray, leg_rows: np.ndarray,
                 capture: float) -> None:
        model = robot.model
        data = model.createData()
        n, n_legs = motion.n_samples, len(robot.legs)
        self.placed = np.asarray(placed, dtype=bool)
        self.leg_rows = np.asarray(leg_rows, dtype=bool)
        self.hips = np.zeros((n_legs, 3))
        """Each leg's first joint in the base frame (its hip), m, (n_legs, 3)."""
        neutral = motion.q[0].copy()
        neutral[:7] = [0, 0, 0, 0, 0, 0, 1]
        pin.forwardKinematics(model, data, neutral)
        for i, leg in enumerate(robot.legs):
            self.hips[i] = data.oMi[leg.joint_ids[0]].translation
        stance = np.asarray(motion.stance).astype(bool)
        swinging = ~(stance & np.roll(stance, -1, axis=0))  # as the controller splits them
        self.swing_at, self.swing_of = runs(swinging)
        """Per sample and leg, (T, n_legs): the samples since its swing's lift-off and the
        swing's samples from lift-off to touchdown (:func:`runs`)."""
        self.stance_at, self.stance_of = runs(~swinging)
        """The same of each stance, from touchdown to lift-off."""
        landing = (np.arange(n)[:, None] + self.swing_of - self.swing_at).astype(int) % n
        stand = longest_stand(robot, motion) if self.placed.any() else None
        self.lead = (lead(np.take_along_axis(self.stance_of, landing, axis=0) * motion.dt,
                          0.0 if stand is None else stand.omega)
                     + capture)
        """Per sample and leg, (T, n_legs), s: min(T_stance/2, coth(ω₀ T_stance)/ω₀) (the
        stance after the swing, :func:`lead`) + k, the landing point's shift per m/s of the
        body's velocity error (module docstring)."""
        self.landing = np.zeros(leg_rows.shape[1])
        """Each joint's swing correction at its last update (its leg's landing correction
        once the foot is down), rad."""

    def step(self, k: int, s: float, swing: np.ndarray, x: np.ndarray, p: np.ndarray,
             rot: np.ndarray, p_plan: np.ndarray, r_plan: np.ndarray, dv: np.ndarray,
             swing_map: np.ndarray) -> np.ndarray:
        """The placed swing feet's joint step ``b(φ) J_b⁺ Rᵀ (x̃ − p̃)`` (module docstring),
        kept as their legs' landing corrections; shape (nj,).

        Args:
            k: The plan's sample before the update. s: The weight of sample k + 1, in [0, 1].
            swing: The swinging legs, (n_swing,).
            x: Their planned feet at the update, world, m, (n_swing, 3).
            p: The base's measured position, world, m. rot: Its orientation, (3, 3).
            p_plan: The plan's base position, world, m. r_plan: The plan's orientation.
            dv: The base's velocity less the plan's, world, m/s, (3,).
            swing_map: J_b⁺ of the swinging legs, (nj, 3 n_swing).
        """
        placed = self.placed[swing]
        blend = smoothstep((self.swing_at[k, swing] + s) / self.swing_of[k, swing])
        blend[~placed] = 0.0
        carried = p + (x - p_plan) @ r_plan @ rot.T  # the planned foot, carried
        shift = (x - carried + (p + self.hips[swing] @ rot.T)
                 - (p_plan + self.hips[swing] @ r_plan.T)
                 + self.lead[k, swing, None] * dv)
        shift[:, 2] = 0.0  # the foot's height in the body as planned
        step = np.asarray(swing_map @ (blend[:, None] * (shift @ rot)).ravel())
        rows = self.leg_rows[swing[placed]].any(axis=0)
        self.landing[rows] = step[rows]
        return step

    def release(self, k: int, s: float, standing: np.ndarray) -> np.ndarray:
        """The placed stance legs' landing corrections, released over each stance's first
        :data:`HOLD` by ``1 − b`` (module docstring); shape (nj,).

        Args:
            k: The plan's sample before the update. s: The weight of sample k + 1.
            standing: Which legs stand at samples k and k + 1, (n_legs,), bool.
        """
        out = np.zeros(len(self.landing))
        for leg in np.flatnonzero(standing & self.placed):
            at = (self.stance_at[k, leg] + s) / (HOLD * self.stance_of[k, leg])
            if at < 1.0:
                rows = self.leg_rows[leg]
                out[rows] += (1.0 - smoothstep(at)) * self.landing[rows]
        return out


def lead(stance: np.ndarray, omega: float) -> np.ndarray:
    """The landing point's lead per m/s of the body's velocity error, s, for a stance of
    duration T: Raibert's ``T/2``, but never past the linear inverted pendulum's deadbeat
    step ``coth(ω₀ T) / ω₀`` (module docstring).

    A centre of mass at height h over a point foot moves as ``ẍ = ω₀² x``, ``ω₀ = √(g/h)``
    (x from the foot; Kajita et al., "The 3D linear inverted pendulum mode", IROS 2001, eq.
    5–6). The plan sets each foot down at its own neutral point; a velocity error e at
    touchdown with the foot set down ``L e`` further ahead leaves the stance as
    ``e (cosh ω₀T − ω₀ L sinh ω₀T)``. At ``L = coth(ω₀ T)/ω₀`` it leaves as 0 (deadbeat: the
    capture point's ``1/ω₀``, Pratt et al., Humanoids 2006, is its limit for a long stance;
    the capturability of a finite stance: Koolen et al., IJRR 31(9), 2012, §5). Raibert's
    ``T/2`` (*Legged Robots That Balance*, 1986, ch. 2) leaves it as ``cosh x − (x/2) sinh x``,
    ``x = ω₀T``: between 1 and 0 up to ``x = 2.07``, where the two leads meet (Solo-12's trot:
    x = 1.4, ×0.81; the sized trots x = 2.0, ×0.14), and beyond it past zero — ×−1.4 at
    x = 2.5, ×−28 at 4.0 (Solo-12's co-designed trot, T = 0.644 s): the error comes back
    reversed and larger, step after step. For a short stance the deadbeat step grows as
    ``1/(ω₀² T)`` without bound (a pendulum that hardly moves in a stance is corrected over
    several), so the lead is the smaller of the two: Raibert's where it measured (every trot
    of ``docs/simulate.md``, "Balance feedback"), the deadbeat step where ``T/2`` would
    overshoot.

    Args:
        stance: Stance durations T, s, any shape.
        omega: ω₀, 1/s, ≥ 0 (0: no pendulum known, Raibert's ``T/2``).

    Returns:
        The lead per m/s, s, the shape of ``stance``.
    """
    stance = np.asarray(stance, dtype=float)
    if omega <= 0.0:
        return stance / 2
    with np.errstate(divide="ignore"):
        deadbeat = 1.0 / (omega * np.tanh(omega * stance))
    return np.asarray(np.minimum(stance / 2, deadbeat))


def smoothstep(u: np.ndarray | float) -> np.ndarray:
    """3u² − 2u³ of u clipped to [0, 1]: from 0 to 1 with zero slope at both ends (the swing
    foot's blend: no jump of the servo's reference at lift-off or touchdown)."""
    u = np.clip(u, 0.0, 1.0)
    return np.asarray(u * u * (3.0 - 2.0 * u))


def runs(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The runs of True of each column of a periodic mask (sample T − 1 followed by 0).

    Args:
        mask: (T, n_legs), bool.

    Returns:
        ``(at, of)``, each (T, n_legs): at a True sample, the samples since its run began and
        the run's length in samples; 0 and 1 elsewhere (and 0, T for a column all True).
    """
    n, n_legs = mask.shape
    at, of = np.zeros((n, n_legs)), np.ones((n, n_legs))
    for i in range(n_legs):
        column = mask[:, i]
        if column.all():
            at[:, i], of[:, i] = np.arange(n), n
            continue
        start = int(np.flatnonzero(~column)[0]) + 1  # read from a sample after a False one
        run: list[int] = []
        for j in range(n + 1):
            k = (start + j) % n
            if j < n and column[k]:
                run.append(k)
            elif run:
                at[run, i], of[run, i] = np.arange(len(run)), len(run)
                run = []
    return at, of
