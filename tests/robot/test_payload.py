"""Tests of hexaleg.robot.payload: a payload on the base is in the dynamics (Σ f = (m + m_p)
(a_com − g), checked against the robot's own CoM and the payload's acceleration computed by
hand), its rotational inertia is the base's, the report shows it, the spring design carries it,
and a bad payload is a named error."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.payload import Payload, with_payload

BOX = Payload(mass=0.4, com=(0.03, -0.01, 0.04),
              inertia=((2e-3, 1e-4, 0.0), (1e-4, 3e-3, 0.0), (0.0, 0.0, 4e-3)))


def _hat(w: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def test_the_forces_carry_robot_and_payload(robot):
    """Σ f = m a_com(robot) + m_p a_p − (m + m_p) g, a_p the payload's acceleration from the
    base's LOCAL twist: R (a + ω × v + ω̇ × r + ω × (ω × r)) (rigid-body kinematics)."""
    heavy = BOX.attach(robot)
    assert heavy.mass == pytest.approx(robot.mass + 0.4, rel=1e-12)
    assert robot.mass == pytest.approx(1.36366, abs=1e-5)  # the robot given is not modified
    motion = hexaleg.gait(heavy, hexaleg.GaitParams(samples=100, yaw_rate=0.3, duty_factor=0.6))
    analysis = hexaleg.prepare(heavy, motion).evaluate()
    data, r = robot.model.createData(), np.array(BOX.com)
    g = robot.model.gravity.linear
    for k in range(motion.n_samples):
        q, v, a = motion.q[k], motion.v[k], motion.a[k]
        pin.centerOfMass(robot.model, data, q, v, a)
        rot = pin.Quaternion(q[3:7]).toRotationMatrix()
        lin, w, alpha = v[:3], v[3:6], a[3:6]
        a_p = rot @ (a[:3] + np.cross(w, lin) + np.cross(alpha, r) + np.cross(w, np.cross(w, r)))
        expected = robot.mass * data.acom[0] + 0.4 * a_p - (robot.mass + 0.4) * g
        assert np.allclose(analysis.forces[k].sum(axis=0), expected, atol=1e-8)


def test_the_payload_inertia_is_added_to_the_base_about_its_origin(robot):
    heavy = BOX.attach(robot)
    before, after = robot.model.inertias[1].matrix(), heavy.model.inertias[1].matrix()
    c, m = np.array(BOX.com), BOX.mass
    expected = np.zeros((6, 6))  # spatial inertia of the box about the base origin
    expected[:3, :3] = m * np.eye(3)
    expected[:3, 3:] = -m * _hat(c)
    expected[3:, :3] = m * _hat(c)
    expected[3:, 3:] = np.array(BOX.inertia) - m * _hat(c) @ _hat(c)
    assert np.allclose(after - before, expected, atol=1e-15)
    point = with_payload(robot, 0.4, np.array(BOX.com))
    assert np.allclose(heavy.model.inertias[1].matrix() - point.model.inertias[1].matrix(),
                       np.pad(np.array(BOX.inertia), ((3, 0), (3, 0))), atol=1e-15)
    assert "payload 0.4 kg" in heavy.notes[-1] and "rigid body" in heavy.notes[-1]


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"mass": -0.1}, r"invalid payload mass = -0\.1; allowed: a finite mass >= 0 kg"),
    ({"mass": float("nan")}, "invalid payload mass"),
    ({"com": (0.0, 0.0)}, "invalid payload com"),
    ({"inertia": ((1.0, 0.5, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))}, "symmetric"),
    ({"inertia": ((-1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))}, "principal moments"),
    ({"inertia": ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 3.0))}, r"I₁ \+ I₂ ≥ I₃"),
])
def test_a_bad_payload_is_named(kwargs, match):
    with pytest.raises(InvalidParameterError, match=match):
        Payload(**kwargs)


def test_the_report_and_the_design_carry_the_payload(robot):
    from hexaleg.design.search.optimal import optimal_springs
    from hexaleg.report.build import build_report
    from hexaleg.report.config import ReportConfig

    config = ReportConfig.from_mapping({
        "gait": {"samples": 60}, "payload": {"mass": 0.4, "com": [0.03, -0.01, 0.04]},
        "report": {"stiffness_points": 2, "paper_samples": 16}})
    assert config.payload == Payload(mass=0.4, com=(0.03, -0.01, 0.04))
    report = build_report(config, robot=robot)
    assert report.robot.mass == pytest.approx(robot.mass + 0.4)
    assert report.data["payload"]["mass"] == {"value": 0.4, "unit": "kg"}
    assert report.data["payload"]["total_mass"]["value"] == pytest.approx(robot.mass + 0.4)
    assert report.data["robot"]["mass"]["value"] == pytest.approx(robot.mass + 0.4)
    assert build_report(ReportConfig.from_mapping({
        "gait": {"samples": 60}, "report": {"stiffness_points": 2, "paper_samples": 16}}),
        robot=robot).data["payload"] is None
    from collections import defaultdict

    from hexaleg.outputs.html import render_html
    page = render_html({**report.data, "files": []}, defaultdict(str))
    assert '<th class="name">payload</th><td>0.4 kg</td>' in page
    # The spring design sees the heavier robot: the femurs carry more, the optimum differs.
    light = optimal_springs(hexaleg.prepare(robot, report.motion), ["femur"], "linear")
    heavy = optimal_springs(hexaleg.prepare(report.robot, report.motion), ["femur"], "linear")
    assert heavy.baseline > 1.1 * light.baseline
    assert heavy.magnitudes != light.magnitudes


def test_point_masses_at_joints_ride_on_their_child_links(robot):
    """:func:`with_point_masses`: the mass at a joint's origin on its child link; the total mass
    grows by their sum, the kinematics do not change, a bad joint or mass is named."""
    from hexaleg.errors import UnknownNameError
    from hexaleg.robot.payload import with_point_masses

    heavy = with_point_masses(robot, {"LF_femur": 0.02, "RH_tibia": 0.03}, note="springs")
    assert heavy.mass == pytest.approx(robot.mass + 0.05, rel=1e-12)
    assert heavy.notes[-1] == "springs" and robot.mass == pytest.approx(1.36366, abs=1e-5)
    q = robot.pose("stand")
    assert np.allclose(heavy.foot_positions(q), robot.foot_positions(q), atol=1e-15)
    jid = robot.model.getJointId("LF_femur")
    added = heavy.model.inertias[jid].matrix() - robot.model.inertias[jid].matrix()
    assert np.allclose(added, np.diag([0.02, 0.02, 0.02, 0.0, 0.0, 0.0]), atol=1e-15)
    with pytest.raises(UnknownNameError, match="LF_knee"):
        with_point_masses(robot, {"LF_knee": 0.01})
    with pytest.raises(InvalidParameterError, match="mass at LF_femur"):
        with_point_masses(robot, {"LF_femur": -0.01})
