"""Tests of hexaleg.motion.limits: sample counts and joint limits are checked with errors that name
the parameter (or joint), the value and what is allowed."""

from __future__ import annotations

import numpy as np
import pytest

import hexaleg
from hexaleg.checks import MEMORY_BUDGET
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.limits import (
    MAX_SAMPLES,
    MIN_SAMPLES,
    SAMPLE_BYTES,
    check_joint_limits,
    check_samples,
)


def test_check_samples():
    assert check_samples(np.int64(MIN_SAMPLES)) == MIN_SAMPLES
    assert type(check_samples(np.int64(40))) is int
    for bad in (MIN_SAMPLES - 1, 100.0, True):
        with pytest.raises(InvalidParameterError, match=rf"samples = .*in \[{MIN_SAMPLES}, "):
            check_samples(bad)
    assert check_samples(MAX_SAMPLES) == MAX_SAMPLES
    with pytest.raises(InvalidParameterError, match=rf"samples = {MAX_SAMPLES + 1}; .*"
                                                    r"memory budget of 2 GiB.*fewer samples"):
        check_samples(MAX_SAMPLES + 1)
    assert MAX_SAMPLES * SAMPLE_BYTES <= MEMORY_BUDGET < (MAX_SAMPLES + 1) * SAMPLE_BYTES


def test_check_joint_limits_names_joint_angle_and_time(robot):
    q = np.tile(robot.pose("stand"), (3, 1))
    t = np.array([0.0, 0.1, 0.2])
    check_joint_limits(robot, q, t)
    col = robot.column("LF_femur")
    q[2, 7 + col] = robot.model.upperPositionLimit[7 + col] + 0.1
    with pytest.raises(InvalidParameterError, match=r"joint LF_femur = .* rad at t = 0\.2 s"):
        check_joint_limits(robot, q, t)


def test_a_sample_costs_less_memory_than_its_bound(robot):
    """SAMPLE_BYTES (the bound behind MAX_SAMPLES) covers what one sample really costs through
    gait + prepare + evaluate: the tracemalloc peak's growth from 200 to 600 samples, per sample
    (18–20 kB on the 24-DoF hexapod)."""
    import tracemalloc

    from hexaleg.dynamics.prepare import prepare
    from hexaleg.motion.limits import SAMPLE_BYTES

    def peak(samples: int) -> int:
        tracemalloc.start()
        try:
            motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=samples))
            prepare(robot, motion).evaluate(None)
            return tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()

    per_sample = (peak(600) - peak(200)) / 400
    assert 4 * 1024 < per_sample < SAMPLE_BYTES, per_sample
