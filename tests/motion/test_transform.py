"""Tests of hexaleg.motion.transform: the stand → sphere transformation sits down on its feet,
folds resting on the ground, never passes below it, is smooth across the phase switch; errors."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.motion.transform import transform_motion


@pytest.fixture(scope="module")
def fold(robot) -> hexaleg.motion.trajectory.Motion:
    return transform_motion(robot, duration=2.0, samples=401)


def test_transform_sits_down_on_its_feet_then_folds_resting_on_the_ground(robot, fold,
                                                                          frame_kinematics):
    sit = ~fold.supported
    n_sit = int(sit.sum())
    assert n_sit == 100 and sit[:n_sit].all()  # t < 0.25 · 2 s at dt = 5 ms
    # Starts standing: the stand pose with the feet on the ground; ends in the sphere pose.
    h0 = fold.info["stand_height"]
    assert h0 == pytest.approx(-robot.foot_positions(robot.pose("stand"))[:, 2].min(), abs=1e-15)
    assert np.allclose(fold.q[0, 7:], robot.pose("stand")[7:]) and fold.q[0, 2] == h0
    assert np.allclose(fold.q[-1, 7:], robot.pose("sphere")[7:])
    # The sphere rests on its lowest point, the lower body dome: in urdf/hexaleg.urdf a sphere
    # of radius 0.07 m centred 0.0135 m below the base.
    assert fold.info["rest_height"] == pytest.approx(0.0135 + 0.07, abs=1e-12)
    assert fold.info["clearance"] == pytest.approx(0.0, abs=1e-12)
    # Sitting: all six feet stand still on the ground and carry the body down vertically.
    assert fold.stance[:n_sit].all() and not fold.stance[n_sit:].any()
    pos, vel, acc = frame_kinematics(robot, fold)
    assert np.abs(pos - fold.feet).max() <= 1e-9
    assert np.abs(pos[:n_sit] - pos[0]).max() <= 1e-9
    assert np.abs(pos[:n_sit, :, 2]).max() <= 1e-12
    assert np.abs(vel[:n_sit]).max() <= 1e-9 and np.abs(acc[:n_sit]).max() <= 1e-9
    assert np.abs(fold.q[:n_sit, [0, 1, 3, 4, 5]]).max() == 0.0  # straight down, no tilt
    assert np.all(np.diff(fold.q[:n_sit, 2]) <= 0.0)
    # Folding: the body rests (base still at the resting height), feet lift off and stay up.
    assert np.allclose(fold.q[n_sit:, :7], fold.q[-1, :7], atol=0.0)
    assert fold.q[-1, 2] == fold.info["rest_height"]
    assert np.abs(fold.v[n_sit:, :6]).max() == 0.0 and np.abs(fold.a[n_sit:, :6]).max() == 0.0
    assert np.all(fold.feet[n_sit + 1:, :, 2] > 0.0)
    assert np.abs(vel[n_sit:]).max() > 0.05  # the legs really move (feet at up to 0.077 m/s)


def test_transform_never_passes_below_the_ground(robot, fold):
    """Every geometry but the foot balls (the feet are their points) stays at z ≥ 0 all along,
    and the body touches the ground exactly while folding."""
    feet = [robot.model.frames[leg.foot_frame_id].name for leg in robot.legs]
    z, names = robot.lowest_points(fold.q, ignore=feet)
    assert z.min() >= -1e-12
    assert np.abs(z[fold.supported]).max() <= 1e-12
    assert set(np.asarray(names)[fold.supported]) == {"body_1"}
    assert fold.feet[..., 2].min() >= -1e-12


def test_transform_is_smooth_across_the_phase_switch(robot, fold):
    """Zero velocity and acceleration at both ends and at the switch; v and a are the time
    derivatives of q and v (central differences, interior samples, both phases)."""
    n_sit = int((~fold.supported).sum())
    assert fold.t[n_sit] == fold.info["sit_time"]  # the fold starts on a sample, at rest
    for k in (0, n_sit, fold.n_samples - 1):
        assert np.abs(fold.v[k]).max() == 0.0 and np.abs(fold.a[k]).max() == 0.0
    # ... and the sit ends at rest: one sample before the switch, v and a have almost vanished.
    assert np.abs(fold.v[n_sit - 1]).max() < 1e-3 * np.abs(fold.v).max()
    assert np.abs(fold.a[n_sit - 1]).max() < 3e-2 * np.abs(fold.a).max()
    assert fold.t[-1] == pytest.approx(2.0) and fold.period == 2.0 and not fold.periodic
    dt = fold.dt
    dq = np.array([pin.difference(robot.model, a, b)
                   for a, b in zip(fold.q[:-2], fold.q[2:], strict=True)]) / (2 * dt)
    assert np.abs(dq - fold.v[1:-1]).max() < 1e-3 * np.abs(fold.v).max()
    assert np.abs((fold.v[2:] - fold.v[:-2]) / (2 * dt) - fold.a[1:-1]).max() \
        < 1e-2 * np.abs(fold.a).max()


def test_transform_errors(robot):
    with pytest.raises(InvalidParameterError, match="duration"):
        transform_motion(robot, duration=0.0)
    with pytest.raises(UnknownNameError, match=r"'ball'.*sphere"):
        transform_motion(robot, end="ball")
    with pytest.raises(InvalidParameterError, match=r"rest_height.*\(0, 0\.0913\]"):
        transform_motion(robot, rest_height=-0.1)
    with pytest.raises(InvalidParameterError, match="cannot rise"):
        transform_motion(robot, rest_height=0.2)
    # Seated too low, the body dome would have to sink into the ground: named, with the depth.
    with pytest.raises(InvalidParameterError, match=r"body_1 reaches 33\.50 mm below"):
        transform_motion(robot, rest_height=0.05)
    with pytest.raises(InvalidParameterError, match="sit_fraction"):
        transform_motion(robot, sit_fraction=1.0)
    with pytest.raises(InvalidParameterError, match=r"two samples in each phase \(sit 1"):
        transform_motion(robot, samples=20, sit_fraction=0.01)
