"""Invariants of the simulation: a free swing of the springs conserves energy to the integrator's
order."""

from __future__ import annotations

import mujoco
import numpy as np
import pinocchio as pin

from hexaleg.robot.springs import DeadZoneSpring, LinearSpring, SpringSet
from hexaleg.simulation.model import build_model


def _energy_error(prepared, springs: SpringSet, dt: float, duration: float = 0.5) -> np.ndarray:
    """|E(t) − E(0)| of a free swing: gravity, contacts, servos and damping off, the joints
    launched at random speeds; E = kinetic (Pinocchio) + the springs' stored energy."""
    robot, motion = prepared.robot, prepared.motion
    sim = build_model(robot, motion, prepared.motor, springs=springs, timestep=dt)
    m = sim.model
    m.opt.gravity[:] = 0.0
    m.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONTACT
                              | mujoco.mjtDisableBit.mjDSBL_ACTUATION)
    m.dof_damping[:] = 0.0
    data = mujoco.MjData(m)
    v0 = np.zeros(robot.model.nv)
    v0[6:] = np.random.default_rng(0).normal(size=robot.nj) * 2.0
    data.qpos[:], data.qvel[:] = sim.joints.to_mujoco(motion.q[0], v0)
    n = round(duration / dt)
    qpos, qvel = np.empty((n + 1, m.nq)), np.empty((n + 1, m.nv))
    qpos[0], qvel[0] = data.qpos, data.qvel
    for k in range(n):
        mujoco.mj_step(m, data)
        qpos[k + 1], qvel[k + 1] = data.qpos, data.qvel
    q, v = sim.joints.to_pinocchio(qpos, qvel)
    kinetic = np.array([pin.computeKineticEnergy(robot.model, robot.data, a, b)
                        for a, b in zip(q, v, strict=True)])
    total = kinetic + springs.energies(robot, q).sum(axis=1)
    return np.abs(total - total[0])


def test_free_swing_conserves_energy_to_first_order(prepared):
    """Symplectic Euler: over half a second of swinging (the springs engaging and releasing) the
    energy error halves with the timestep — first order — and stays within 1.7 % at dt = 0.25 ms
    (docs/simulate.md: 1.6 % of the 1.34 J)."""
    robot = prepared.robot
    springs = SpringSet({**{j: DeadZoneSpring(stiffness=2.0, theta_k=0.05, neutral=0.5)
                            for j in robot.joints("femur")},
                         **{j: LinearSpring(stiffness=0.5, reference=-1.0)
                            for j in robot.joints("tibia")}})
    coarse = _energy_error(prepared, springs, 5e-4)
    fine = _energy_error(prepared, springs, 2.5e-4)
    assert 1.9 < coarse.max() / fine.max() < 2.2
    assert fine.max() < 0.0225  # J, of 1.34 J in the swing
