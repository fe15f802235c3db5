"""Tests of hexaleg.motion.patterns and the named gaits: the conventional offsets and duty factors,
and for every pattern the invariants of the tripod — stance feet at rest in the world, the
expected fewest stance feet, a positive static margin where the pattern promises one,
Newton–Euler of the analysed forces and zero cyclic joint work — plus custom phases, any β and
the named errors of bad input."""

from __future__ import annotations

import dataclasses
from fractions import Fraction

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.motion.params import TRIPODS, GaitParams
from hexaleg.motion.patterns import PATTERNS, groups_of, leg_offsets, leg_places, pattern_offsets
from hexaleg.motion.scaling import robot_gait
from hexaleg.robot.registry import TROT

HEXAPOD = ("LF", "LM", "LH", "RF", "RM", "RH")
QUADRUPED = ("LF", "RF", "LH", "RH")
SAMPLES = 120


def _offsets(name: str, legs: tuple[str, ...]) -> dict[str, float]:
    return dict(zip(legs, pattern_offsets(name, legs).tolist(), strict=True))


def test_the_conventional_offsets_and_duty_factors():
    tripod = _offsets("tripod", HEXAPOD)
    assert {leg for leg, o in tripod.items() if o == 0.0} == set(TRIPODS[0])
    assert {leg for leg, o in tripod.items() if o == 0.5} == set(TRIPODS[1])
    # Ripple: each side a back-to-front wave a third of a cycle apart, the sides half apart.
    ripple = _offsets("ripple", HEXAPOD)
    assert ripple == pytest.approx({"LH": 0, "LM": 1 / 3, "LF": 2 / 3, "RH": 1 / 2,
                                    "RM": 5 / 6, "RF": 1 / 6})
    wave = _offsets("wave", HEXAPOD)
    assert wave == pytest.approx({"LH": 0, "LM": 1 / 6, "LF": 2 / 6, "RH": 3 / 6,
                                  "RM": 4 / 6, "RF": 5 / 6})
    # The crawl: lateral sequence LH → LF → RH → RF, each fore leg lifting as its hind leg lands.
    crawl = _offsets("crawl", QUADRUPED)
    assert sorted(crawl, key=crawl.__getitem__) == ["LH", "LF", "RH", "RF"]
    assert crawl == pytest.approx({"LH": 0.0, "LF": 0.2, "RH": 0.5, "RF": 0.7})
    trot = _offsets("trot", QUADRUPED)
    assert {leg for leg, o in trot.items() if o == 0.0} == set(TROT[0])
    pace = _offsets("pace", QUADRUPED)
    assert {leg for leg, o in pace.items() if o == 0.0} == {"LF", "LH"}
    betas = {name: p.duty_factor for name, p in PATTERNS.items()}
    assert betas == {"tripod": Fraction(1, 2), "ripple": Fraction(2, 3), "wave": Fraction(5, 6),
                     "crawl": Fraction(4, 5), "trot": Fraction(1, 2), "pace": Fraction(1, 2)}
    assert GaitParams(pattern="wave").duty_factor == pytest.approx(5 / 6)


@pytest.mark.parametrize("name", list(PATTERNS))
def test_each_pattern_stands_on_its_fewest_feet_at_its_own_duty_factor(name):
    """Counted exactly on a fine grid of phases: the pattern's promise, no rounding."""
    p = PATTERNS[name]
    legs = HEXAPOD if p.legs_per_side == 3 else QUADRUPED
    offsets = pattern_offsets(name, legs)
    phase = (np.arange(6000)[:, None] / 6000 - offsets[None, :]) % 1.0
    counts = (phase < float(p.duty_factor) - 1e-9).sum(axis=1)
    assert counts.min() == p.min_stance_feet


def test_leg_places_from_names():
    assert leg_places(["LF", "RH", "LM", "L3"]) is not None
    assert leg_places(["LF", "LM", "LH"]) == [("L", 0), ("L", 1), ("L", 2)]
    assert leg_places(["L1", "L2", "R1", "R2"]) == [("L", 0), ("L", 1), ("R", 0), ("R", 1)]
    assert leg_places(["front_left"]) is None
    assert groups_of(HEXAPOD, pattern_offsets("tripod", HEXAPOD)) == (
        ("LF", "LH", "RM"), ("LM", "RF", "RH"))


