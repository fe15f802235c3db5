"""Every spring family in MuJoCo equals hexaleg's spring law, to 2e-15 N·m at sampled states."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from hexaleg.errors import UnknownNameError
from hexaleg.robot.springs import (
    DeadZoneSpring,
    LinearSpring,
    OneSidedSpring,
    PreloadedSpring,
    SpringSet,
    StiffeningSpring,
)
from hexaleg.simulation.model import build_model
from hexaleg.simulation.springs import STEP_WIDTH, plan_springs

FAMILIES = {
    "linear": (LinearSpring(stiffness=0.8, reference=0.3, torque_at_reference=-0.1), True),
    "constant_torque": (LinearSpring(stiffness=0.0, torque_at_reference=-0.09), True),
    "near_constant": (LinearSpring(stiffness=3e-12, reference=0.5, torque_at_reference=-0.09),
                      True),
    "dead_zone": (DeadZoneSpring(stiffness=1.5, theta_minus=-0.1, theta_plus=0.15,
                                 stiffness_minus=0.7, k2=0.05, alpha=1.05, neutral=0.4), True),
    "dead_zone_damped": (DeadZoneSpring(stiffness=1.2, theta_k=0.1, damping=0.02,
                                        convention="eq14", alpha=1.1, neutral=0.2), False),
    "preloaded": (PreloadedSpring(stiffness=1.0, preload=0.05, theta_minus=-0.1, theta_plus=0.2,
                                  preload_minus=0.02, neutral=0.3), True),
    "one_sided": (OneSidedSpring(stiffness=2.0, contact=0.5, side="below", preload=0.03), True),
    "stiffening": (StiffeningSpring(above=((0.5, 1.0), (0.7, 2.0)), below=((0.1, 0.5),)), True),
}
JOINTS = ("LF_femur", "RM_tibia", "LH_coxa")


@pytest.mark.parametrize("family", FAMILIES)
def test_simulated_spring_torque_is_the_spring_law(family, prepared):
    """MuJoCo's spring torque (native passive forces + constant actuators + the non-native
    terms) equals ``SpringSet.torques`` at 40 random states whose angles sweep every contact
    angle, on three joints at once."""
    spring, native = FAMILIES[family]
    springs = SpringSet(dict.fromkeys(JOINTS, spring))
    robot, motion = prepared.robot, prepared.motion
    sim = build_model(robot, motion, prepared.motor, springs=springs)
    assert sim.springs.native is native
    m, data = sim.model, mujoco.MjData(sim.model)
    rng = np.random.default_rng(7)
    q = np.tile(motion.q[0], (40, 1))
    v = rng.normal(size=(40, robot.model.nv))
    cols = [robot.model.joints[robot.model.getJointId(j)].idx_q for j in JOINTS]
    q[:, cols] = rng.uniform(-0.6, 1.2, size=(40, len(JOINTS)))
    expected = springs.torques(robot, q, v)
    assert np.abs(expected).max() > 0.01  # the states engage the springs
    for k in range(40):
        data.qpos[:], data.qvel[:] = sim.joints.to_mujoco(q[k], v[k])
        mujoco.mj_forward(m, data)
        assert np.allclose(sim.spring_torque(data), expected[k], rtol=0, atol=2e-15)


def test_no_springs_no_elements(prepared):
    plan = plan_springs(prepared.robot, SpringSet())
    assert plan.native and not plan.tendons and not plan.stiffness and not plan.actuators


def test_a_spring_on_a_joint_the_robot_lacks_is_named(prepared):
    with pytest.raises(UnknownNameError, match="LF_knee"):
        plan_springs(prepared.robot, SpringSet({"LF_knee": FAMILIES["linear"][0]}))


@pytest.mark.parametrize("side", ["above", "below"])
def test_a_preload_step_is_exact_outside_its_nanoradian_ramp(side, prepared):
    """The native step (a clamped affine actuator) gives the preload's full jump 10 nrad past the
    contact angle and nothing 10 nrad before it — the law to the last bit, on both sides."""
    spring = OneSidedSpring(stiffness=2.0, contact=0.7, side=side, preload=0.25)
    springs = SpringSet({"LF_femur": spring})
    robot, motion = prepared.robot, prepared.motion
    sim = build_model(robot, motion, prepared.motor, springs=springs)
    assert sim.springs.native and len(sim.springs.actuators) == 1
    data = mujoco.MjData(sim.model)
    col = robot.column("LF_femur")
    idx = robot.model.joints[robot.model.getJointId("LF_femur")].idx_q
    past = 1.0 if side == "above" else -1.0
    for offset in (-1e-3, -10 * STEP_WIDTH, 10 * STEP_WIDTH, 1e-3):
        q = motion.q[0].copy()
        q[idx] = 0.7 + past * offset
        data.qpos[:], data.qvel[:] = sim.joints.to_mujoco(q, np.zeros(robot.model.nv))
        mujoco.mj_forward(sim.model, data)
        expected = springs.torques(robot, q[None], np.zeros((1, robot.model.nv)))[0, col]
        assert abs(expected) == (0.0 if offset < 0 else pytest.approx(0.25 + 2.0 * offset))
        assert sim.spring_torque(data)[col] == expected
