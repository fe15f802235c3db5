"""Tests of hexaleg.motion.shift: statically stable crawls. The body shift keeps the CoM inside
every support polygon with the margin asked for, is smooth with exact derivatives (central
differences), leaves the stance feet at rest, makes the crawl's force program feasible where the
unshifted crawl's is not, and a margin the gait cannot keep is named before any force program
runs."""

from __future__ import annotations

import dataclasses

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.errors import InfeasibleForcesError, StaticMarginError
from hexaleg.motion.params import GaitParams
from hexaleg.motion.scaling import robot_gait
from hexaleg.motion.shift import required_margin
from hexaleg.motion.support import polygon_edges, static_margins, support_margin, switch_margin

SAMPLES = 100


@pytest.fixture(scope="module")
def solo() -> hexaleg.Robot:
    return hexaleg.load("solo12")


@pytest.fixture(scope="module")
def crawl_params() -> GaitParams:
    return robot_gait("solo12").updated({"pattern": "crawl", "period": 2.0,
                                                   "samples": SAMPLES})


@pytest.fixture(scope="module")
def crawl(solo, crawl_params) -> hexaleg.Motion:
    return hexaleg.gait(solo, crawl_params)


def test_polygon_edges_are_inward_half_planes():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]])
    normal, b = polygon_edges(square)
    assert len(b) == 4 and np.allclose(np.linalg.norm(normal, axis=1), 1.0)
    rng = np.random.default_rng(3)
    for c in rng.uniform(-0.5, 1.5, size=(20, 2)):
        assert (normal @ c - b).min() == pytest.approx(support_margin(square, c), abs=1e-12)
    assert len(polygon_edges(square[:2])[1]) == 0


@pytest.mark.parametrize(("name", "margin"), [("hexaleg", 0.0189), ("solo12", 0.0258)])
def test_the_default_margins_of_the_registry_gaits(name, margin):
    """MARGIN_FRACTION's docstring: 10 % of the nearest nominal foothold's distance."""
    robot, gait = hexaleg.load(name), robot_gait(name)
    nominal = hexaleg.motion.body.nominal_footholds(robot, gait)
    assert required_margin(robot, gait, nominal) == pytest.approx(margin, abs=5e-5)


def test_the_shifted_crawl_keeps_the_margin_at_every_sample(solo, crawl, crawl_params):
    target = required_margin(solo, crawl_params, hexaleg.motion.body.nominal_footholds(
        solo, crawl_params))
    footholds = hexaleg.motion.body.nominal_footholds(solo, crawl_params)
    assert target == pytest.approx(0.1 * np.linalg.norm(footholds[:, :2], axis=1).min())
    balance = crawl.info["balance"]
    assert balance["mode"] == "shift" and balance["target"] == target
    margins = static_margins(solo, crawl.q, crawl.feet, crawl.stance)
    assert margins.min() >= target and crawl.info["static_margin"] == pytest.approx(margins.min())
    assert switch_margin(solo, crawl) >= target and balance["margin"] >= target
    assert crawl.info["min_stance_feet"] == 3
    # Without the shift the CoM crosses the diagonals: no margin to speak of.
    rigid = hexaleg.gait(solo, dataclasses.replace(crawl_params, balance="none"))
    assert rigid.info["static_margin"] < 0.2 * target
    assert 0.02 < balance["amplitude"] < 0.15


def test_the_shift_is_smooth_with_exact_derivatives(solo, crawl_params, frame_kinematics,
                                                     central_differences):
    """v ≈ pin.difference(q(t−h), q(t+h)) / 2h, a ≈ (v(t+h) − v(t−h)) / 2h at second order,
    off the grid too (the shift is a trigonometric polynomial), stance feet at rest."""
    t = np.linspace(0.0, crawl_params.period, 40, endpoint=False) + 0.013
    motion, errors = central_differences(solo, crawl_params, t, slice(0, 6))
    (ev1, ea1), (ev2, ea2) = errors
    assert 3.5 < ev1 / ev2 < 4.5 and 3.5 < ea1 / ea2 < 4.5
    assert np.abs(motion.v[:, :2]).max() > 0.04  # the base does move sideways and forward
    _, vel, acc = frame_kinematics(solo, motion)
    assert np.abs(vel[motion.stance]).max() <= 1e-9 and np.abs(acc[motion.stance]).max() <= 1e-9


