"""The servos: gains from the servo model, the torque–speed envelope, the reference."""

from __future__ import annotations

from types import SimpleNamespace

import mujoco
import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.simulation.controllers import COMPLIANCE, Servo, controls, reference
from hexaleg.simulation.model import build_model


def test_gains_from_the_servo_model(prepared):
    """kp = τ_s/θ_c (AX compliance slope 32 × 0.29°), D = kd = τ_s/ω₀ (back-EMF)."""
    motor = prepared.motor
    kp, kd, damping, stall = Servo().gains(motor, 18)
    assert COMPLIANCE == pytest.approx(np.deg2rad(9.28))
    assert np.allclose(kp, motor.stall_torque / COMPLIANCE)
    assert np.allclose(kd, motor.stall_torque / motor.no_load_speed) and np.allclose(kd, damping)
    assert np.allclose(stall, motor.stall_torque)
    assert (kp[0], kd[0]) == pytest.approx((11.11, 0.1772), rel=1e-3)  # the AX-18A, docs
    kp2, kd2, _, _ = Servo(kp_scale=4, kd_scale=0.25).gains(motor, 18)
    assert np.allclose(kp2, 4 * kp) and np.allclose(kd2, kd / 4)


def test_per_joint_motors_broadcast():
    """A motor set gives (nj,) stall torques and speeds: the gains follow joint by joint."""
    stall, speed = np.linspace(1.0, 2.0, 18), np.linspace(5.0, 10.0, 18)
    kp, kd, damping, s = Servo().gains(SimpleNamespace(stall_torque=stall,
                                                       no_load_speed=speed), 18)
    assert np.allclose(kp, stall / COMPLIANCE) and np.allclose(damping, stall / speed)
    assert np.allclose(kd, damping) and np.array_equal(s, stall)
    with pytest.raises(InvalidParameterError, match="stall_torque"):
        Servo().gains(SimpleNamespace(stall_torque=stall[:5], no_load_speed=2.0), 18)


@pytest.mark.parametrize("kwargs, error", [({"controller": "pid"}, UnknownNameError),
                                           ({"kp_scale": 0.0}, InvalidParameterError),
                                           ({"kd_scale": -1.0}, InvalidParameterError),
                                           ({"compliance": 0.0}, InvalidParameterError)])
def test_bad_servo_settings_are_named(kwargs, error):
    with pytest.raises(error, match=next(iter(kwargs))):
        Servo(**kwargs)


def test_reference_hits_the_samples_and_is_smooth(walk, prepared):
    """At the samples the reference is the plan; between them its velocity is the derivative of
    its angle (cubic Hermite) and the torque is interpolated linearly."""
    tau = prepared.evaluate(None).tau_motor
    h = walk.dt
    at = reference(walk, tau, np.arange(5) * h + 3 * walk.period)  # periodic
    assert np.allclose(at.q, walk.q[:5, 7:], atol=1e-12)
    assert np.allclose(at.qdot, walk.v[:5, 6:], atol=1e-9)
    assert np.allclose(at.tau, tau[:5])
    t = np.linspace(100 * h, 101 * h, 201)
    ref = reference(walk, tau, t)
    assert np.allclose(np.gradient(ref.q, t, axis=0)[1:-1], ref.qdot[1:-1], atol=1e-6)
    assert np.allclose(ref.tau[100], (tau[100] + tau[101]) / 2)


