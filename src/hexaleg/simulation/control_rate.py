"""How often the balance controller (:mod:`hexaleg.simulation.balance`) updates its correction.

The controller runs every :data:`CONTROL_PERIOD` (100 Hz: the rate of a Dynamixel bus's
position commands to 18 servos, and within the 30–500 Hz of the MIT Cheetahs' MPC and WBIC
loops), holding its correction in between. At 100 Hz the controller costs ≤ 3× the open-loop
step (``analysis/bench_simulate.py``); 200 Hz walks the same four trots with the same verdicts.

The correction is held over the period T, so the loop is a sampled one, and the base it acts on
answers faster than the model the wrench assumes (m and the centroidal inertia): over one period
the servos' forces hold the joints only through their motion, so the base moves with the base
block ``B`` of ``M⁻¹`` (the joints free, the plan's first sample). Its error then follows
``ë = −r (k_p e + k_d ė)``, r the largest eigenvalue of ``m B_lin`` and of ``B_ang I_c`` — a held
correction is the explicit step of that loop, stable while ``r k_p T² + 2 r k_d T < 4`` (the
Jury criterion of the step, as the integration's in :mod:`hexaleg.simulation.model`). The
controller runs every :data:`CONTROL_PERIOD` or, where that breaks the criterion, every
:data:`LOOP_MARGIN` of the limit (a whole number of steps).

Unitree G1 (example-robot-data, 33 kg, its 3.8-kg pelvis under a 3-joint waist): r = 60.7 on
the pelvis' pitch (the registered robots 2.4–5.1, Talos 16.8, every one below the limit at
100 Hz), the criterion 15.6 at 100 Hz: its stance hip's torque flipped sign at every update,
±100 N·m by 0.1 s, and it fell within 2.6 s at any timestep; at 2.08 ms it walks
(``analysis/bench_logs/newcomers_simulate.log``, the G1 block).
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from hexaleg.motion.recorded.base import rotation_from_quaternion
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot

CONTROL_PERIOD = 1e-2
"""s: the balance controller's period (100 Hz; module docstring)."""
LOOP_MARGIN = 0.8
"""The controller's period is at most this share of its sampled loop's stability limit (module
docstring), as the automatic timestep is of the integration's
(:func:`hexaleg.simulation.timestep.automatic_timestep`)."""

def loop_ratio(robot: Robot, q: np.ndarray) -> float:
    """r: how much faster the base answers the controller's wrench than the model it is sized
    for (module docstring): the largest eigenvalue of ``m B_lin`` and of
    ``B_ang I_c``, B the base's block of ``M⁻¹`` at ``q`` (the joints free; Pinocchio's
    ``computeMinverse``, the base frame) and I_c the centroidal inertia (``ccrba``, turned into
    the base frame), ≥ 0."""
    model = robot.model
    data = model.createData()
    upper = pin.computeMinverse(model, data, q)
    minv = np.triu(upper) + np.triu(upper, 1).T  # Pinocchio fills the upper triangle
    pin.ccrba(model, data, q, np.zeros(model.nv))
    rot = rotation_from_quaternion(q[None, 3:7])[0]
    inertia = rot.T @ np.asarray(data.Ig.inertia) @ rot
    linear = np.linalg.eigvals(minv[:3, :3] * robot.mass).real
    angular = np.linalg.eigvals(minv[3:6, 3:6] @ inertia).real
    return float(max(linear.max(), angular.max()))


def control_period(robot: Robot, motion: Motion, omega: float, zeta: float = 1.0) -> float:
    """The balance controller's period, s: :data:`CONTROL_PERIOD`, or :data:`LOOP_MARGIN` of the
    sampled loop's limit where that is shorter — the T with ``r k_p T² + 2 r k_d T = 4``,
    k_p = ω², k_d = 2 ζ ω and r :func:`loop_ratio` at the plan's first sample (module
    docstring)."""
    r = loop_ratio(robot, motion.q[0])
    a, b = r * 2 * zeta * omega, r * omega**2
    limit = (-2 * a + math.sqrt(4 * a * a + 16 * b)) / (2 * b)
    return min(CONTROL_PERIOD, LOOP_MARGIN * limit)
