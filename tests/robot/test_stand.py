"""A standing pose from foot positions and a body height."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot.stand import stand_from_feet


def test_feet_land_where_asked(spider):
    q = stand_from_feet(spider, 0.07, {"LF": [-0.17, 0.12]})
    feet = spider.foot_positions(q)
    np.testing.assert_allclose(feet[:, 2], -0.07, atol=1e-9)
    np.testing.assert_allclose(feet[0, :2], [-0.17, 0.12], atol=1e-9)
    zero = spider.foot_positions(np.r_[q[:7], np.zeros(spider.nj)])
    np.testing.assert_allclose(feet[1:, :2], zero[1:, :2], atol=1e-9)  # the others keep x, y
    model = spider.model
    assert np.all(q[7:] >= model.lowerPositionLimit[7:]) and np.all(
        q[7:] <= model.upperPositionLimit[7:])


def test_builtin_stand_is_recovered(robot):
    """The built-in stand's feet and height give back a pose with the same feet."""
    q0 = robot.pose("stand")
    feet = robot.foot_positions(q0)
    q = stand_from_feet(robot, float(-feet[0, 2]), {leg: feet[k, :2] for k, leg in
                                                    enumerate(robot.leg_names)})
    np.testing.assert_allclose(robot.foot_positions(q), feet, atol=1e-9)


def test_unreachable_and_bad_inputs_are_named(spider):
    with pytest.raises(InvalidParameterError, match=r"stand foot of leg LF.*lower body_height"):
        stand_from_feet(spider, 0.5)
    with pytest.raises(InvalidParameterError, match="body_height"):
        stand_from_feet(spider, -0.1)
    with pytest.raises(InvalidParameterError, match=r"stand.feet.LF"):
        stand_from_feet(spider, 0.08, {"LF": [0.1]})
    with pytest.raises(UnknownNameError, match="valid legs are"):
        stand_from_feet(spider, 0.08, {"XX": [0.1, 0.1]})


def _pryquad():
    from pathlib import Path

    import hexaleg

    return hexaleg.load(str(Path(__file__).resolve().parents[1] / "data" / "pryquad.toml"))


def test_a_pitch_roll_yaw_hip_gets_a_stand_within_its_limits():
    """The bent-knee starts suit a yaw–pitch–knee hip: on a pitch–roll–yaw hip whose knee range
    excludes 0 they end outside the limits, and the starts inside the limits find the stand
    (issue #55: refused as "out of reach" before)."""
    robot = _pryquad()
    q = robot.pose("stand")
    model = robot.model
    assert np.all(q[7:] >= model.lowerPositionLimit[7:] - 1e-12)
    assert np.all(q[7:] <= model.upperPositionLimit[7:] + 1e-12)
    np.testing.assert_allclose(robot.foot_positions(q)[:, 2], -0.19, atol=1e-9)
    knee = 2 * np.arccos(0.19 / 0.24)  # two 12 cm links, the hip straight above the foot
    np.testing.assert_allclose(q[7:][3::4], -knee, atol=1e-6)


def test_outside_the_limits_is_told_from_out_of_reach():
    """0.2385 m needs the knee at −0.22 rad, beyond its upper limit −0.3: outside the limits,
    naming the knee's limit; 0.3 m is beyond the stretched leg's 0.24 m: out of reach."""
    robot = _pryquad()
    with pytest.raises(InvalidParameterError, match=r"outside the limits: .* held by joint "
                       r"LF_knee at its upper limit -0.3 rad") as e:
        stand_from_feet(robot, 0.2385)
    assert "out of reach" not in str(e.value)
    with pytest.raises(InvalidParameterError, match=r"out of reach: it stops 0.06 m") as e:
        stand_from_feet(robot, 0.3)
    assert "outside the limits" not in str(e.value)


def test_joints_on_no_leg_hold_a_pose_within_their_limits():
    from pathlib import Path

    import hexaleg
    from hexaleg.robot.stand import hold_other_joints

    humanoid = hexaleg.load(str(Path(__file__).resolve().parents[1] / "data" / "humanoid.toml"))
    q = hold_other_joints(humanoid, np.r_[humanoid.pose("stand")[:7], np.zeros(humanoid.nj)],
                          {"R_shoulder": -0.2})
    at = {j: q[7 + humanoid.column(j)] for j in humanoid.other_joints}
    assert at == {"waist": 0.0, "L_shoulder": 0.0, "L_elbow": 0.1, "R_shoulder": -0.2,
                  "R_elbow": 0.1}
    assert q[7 + humanoid.column("L_knee")] == 0.0  # the legs are not touched
    with pytest.raises(UnknownNameError, match=r"stand.joints entry .*L_knee.*waist"):
        hold_other_joints(humanoid, q, {"L_knee": 0.3})


def test_a_redundant_leg_is_untwisted_on_its_target():
    """A four-joint leg reaches a foot with its hip rolled and turned; the null-space pull
    (then a plain solve) brings roll and yaw back to their zero, the foot still on its target —
    what gives a humanoid's six-joint legs a straight stand (issue #55)."""
    from hexaleg.robot.stand import _newton

    robot = _pryquad()
    leg = robot.legs[0]
    model, data = robot.model, robot.model.createData()
    lo, hi = model.lowerPositionLimit[leg.q_index], model.upperPositionLimit[leg.q_index]
    target = robot.foot_positions(robot.pose("stand"))[0]
    q = robot.pose("stand")
    q[leg.q_index] = [0.3, 0.3, 0.4, -1.0]
    assert _newton(robot, data, leg, target, q, (lo, hi)) < 1e-9
    twisted = q[leg.q_index].copy()
    assert abs(twisted[2]) > 0.1  # the plain solve keeps the hip turned
    assert _newton(robot, data, leg, target, q, (lo, hi), pull=True) < 1e-4
    assert _newton(robot, data, leg, target, q, (lo, hi)) < 1e-9
    np.testing.assert_allclose(robot.foot_positions(q)[0], target, atol=1e-9)
    assert abs(q[leg.q_index][2]) < 1e-3 < abs(twisted[2])
    assert np.all(q[leg.q_index] >= lo) and np.all(q[leg.q_index] <= hi)


def test_a_leg_that_cannot_fold_to_its_foot_is_told_to_stand_higher(tmp_path):
    """Data we did not make: example-robot-data's ``quadruped_description`` with its knees
    welded (``fixed``): each leg is one hip joint and a 0.345-m limb, so a foot 0.25 m below the
    hip is too near, not too far — the advice raises body_height (it said "lower" before)."""
    from hexaleg.robot.description import RobotDescription
    from hexaleg.robot.sources import example_robot_data_dir

    text = (example_robot_data_dir() / "quadruped_description" / "urdf" /
            "quadruped.urdf").read_text(encoding="utf-8")
    welded = text.replace('_KFE" type="revolute"', '_KFE" type="fixed"')
    assert welded.count('type="fixed"') == text.count('type="fixed"') + 4
    (tmp_path / "welded.urdf").write_text(welded, encoding="utf-8")
    (tmp_path / "q.toml").write_text('[robot]\nname = "q"\nurdf = "welded.urdf"\n'
                                     'stand = {body_height = 0.25}\n')
    with pytest.raises(InvalidParameterError, match=r"out of reach: it stops 0.095 m from it, "
                       r"0.25 m from the first joint; the foot is 0.345 m from the first joint "
                       r"when stretched\): the leg does not fold that short: raise body_height"):
        RobotDescription.from_toml(tmp_path / "q.toml").load()
