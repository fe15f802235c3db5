"""A foot point's contact-space inverse inertia is MuJoCo's and the finite differences' (the
foot's position differenced along each velocity direction, Pinocchio's mass matrix), and the mass
a held foot's normal contact moves is the Schur complement's."""

from __future__ import annotations

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from hexaleg.simulation.foot_mass import contact_inverse_inertia, held_masses, sliding_masses
from hexaleg.simulation.model import build_model


def _configurations(robot, motion, n: int = 3):
    """The gait's first sample and ``n`` random ones, the base turned and the joints anywhere
    in ±1 rad of the stand."""
    rng = np.random.default_rng(7)
    yield motion.q[0]
    for _ in range(n):
        v = np.concatenate([rng.normal(0, 0.3, 6), rng.uniform(-1, 1, robot.model.nv - 6)])
        yield pin.integrate(robot.model, motion.q[0], v)


def _finite_differences(robot, q: np.ndarray, h: float = 1e-6) -> np.ndarray:
    """``J M⁻¹ Jᵀ`` with each foot's Jacobian column ``(p(q ⊕ h eᵢ) − p(q ⊖ h eᵢ)) / 2h`` and
    Pinocchio's CRBA mass matrix, (n_legs, 3, 3)."""
    model, data = robot.model, robot.model.createData()

    def feet(x):
        pin.framesForwardKinematics(model, data, x)
        return np.array([data.oMf[leg.foot_frame_id].translation for leg in robot.legs])

    jac = np.empty((len(robot.legs), 3, model.nv))
    for i in range(model.nv):
        step = np.zeros(model.nv)
        step[i] = h
        jac[:, :, i] = (feet(pin.integrate(model, q, step))
                        - feet(pin.integrate(model, q, -step))) / (2 * h)
    mass = pin.crba(model, data, q)
    mass = np.triu(mass) + np.triu(mass, 1).T
    return jac @ np.linalg.solve(mass, jac.transpose(0, 2, 1))


def _mujoco(sim, q: np.ndarray) -> np.ndarray:
    """``J M⁻¹ Jᵀ`` of each foot sphere's centre from MuJoCo's own Jacobian (``mj_jac``) and
    mass matrix (``mj_solveM``), (n_legs, 3, 3)."""
    m = sim.model
    d = mujoco.MjData(m)
    d.qpos[:], _ = sim.joints.to_mujoco(q, np.zeros(sim.robot.model.nv))
    mujoco.mj_forward(m, d)
    out = []
    for g in sim.foot_geoms:
        jacp = np.zeros((3, m.nv))
        mujoco.mj_jac(m, d, jacp, None, d.geom_xpos[g], m.geom_bodyid[g])
        x = np.zeros((3, m.nv))
        mujoco.mj_solveM(m, d, x, jacp)
        out.append(jacp @ x.T)
    return np.array(out)


def test_the_inverse_inertia_is_the_finite_differences_and_mujocos(prepared):
    robot, motion = prepared.robot, prepared.motion
    sim = build_model(robot, motion, prepared.motor)
    for q in _configurations(robot, motion):
        a = contact_inverse_inertia(robot, q)
        assert a == pytest.approx(_finite_differences(robot, q), rel=1e-6, abs=1e-9)
        assert a == pytest.approx(_mujoco(sim, q), rel=1e-6, abs=1e-9)


def test_a_held_foot_moves_the_schur_complements_mass(prepared):
    """Held by its friction, the normal row moves ``1 / (A_zz − A_zt A_tt⁻¹ A_tz)``, more than
    the sliding foot's ``1 / A_zz`` and less than the robot; on the built-in robot 0.073 kg at
    the stand's hind feet, 15 % under MuJoCo's ``body_invweight0`` of the tibia (0.085 kg),
    which sized the contact's stability before (docs/simulate.md)."""
    robot, motion = prepared.robot, prepared.motion
    for q in _configurations(robot, motion):
        a = contact_inverse_inertia(robot, q)
        schur = a[:, 2, 2] - np.einsum("li,lij,lj->l", a[:, 2, :2],
                                       np.linalg.inv(a[:, :2, :2]), a[:, :2, 2])
        held, sliding = held_masses(robot, q), sliding_masses(robot, q)
        assert held == pytest.approx(1.0 / schur, rel=1e-9)
        assert np.all(sliding <= held * (1 + 1e-12)) and np.all(held < robot.mass)
    assert held_masses(robot, motion.q[0]).min() == pytest.approx(0.0726, abs=5e-5)
