"""The paper's Adams experiment in MuJoCo, and the open-loop invariant of its single joint."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import UnknownNameError
from hexaleg.paper.joint import PaperJoint
from hexaleg.paper.metrics import metric
from hexaleg.paper.simulated_joint import AdamsJoint, adams, open_loop, open_loop_bound

JOINT = PaperJoint()


def test_rigid_joint_is_the_analytic_torque():
    """No main spring, no friction: the required torque of the driven lever is J θ̈ plus Table 5's
    secondary spring, exactly."""
    model = AdamsJoint(friction=False)
    run = adams(model, 0.0, periods=1)
    theta, theta_dot, theta_ddot = JOINT.trajectory(run.t)
    expected = JOINT.J * theta_ddot + model.stiffness_si(0.01) * theta \
        + model.stiffness_si(1e-4) * theta_dot
    assert np.allclose(run.torque, expected, rtol=0, atol=1e-15)


def test_gravity_is_the_joints_own():
    """With gravity the hanging lever's torque adds m g l sin θ with the joint's g (here 5 m/s²,
    not the standard 9.81)."""
    joint = PaperJoint(gravity=5.0)
    model = AdamsJoint(joint=joint, gravity=True, friction=False)
    run = adams(model, 0.0, periods=1)
    theta, theta_dot, theta_ddot = joint.trajectory(run.t)
    expected = joint.J * theta_ddot + joint.mass * 5.0 * joint.com * np.sin(theta) \
        + model.stiffness_si(0.01) * theta + model.stiffness_si(1e-4) * theta_dot
    assert np.allclose(run.torque, expected, rtol=0, atol=1e-15)


def test_springs_as_bodies_follow_the_dead_zone_law():
    """At k_M the contact-driven spring arms reproduce the analytic mean torque within 10 %
    (impacts and the arms' inertia add the rest); the arms rest on their stops at ±θ_k and follow
    the lever to ±A; Table 2's friction adds torque."""
    model = AdamsJoint(friction=False)
    run = adams(model, 713.547, periods=1)
    analytic = float(metric(JOINT, "mean_abs", 713.547e-6, gravity=False))
    assert run.mean_abs() == pytest.approx(analytic, rel=0.10)
    assert run.arms[:, 0].min() == pytest.approx(JOINT.theta_k, abs=0.01)
    assert run.arms[:, 0].max() == pytest.approx(JOINT.amplitude, abs=0.005)
    assert adams(AdamsJoint(), 713.547, periods=1).mean_abs() > run.mean_abs()


def test_units_of_the_tables():
    paper, printed = AdamsJoint(), AdamsJoint(units="printed")
    assert paper.stiffness_si(713.547) == pytest.approx(JOINT.k_M() * JOINT.transmission / 1.05,
                                                        rel=1e-5)
    assert printed.stiffness_si(1.0) == pytest.approx(1e-3 * 180 / np.pi)
    k, c, d = paper.contact_si()
    assert (k, c, d) == pytest.approx((1e5 * 1e-3 * 1000**2.2, 10.0, 1e-4))
    assert printed.contact_si()[0] == pytest.approx(1000 * k)
    with pytest.raises(UnknownNameError, match="units"):
        AdamsJoint(units="SI")


def test_open_loop_follows_the_plan_within_the_bound_at_second_order():
    """The analysis' torque with no feedback: the error stays inside the derived bound and falls
    fourfold when the timestep halves."""
    joint = PaperJoint(gravity=0.0)
    errors = []
    for dt in (1e-3, 5e-4):
        t, err = open_loop(joint, joint.k_M(), dt)
        assert np.all(np.abs(err) <= open_loop_bound(joint, dt, t))
        errors.append(np.abs(err).max())
    assert errors[0] / errors[1] == pytest.approx(4.0, rel=0.1)
