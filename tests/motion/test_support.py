"""Tests of hexaleg.motion.support: the CoM's static margin inside the support polygon, against
an independent triangle formula and the tripod's geometry (inradius)."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest

from hexaleg.motion.legged import tripod_gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.support import static_margins, support_margin


def _inside_margin(points: np.ndarray, c: np.ndarray) -> float:
    """Signed distance of c inside the triangle ``points`` (3, 2) (independent check)."""
    a, b, d = points
    if (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]) < 0:
        b, d = d, b
    out = []
    for p, q in ((a, b), (b, d), (d, a)):
        e = q - p
        out.append((e[0] * (c[1] - p[1]) - e[1] * (c[0] - p[0])) / np.linalg.norm(e))
    return min(out)


def test_com_stays_inside_each_tripod_and_margin_is_reported(robot, walk):
    data = robot.model.createData()
    margins = []
    for k in range(0, walk.n_samples, 10):
        com = pin.centerOfMass(robot.model, data, walk.q[k])
        margins.append(_inside_margin(walk.feet[k, walk.stance[k], :2], com[:2]))
    assert min(margins) > 0.05
    assert walk.info["static_margin"] == pytest.approx(min(margins), abs=1e-6)
    # The worst instant is a contact switch, the CoM β·stride/2 = 0.015 m from mid-stance: the
    # inradius R/2 of the equilateral tripod less 0.015·cos 30° towards a slanted edge.
    assert walk.info["static_margin_t"] in (0.0, 0.5)
    radius = walk.info["foot_radius"]
    assert walk.info["static_margin"] == pytest.approx(
        radius / 2 - 0.5 * 0.06 / 2 * math.cos(math.radians(30)), rel=1e-4)


def test_in_place_margin_is_the_inradius_of_the_tripod(robot):
    """Stride 0: the CoM stays on the axis of symmetry; an equilateral tripod of circumradius R
    has inradius R/2."""
    motion = tripod_gait(robot, GaitParams(stride_length=0.0, samples=100))
    assert motion.info["static_margin"] == pytest.approx(motion.info["foot_radius"] / 2, rel=1e-6)
    assert np.allclose(motion.q[:, :3], motion.q[0, :3])


def test_support_margin_of_a_square_and_degenerate_polygons():
    """Inside: the distance to the nearest edge; outside: minus the distance to the edge line;
    fewer than three points or collinear points: no polygon (−inf)."""
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]])
    assert support_margin(square, np.array([0.5, 0.5])) == pytest.approx(0.5)
    assert support_margin(square, np.array([0.2, 0.6])) == pytest.approx(0.2)
    assert support_margin(square[::-1], np.array([1.5, 0.5])) == pytest.approx(-0.5)
    assert support_margin(square[:2], np.array([0.5, 0.0])) == -math.inf
    line = np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])
    assert support_margin(line, np.array([1.0, 1.0])) == -math.inf


def test_static_margins_are_minus_infinity_below_three_feet(robot, walk):
    """Per sample, the gait's margins; a sample with two stance feet has none."""
    margins = static_margins(robot, walk.q, walk.feet, walk.stance)
    assert margins.min() == walk.info["static_margin"]
    assert walk.t[np.argmin(margins)] == walk.info["static_margin_t"]
    two = walk.stance[:3].copy()
    two[:, np.flatnonzero(two[0])[0]] = False
    assert np.all(static_margins(robot, walk.q[:3], walk.feet[:3], two) == -math.inf)