def test_tripod_pattern_and_its_phases_are_the_default_gait(robot, walk200):
    """The named tripod and its offsets given as phases make the default gait bit for bit."""
    named = hexaleg.gait(robot, GaitParams(pattern="tripod", samples=200))
    phases = tuple(pattern_offsets("tripod", robot.leg_names))
    custom = hexaleg.gait(robot, GaitParams(phases=phases, samples=200))
    for m in (named, custom):
        for field in ("q", "v", "a", "stance", "feet"):
            assert np.array_equal(getattr(m, field), getattr(walk200, field)), field
    assert named.info["pattern"] == "tripod" and named.info["groups"] == (
        ("LF", "LH", "RM"), ("LM", "RF", "RH"))
    assert hexaleg.gait(robot, GaitParams(pattern="tripod", samples=200)).info == \
        named.info


@pytest.fixture(scope="module")
def solo() -> hexaleg.Robot:
    return hexaleg.load("solo12")


def _pattern_case(name: str, robot: hexaleg.Robot, solo: hexaleg.Robot
                  ) -> tuple[hexaleg.Robot, GaitParams, hexaleg.ContactParams]:
    """The robot, gait and contact a pattern is tested with: the hexapod for the hexapod
    patterns, Solo-12 (its own period, stride, step height) for the quadruped ones; the crawl
    slowly (2 s), the pace on grippier ground (its LIP sway crosses 0.15 m from a 0.19 m height:
    μ ≈ 0.8 at the switches)."""
    if PATTERNS[name].legs_per_side == 3:
        return robot, GaitParams(pattern=name, samples=SAMPLES), hexaleg.ContactParams()
    table: dict[str, object] = {"pattern": name, "samples": SAMPLES}
    if name == "crawl":
        table["period"] = 2.0
    gait = robot_gait("solo12").updated(table)
    return solo, gait, hexaleg.ContactParams(mu=1.0 if name == "pace" else 0.6)


@pytest.mark.parametrize("name", list(PATTERNS))
def test_every_pattern_keeps_the_invariants_of_the_tripod(name, robot, solo, frame_kinematics):
    bot, gait, contact = _pattern_case(name, robot, solo)
    pattern = PATTERNS[name]
    assert gait.duty_factor == float(pattern.duty_factor)
    motion = hexaleg.gait(bot, gait)
    _, vel, acc = frame_kinematics(bot, motion)
    assert np.abs(vel[motion.stance]).max() <= 1e-9
    assert np.abs(acc[motion.stance]).max() <= 1e-9
    assert motion.info["min_stance_feet"] == pattern.min_stance_feet
    if pattern.static:
        assert motion.info["static_margin"] > 0.01
    else:
        assert motion.info["static_margin"] is None and motion.info["balance"]["mode"] == "sway"
    analysis = hexaleg.prepare(bot, motion, contact=contact).evaluate()
    model, data = bot.model, bot.model.createData()
    rhs = np.empty((motion.n_samples, 3))
    for k in range(motion.n_samples):
        pin.centerOfMass(model, data, motion.q[k], motion.v[k], motion.a[k])
        rhs[k] = bot.mass * (data.acom[0] - model.gravity.linear)
    assert np.abs(analysis.forces.sum(axis=1) - rhs).max() <= 1e-8 * np.abs(rhs).max()
    p = analysis.tau_total * analysis.qdot
    assert abs(p.sum()) <= 1e-6 * np.abs(p).sum()
    assert np.all(analysis.forces[..., 2][motion.stance] >= -1e-9)


