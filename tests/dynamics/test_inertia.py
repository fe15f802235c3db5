"""Tests of hexaleg.dynamics.inertia: joint ranges and apparent inertias of a robot on a motion."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.dynamics.inertia import apparent_inertia, apparent_inertias, joint_range
from hexaleg.errors import UnknownNameError


def test_apparent_inertia_of_the_tibia_is_the_rod_about_its_end(robot, walk200):
    """The tibia moves only itself: J = I_c + m c² of the 120 mm, 45 g rod with CoM at 50 mm."""
    j = apparent_inertia(robot, walk200, "LF_tibia")
    assert j == pytest.approx(0.045 * 0.12**2 / 12 + 0.045 * 0.05**2, rel=1e-9)


def test_apparent_inertias_are_per_joint_in_column_order(robot, walk200):
    inertias = apparent_inertias(robot, walk200)
    assert inertias.shape == (robot.nj,)
    for joint in ("LF_coxa", "LF_femur", "RH_tibia"):
        assert inertias[robot.column(joint)] == apparent_inertia(robot, walk200, joint)
    # A joint moves everything distal to it: the femur carries the tibia too.
    assert apparent_inertia(robot, walk200, "LF_femur") > apparent_inertia(robot, walk200,
                                                                          "LF_tibia")


def test_joint_range_is_the_extremes_of_the_joint_over_the_motion(robot, walk200):
    q = walk200.q[:, 7 + robot.column("LM_femur")]
    lo, hi = joint_range(robot, walk200, "LM_femur")
    assert (lo, hi) == (q.min(), q.max()) and lo < hi
    assert isinstance(lo, float) and not np.isnan(hi)
    with pytest.raises(UnknownNameError):
        joint_range(robot, walk200, "LF_knee")
    with pytest.raises(UnknownNameError):
        apparent_inertia(robot, walk200, "LF_knee")
