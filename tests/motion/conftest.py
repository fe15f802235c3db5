"""Fixtures of the motion tests: Pinocchio's own foot kinematics and central differences of a
gait, the independent checks of the motions' q, v and a; a robot turned inside its base frame (a
URDF facing another way)."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.motion.legged import sample_gait

FrameKinematics = Callable[[hexaleg.Robot, hexaleg.Motion],
                           tuple[np.ndarray, np.ndarray, np.ndarray]]


def _frame_kinematics(robot: hexaleg.Robot, motion: hexaleg.Motion
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """World position, velocity and classical acceleration (LOCAL_WORLD_ALIGNED) of every foot."""
    data = robot.model.createData()
    shape = (motion.n_samples, len(robot.legs), 3)
    pos, vel, acc = np.empty(shape), np.empty(shape), np.empty(shape)
    for k in range(motion.n_samples):
        pin.forwardKinematics(robot.model, data, motion.q[k], motion.v[k], motion.a[k])
        pin.updateFramePlacements(robot.model, data)
        for i, leg in enumerate(robot.legs):
            fid = leg.foot_frame_id
            pos[k, i] = data.oMf[fid].translation
            vel[k, i] = pin.getFrameVelocity(robot.model, data, fid,
                                             pin.LOCAL_WORLD_ALIGNED).linear
            acc[k, i] = pin.getFrameClassicalAcceleration(robot.model, data, fid,
                                                          pin.LOCAL_WORLD_ALIGNED).linear
    return pos, vel, acc


@pytest.fixture(scope="session")
def frame_kinematics() -> FrameKinematics:
    """``frame_kinematics(robot, motion)`` → world position, velocity and classical
    acceleration (LOCAL_WORLD_ALIGNED) of every foot, each (T, n_legs, 3)."""
    return _frame_kinematics


def _central_differences(robot: hexaleg.Robot, gait: hexaleg.GaitParams, t: np.ndarray,
                         columns: slice = slice(None)
                         ) -> tuple[hexaleg.Motion, list[tuple[float, float]]]:
    """The gait at ``t`` and, for h = 2 ms and 1 ms, the largest errors of its v and a (velocity
    columns ``columns``) against ``pin.difference(q(t−h), q(t+h)) / 2h`` and
    ``(v(t+h) − v(t−h)) / 2h``: second-order differences, so exact derivatives have errors
    falling ~4× from the first h to the second."""
    motion = sample_gait(robot, gait, t)
    errors = []
    for h in (2e-3, 1e-3):
        plus, minus = sample_gait(robot, gait, t + h), sample_gait(robot, gait, t - h)
        dq = np.array([pin.difference(robot.model, qm, qp)
                       for qm, qp in zip(minus.q, plus.q, strict=True)]) / (2 * h)
        dv = (plus.v - minus.v) / (2 * h)
        errors.append((float(np.abs(dq - motion.v)[:, columns].max()),
                       float(np.abs(dv - motion.a)[:, columns].max())))
    return motion, errors


@pytest.fixture(scope="session")
def central_differences() -> Callable[..., tuple[hexaleg.Motion, list[tuple[float, float]]]]:
    """``central_differences(robot, gait, t, columns=slice(None))`` → the gait at ``t`` and the
    errors ``[(e_v, e_a) at h = 2 ms, (e_v, e_a) at h = 1 ms]`` of its v and a against central
    differences of q and v (:func:`_central_differences`)."""
    return _central_differences


def _rotated(robot: hexaleg.Robot, angle: float) -> hexaleg.Robot:
    """The same robot with its body turned by ``angle`` about the base z axis inside the base
    frame (what a URDF facing another way looks like), its heading turned with it."""
    model = robot.model.copy()
    turn = pin.SE3(pin.rpy.rpyToMatrix(0.0, 0.0, angle), np.zeros(3))
    for jid in range(2, model.njoints):
        if model.parents[jid] == 1:
            model.jointPlacements[jid] = turn * model.jointPlacements[jid]
    for frame in model.frames:
        if frame.parentJoint == 1:
            frame.placement = turn * frame.placement
    model.inertias[1] = model.inertias[1].se3Action(turn)
    return dataclasses.replace(robot, model=model, data=model.createData(),
                               heading=turn.rotation @ robot.heading)


@pytest.fixture(scope="session")
def rotated() -> Callable[[hexaleg.Robot, float], hexaleg.Robot]:
    """``rotated(robot, angle)``: the robot's body turned by ``angle`` about z inside its base
    frame, heading included — the same robot, described facing another way."""
    return _rotated


QUAD4DOF = Path(__file__).resolve().parents[1] / "data" / "quad4dof.toml"
"""The four-joint test quadruped (redundant legs)."""


@pytest.fixture(scope="module")
def a1() -> hexaleg.Robot:
    """Unitree A1 from the registry: legs of three joints, not of the closed form."""
    return hexaleg.load("a1")


@pytest.fixture(scope="module")
def quad4dof() -> hexaleg.Robot:
    """The four-joint test quadruped."""
    return hexaleg.load(str(QUAD4DOF))