def test_the_shift_makes_the_crawls_forces_feasible(solo, crawl, crawl_params):
    """The unshifted crawl is the issue's "PrimalInfeasible"; the shifted one has forces."""
    rigid = hexaleg.gait(solo, dataclasses.replace(crawl_params, balance="none"))
    with pytest.raises(InfeasibleForcesError):
        hexaleg.prepare(solo, rigid).evaluate()
    analysis = hexaleg.prepare(solo, crawl).evaluate()
    assert np.all(analysis.forces[..., 2][crawl.stance] > 0)


def test_a_user_margin_is_kept_and_one_too_large_is_named_before_any_forces(solo, crawl_params):
    wide = hexaleg.gait(solo, dataclasses.replace(crawl_params, min_static_margin=0.035))
    assert wide.info["static_margin"] >= 0.035
    with pytest.raises(StaticMarginError, match=r"invalid min_static_margin = 0\.2; allowed: ≤ "
                       r"[\d.]+ m, the largest static margin.*raise duty_factor") as err:
        hexaleg.gait(solo, dataclasses.replace(crawl_params, min_static_margin=0.2))
    assert 0.035 <= err.value.largest < 0.2
    # The wave gait at β₀ = ¾ (each fore leg lifting as its hind leg lands, LH LF RH RF a
    # quarter apart) hands one support triangle to the next on their shared diagonal: no
    # positive margin at all.
    quarter = dataclasses.replace(crawl_params, pattern=None, phases=(0.25, 0.75, 0.0, 0.5),
                                  duty_factor=0.75)
    assert solo.leg_names == ("LF", "RF", "LH", "RH")
    with pytest.raises(StaticMarginError) as tight:
        hexaleg.gait(solo, quarter)
    assert tight.value.largest < 1e-6


def test_a_gait_with_margin_to_spare_is_not_shifted(robot, walk200):
    """The tripod's margin across its switches (0.0813 m: the CoM moves 0.3 mm a sample; 0.0815 m
    per sample) is above the default target: the gait is untouched. Asked for a little more,
    it shifts; for more than 0.0815 m, it says how much it can keep."""
    assert walk200.info["balance"] == {"mode": "none"}
    assert walk200.info["static_margin"] == pytest.approx(0.0815, abs=1e-4)
    assert switch_margin(robot, walk200) == pytest.approx(0.0813, abs=1e-4)
    assert switch_margin(robot, walk200) <= walk200.info["static_margin"]
    shifted = hexaleg.gait(robot, GaitParams(samples=200, min_static_margin=0.0813))
    assert shifted.info["balance"]["mode"] == "shift"
    assert switch_margin(robot, shifted) >= 0.0813
    with pytest.raises(StaticMarginError, match=r"≤ 0\.0814\d* m"):
        hexaleg.gait(robot, GaitParams(samples=200, min_static_margin=0.084))


def test_the_shift_keeps_the_pendulums_zero_moment_point_inside_too(solo, crawl_params):
    """z = c − (h/g) c̈ (linear inverted pendulum, h the CoM's height above the stance feet):
    the shift's acceleration does not push it out of the support polygons — at 0.8 s a cycle,
    where a shift that kept only the CoM inside would leave the ZMP 4 mm from an edge."""
    crawl = hexaleg.gait(solo, dataclasses.replace(crawl_params, period=0.8))
    data = solo.model.createData()
    com, acc = [], []
    for k in range(crawl.n_samples):
        pin.centerOfMass(solo.model, data, crawl.q[k], crawl.v[k], crawl.a[k])
        com.append(data.com[0].copy())
        acc.append(data.acom[0].copy())
    com, acc = np.array(com), np.array(acc)
    feet_z = np.array([f[s, 2].mean() for f, s in zip(crawl.feet, crawl.stance, strict=True)])
    lever = float(np.mean(com[:, 2] - feet_z)) / 9.81
    zmp = com[:, :2] - lever * acc[:, :2]
    margins = [support_margin(crawl.feet[k, crawl.stance[k], :2], zmp[k])
               for k in range(crawl.n_samples)]
    assert min(margins) > 0.95 * crawl.info["balance"]["target"]
    assert np.abs(acc[:, :2]).max() > 0.05  # the shift does accelerate the body


def test_a_margin_lost_to_the_slope_names_the_slope(robot):
    """Too steep a slope used to be a min_static_margin error that did not name the slope."""
    with pytest.raises(StaticMarginError, match=r"min_static_margin.*the ground is inclined "
                                                r"\(slope = 1\.047 rad \(60°\)\)"):
        hexaleg.gait(robot, GaitParams(samples=100, slope=np.radians(60.0)))
