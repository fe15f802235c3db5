"""Fixtures of the robot tests."""

from __future__ import annotations

import pytest


@pytest.fixture(scope="session")
def upstream_placeholders() -> dict[str, set[str]]:
    """Registered robot → the placeholder-limit checks its upstream URDF fails
    (:func:`hexaleg.robot.sanity.limit_findings`): example-robot-data's Solo-12 writes ±10 rad,
    1000 N·m and 1000 rad/s on every joint, both ANYmals ±3π rad ranges."""
    return {"solo12": {"joint_range", "joint_speed_limit", "joint_torque_limit"},
            "anymal": {"joint_range"}, "anymal_c": {"joint_range"}}
