"""Tests of hexaleg.sweep.dead_zones: a sweep whose dead zone holds a joint's whole range
is refused by name before any work; narrower dead zones pass."""

from __future__ import annotations

import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.sweep.dead_zones import check_dead_zones
from hexaleg.sweep.runner import run_sweep
from hexaleg.sweep.spec import SweepSpec


def check(robot, springs):
    spec = SweepSpec(gait={"samples": 40}, springs=springs)
    check_dead_zones(spec, robot, spec.groups(robot))


def test_a_theta_k_wider_than_the_joint_range_is_refused_before_any_work(robot, tmp_path):
    # the femur's URDF range is ±150° = 5.236 rad wide
    spec = SweepSpec(gait={"samples": 40}, springs={"femur": {"k": 1.0, "theta_k": (0.1, 6.0)}})
    with pytest.raises(InvalidParameterError, match=r"springs\.femur dead zone = '\[-6, 6\] "
                                                    r"rad \(theta_k\)'.*LF_femur, 5\.236 rad"):
        run_sweep(spec, tmp_path / "out", executor="serial")
    assert not (tmp_path / "out").exists()


def test_an_asymmetric_dead_zone_is_refused_only_when_both_sides_hold_the_range(robot):
    with pytest.raises(InvalidParameterError, match=r"theta_minus/theta_plus"):
        check(robot, {"tibia": {"k": 1.0, "theta_minus": (-6.0, -0.1), "theta_plus": 5.5}})
    check(robot, {"tibia": {"k": 1.0, "theta_minus": -0.1, "theta_plus": 6.0}})  # engages below


def test_engaging_dead_zones_pass(robot):
    check(robot, {"coxa": {"k": 1.0, "theta_k": (0.01, 5.0)}})  # 5 < 5.236: may engage
    check(robot, {"coxa": {"k": 1.0, "dead_zone": 0.5}})  # a fraction of the motion: engages