def test_any_duty_factor_in_the_open_interval(robot):
    """β = 0.3 flies (no feet at some samples); β = 0.95 stands on five or six."""
    fly = hexaleg.gait(robot, GaitParams(pattern="tripod", duty_factor=0.3, samples=100))
    assert fly.info["min_stance_feet"] == 0 and fly.info["balance"] == {"mode": "none"}
    assert np.isclose(fly.stance.mean(), 0.3)
    slow = hexaleg.gait(robot, GaitParams(pattern="wave", duty_factor=0.95, samples=120))
    assert slow.info["min_stance_feet"] == 5 and np.isclose(slow.stance.mean(), 0.95)


def test_updating_the_pattern_takes_its_own_duty_factor():
    solo = robot_gait("solo12")
    assert solo.duty_factor == 0.6 and solo.groups == TROT
    crawl = solo.updated({"pattern": "crawl"})
    assert crawl.pattern == "crawl" and crawl.duty_factor == pytest.approx(0.8)
    assert crawl.period == solo.period  # the robot's other keys stay
    assert solo.updated({"pattern": "crawl", "duty_factor": 0.9}).duty_factor == 0.9
    back = crawl.updated({"groups": [["LF", "RH"], ["RF", "LH"]]})
    assert back.pattern is None and back.duty_factor == pytest.approx(0.8)
    custom = crawl.updated({"phases": [0.0, 0.5, 0.5, 0.0]})
    assert custom.pattern is None and custom.phases == (0.0, 0.5, 0.5, 0.0)
    assert custom.duty_factor == 0.5
    assert GaitParams.from_toml({"pattern": "ripple"}).duty_factor == pytest.approx(2 / 3)


def test_unknown_pattern_lists_the_patterns():
    with pytest.raises(UnknownNameError) as err:
        GaitParams(pattern="gallop")
    message = str(err.value)
    assert "'gallop'" in message and all(name in message for name in PATTERNS)


@pytest.mark.parametrize(("kwargs", "name", "allowed"), [
    ({"duty_factor": 0.0}, "duty_factor", r"β in \(0, 1\)"),
    ({"duty_factor": 1.0}, "duty_factor", r"β in \(0, 1\)"),
    ({"duty_factor": -0.2}, "duty_factor", r"β in \(0, 1\)"),
    ({"phases": (0.0, 1.0)}, "phases", r"\[0, 1\)"),
    ({"phases": "0.5"}, "phases", "one touch-down offset per leg"),
    ({"phases": (0.0, 0.5), "pattern": "trot"}, "phases", "give one of the two"),
])
def test_bad_timing_is_named(kwargs, name, allowed):
    with pytest.raises(InvalidParameterError, match=rf"invalid {name} = .*{allowed}"):
        GaitParams(**kwargs)


def test_phases_of_the_wrong_length_and_patterns_for_other_legs_are_named(robot):
    with pytest.raises(InvalidParameterError, match=r"invalid phases = .*6 touch-down offsets.*"
                       r"LF, LM, LH, RF, RM, RH"):
        hexaleg.gait(robot, GaitParams(phases=(0.0, 0.5, 0.5, 0.0), samples=40))
    with pytest.raises(InvalidParameterError, match=r"invalid pattern = 'trot'.*3 \+ 3 legs: "
                       r"tripod, ripple, wave"):
        hexaleg.gait(robot, GaitParams(pattern="trot", samples=40))
    with pytest.raises(InvalidParameterError, match="legs named by side and place"):
        leg_offsets(["front", "back", "left"], "tripod", None, ())
    # The groups' errors are unchanged.
    with pytest.raises(UnknownNameError, match="'XX'"):
        leg_offsets(list(HEXAPOD), None, None, (("LF", "XX"),))


def test_explicit_balance_modes_that_do_not_apply_are_named(robot):
    with pytest.raises(InvalidParameterError, match=r"invalid balance = 'sway'.*stands on 3"):
        hexaleg.gait(robot, GaitParams(balance="sway", samples=40))
    with pytest.raises(InvalidParameterError, match=r"invalid balance = 'shift'.*stands on 0"):
        hexaleg.gait(robot, GaitParams(balance="shift", duty_factor=0.3, samples=40))
    assert dataclasses.replace(GaitParams(), balance="none").balance == "none"
