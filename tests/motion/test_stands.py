"""A gait's longest stand on its fewest point feet (hexaleg.motion.stands), against the trot's
timing and the linear inverted pendulum's ω₀ = √(g/h) computed here from the centre of mass and
the feet (Kajita et al., IROS 2001)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.motion.scaling import robot_gait
from hexaleg.motion.stands import HOLDS, longest_stand
from hexaleg.robot.soles import Sole
from hexaleg.units import G

XQUAD = str(Path(__file__).resolve().parents[1] / "data" / "xquad.toml")


def test_a_trots_stand_is_half_its_period_on_a_diagonal(robot, walk200):
    xquad = hexaleg.load(XQUAD)
    gait = dataclasses.replace(robot_gait(XQUAD), period=1.3, samples=100)
    motion = hexaleg.gait(xquad, gait)
    stand = longest_stand(xquad, motion)
    assert stand is not None and stand.feet == 2 and stand.period == 1.3
    assert stand.duration == pytest.approx(gait.duty_factor * 1.3, abs=motion.dt)  # β = 0.5
    data = xquad.model.createData()
    com = pin.centerOfMass(xquad.model, data, motion.q[0])
    h = com[2] - motion.feet[0, motion.stance[0], 2].mean()
    assert 0.4 < h < 0.6  # the hips stand 0.5 m above the feet
    assert stand.omega == pytest.approx(np.sqrt(G / h), rel=1e-12)
    assert stand.constants == pytest.approx(stand.omega * stand.duration, rel=1e-12)
    assert stand.growth == pytest.approx(np.exp(stand.constants), rel=1e-12)
    scaled = stand.holding_period / stand.period
    assert stand.constants * scaled == pytest.approx(HOLDS, rel=1e-12)
    assert longest_stand(robot, walk200) is None  # three feet always
    xquad.soles = {leg.name: Sole(0.1, 0.05) for leg in xquad.legs}
    assert longest_stand(xquad, motion) is None  # the centre of pressure moves within soles
