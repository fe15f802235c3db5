"""Tests of hexaleg.paper.crosscheck: eq. 13 against Pinocchio's RNEA on the robot."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.paper.crosscheck import pinocchio_femur_torque
from hexaleg.paper.joint import PaperJoint


@pytest.mark.parametrize("posture", ["hanging", "upright"])
def test_pinocchio_femur_matches_eq13(posture):
    j = PaperJoint(posture=posture)
    t = j.times(64)
    for g in (False, True):
        ref = j.baseline_torque(t, gravity=g)
        tau = pinocchio_femur_torque(t, j, gravity=g)
        assert np.max(np.abs(tau - ref)) <= 1e-9 * np.max(np.abs(ref))
