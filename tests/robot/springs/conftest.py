"""Checks every spring law must pass: conservative (torque = −dU/dq), zero work over a cycle."""

from __future__ import annotations

import numpy as np
import pytest


def check_conservative(spring, kinks, lo=-1.5, hi=1.5, h=1e-6):
    """``spring.elastic_torque`` = −dU/dq by central differences at points at least 10 h from
    every kink or jump, and the work over a closed path (lo → hi → lo) is zero."""
    q = np.linspace(lo, hi, 3001)
    far = np.all(np.abs(q[:, None] - np.asarray(kinks, dtype=float)[None, :]) > 10 * h, axis=1)
    q = q[far]
    fd = -(spring.energy(q + h) - spring.energy(q - h)) / (2 * h)
    scale = 1.0 + np.abs(spring.elastic_torque(q)).max()
    np.testing.assert_allclose(spring.elastic_torque(q), fd, atol=1e-7 * scale)
    # Work of the spring on the joint along q(t) = lo → hi → lo equals −ΔU = 0 (exact potential):
    path = np.concatenate([np.linspace(lo, hi, 20001), np.linspace(hi, lo, 20001)[1:]])
    work = np.sum(spring.elastic_torque((path[1:] + path[:-1]) / 2) * np.diff(path))
    assert abs(work) < 1e-6 * scale
    # The potential is continuous across every kink and jump (a jump in U would not conserve).
    for k in kinks:
        assert abs(spring.energy(np.array(k + 1e-9)) - spring.energy(np.array(k - 1e-9))) < 1e-6


@pytest.fixture
def conservative():
    return check_conservative