def test_servo_torque_is_pd_plus_feedforward_inside_the_envelope(prepared):
    """At a state near the plan the joint gets τ_ff + kp e + kd ė; far from it the torque is
    the envelope ±τ_s − D q̇ (the voltage limit)."""
    robot, motion = prepared.robot, prepared.motion
    sim = build_model(robot, motion, prepared.motor, servo=Servo(kp_scale=0.5, kd_scale=2.0),
                      timestep=2.5e-4)
    tau_ff = prepared.evaluate(None).tau_motor
    ref = reference(motion, tau_ff, np.array([0.1]))
    ctrl = controls(sim.servo, ref, sim.kp, sim.kd)[0]
    m, data = sim.model, mujoco.MjData(sim.model)
    rng = np.random.default_rng(2)
    for scale, saturated in ((0.005, False), (2.0, True)):
        q, v = motion.q[100].copy(), motion.v[100].copy()
        q[7:] = ref.q[0] + scale * rng.normal(size=18)
        v[6:] = ref.qdot[0] + scale * 10 * rng.normal(size=18)
        data.qpos[:], data.qvel[:] = sim.joints.to_mujoco(q, v)
        data.ctrl[:18] = ctrl
        mujoco.mj_forward(m, data)
        torque = data.actuator_force[:18] - sim.damping * v[6:]
        pd = ref.tau[0] + sim.kp * (ref.q[0] - q[7:]) + sim.kd * (ref.qdot[0] - v[6:])
        envelope = np.clip(pd + sim.damping * v[6:], -sim.stall, sim.stall) - sim.damping * v[6:]
        assert np.allclose(torque, envelope, atol=1e-12)
        assert bool(np.any(np.abs(pd - envelope) > 1e-3)) is saturated


def test_position_servo_has_no_feedforward(prepared):
    """A position servo's control is the plan's angle; asked for the plan's torque (closed
    loop) the angle and τ_ff/kp, Tomei's set point; a feedforward servo's is the same either
    way."""
    tau = prepared.evaluate(None).tau_motor
    ref = reference(prepared.motion, tau, np.array([0.0, 0.3]))
    kp, kd = np.full(18, 2.0), np.full(18, 0.5)
    assert np.array_equal(controls(Servo("position"), ref, kp, kd), ref.q)
    assert np.array_equal(controls(Servo("position"), ref, kp, kd, torques=True),
                          ref.q + ref.tau / 2.0)
    assert np.array_equal(controls(Servo(), ref, kp, kd, torques=True), controls(Servo(), ref,
                                                                                 kp, kd))


BANDWIDTH_ROBOTS = ("hexaleg", "solo12", "anymal", "anymal_c", "go2", "a1",
                    *(f"tests/data/{n}.toml" for n in ("biped", "quad2dof", "quad4dof",
                                                      "spider", "xquad")))


@pytest.mark.slow
@pytest.mark.parametrize("name", BANDWIDTH_ROBOTS)
def test_every_robots_servo_is_stiff_against_its_gait(name):
    """The gains are the robot's own actuator's (kp = τ_s/θ_c): on every registered and test
    robot each joint's closed loop ω_n = √(kp/M_jj) at mid-cycle of its default gait (M_jj its
    inertia with the body held) is at least 5× the gait's frequency (docs/simulate.md quotes
    the least per robot; the test robots, which it does not quote, at 100 samples a cycle: the
    same mid-cycle instant, their ratios within 0.11 % of the 1000 samples', where the biped's
    ZMP gait took 4.7 s of CPU against 0.44)."""
    import pinocchio as pin

    from hexaleg.motion.legged import gait
    from hexaleg.motion.scaling import robot_gait
    from hexaleg.robot.registry import description

    root = __import__("pathlib").Path(__file__).resolve().parents[2]
    key = str(root / name) if name.endswith(".toml") else name
    desc = description(key)
    robot = desc.load()
    kp = Servo("position").gains(desc.actuator(robot), len(robot.joint_names))[0]
    params = robot_gait(key)
    sampled = params.updated({"samples": 100}) if name.endswith(".toml") else params
    q = gait(robot, sampled).q
    inertia = np.diag(pin.crba(robot.model, robot.data, q[len(q) // 2]))[6:]
    ratio = np.sqrt(kp / inertia).min() / (2 * np.pi / params.period)
    assert ratio >= 5.0
    labels = {"hexaleg": "the built-in hexapod", "solo12": "Solo-12", "anymal": "ANYmal",
              "anymal_c": "ANYmal C", "go2": "Go2", "a1": "A1"}
    if name in labels:
        page = " ".join((root / "docs" / "simulate.md").read_text().split())
        assert f"{labels[name]} {ratio:.1f}" in page
