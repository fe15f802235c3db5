"""Default gaits sized to the robot (hexaleg.motion.scaling): the test hexapod scaled ×0.5 and ×2
keeps the default hexapod's Froude number and relative stride; set keys are kept; the period is
lengthened until every joint is within its URDF velocity limit."""

from __future__ import annotations

import dataclasses
import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.motion.params import GaitParams
from hexaleg.motion.sanity import speed_ratio
from hexaleg.motion.scaling import (
    REFERENCE_FROUDE,
    REFERENCE_HIP_HEIGHT,
    REFERENCE_RELATIVE_STRIDE,
    chosen_defaults,
    hip_height,
    robot_gait,
    sized_defaults,
)
from hexaleg.motion.stands import HOLDS
from hexaleg.robot.registry import description
from hexaleg.units import G

SPIDER = Path(__file__).resolve().parents[1] / "data" / "spider.toml"
XQUAD = SPIDER.parent / "xquad.toml"


def scaled_spider(where: Path, scale: float, *, velocity: float | None = None,
                  gait: str = "") -> str:
    """The test hexapod with every length ×scale (masses ×scale³, inertias ×scale⁵), optionally
    its joints' velocity limits replaced, and a ``[robot.gait]`` table; returns the TOML path."""
    tree = ET.parse(SPIDER.parent / "spider.urdf")
    lengths = {"origin": ("xyz",), "box": ("size",), "cylinder": ("radius", "length")}
    for tag, keys in lengths.items():
        for el in tree.getroot().iter(tag):
            for key in keys:
                if el.get(key) is not None:
                    el.set(key, " ".join(str(scale * float(v)) for v in el.get(key, "").split()))
    for el in tree.getroot().iter("mass"):
        el.set("value", str(scale ** 3 * float(el.get("value", ""))))
    for el in tree.getroot().iter("inertia"):
        for key, value in list(el.attrib.items()):
            el.set(key, str(scale ** 5 * float(value)))
    if velocity is not None:
        for el in tree.getroot().iter("limit"):
            el.set("velocity", str(velocity))
    where.mkdir(parents=True, exist_ok=True)
    tree.write(where / "spider.urdf")
    toml = SPIDER.read_text().replace("body_height = 0.08", f"body_height = {0.08 * scale}")
    (where / "spider.toml").write_text(toml + gait)
    return str(where / "spider.toml")


def froude(gait: GaitParams, h: float) -> float:
    return gait.velocity ** 2 / (G * h)


def test_the_reference_is_the_default_hexapod():
    robot = hexaleg.load("hexaleg")
    assert hip_height(robot, GaitParams()) == pytest.approx(REFERENCE_HIP_HEIGHT, rel=1e-6)
    assert robot_gait("hexaleg") == GaitParams()  # the reference is not sized
    assert REFERENCE_FROUDE == pytest.approx(0.06 ** 2 / (G * REFERENCE_HIP_HEIGHT))


@pytest.mark.parametrize("scale", [0.5, 2.0])
def test_a_scaled_robot_keeps_the_froude_number_and_relative_stride(tmp_path, scale):
    base, scaled = robot_gait(str(SPIDER)), robot_gait(
        scaled_spider(tmp_path, scale))
    robot = hexaleg.load(str(tmp_path / "spider.toml"))
    h = hip_height(robot, scaled)
    assert h == pytest.approx(0.08 * scale, rel=1e-6)  # hips at the base's height
    assert froude(scaled, h) == pytest.approx(REFERENCE_FROUDE, rel=1e-9)
    assert scaled.stride / h == pytest.approx(REFERENCE_RELATIVE_STRIDE, rel=1e-9)
    assert scaled.stride == pytest.approx(scale * base.stride, rel=1e-6)
    assert scaled.step_height == pytest.approx(scale * base.step_height, rel=1e-6)
    assert scaled.period == pytest.approx(math.sqrt(scale) * base.period, rel=1e-6)
    sized = sized_defaults(description(str(tmp_path / "spider.toml")), scaled)
    assert sized is not None and sized.stretch == 1.0 and sized.speed_ratio < 1.0
    note = sized.note()
    assert note is not None and "Alexander & Jayes 1983" in note and "lengthened" not in note


def test_set_parameters_are_never_overridden(tmp_path):
    path = scaled_spider(tmp_path, 2.0, velocity=0.5,
                         gait="[robot.gait]\nperiod = 0.7\nstep_height = 0.011\n")
    gait = robot_gait(path)
    assert gait.period == 0.7 and gait.step_height == 0.011  # slow joints: kept anyway
    assert gait.stride == pytest.approx(REFERENCE_RELATIVE_STRIDE * 0.16, rel=1e-6)
    sized = sized_defaults(description(path), gait)
    assert sized is not None and sized.keys == ("stride_length",)
    assert sized.note(overridden=["stride_length"]) is None  # a config file set it
    stride_set = robot_gait(scaled_spider(tmp_path / "s", 2.0,
                                                    gait="[robot.gait]\nstride_length = 0.05\n"))
    assert stride_set.stride == 0.05  # the period follows the Froude number from it
    assert froude(stride_set, 0.16) == pytest.approx(REFERENCE_FROUDE, rel=1e-6)


def test_the_period_is_lengthened_to_the_joints_speed_limits(tmp_path):
    """Joints limited to 1 rad/s: the similar gait would run them over; the chosen period brings
    every joint within its limit at full sampling, and the note says by how much."""
    path = scaled_spider(tmp_path, 1.0, velocity=1.0)
    gait = robot_gait(path)
    free = robot_gait(str(SPIDER))
    robot = hexaleg.load(path)
    sized = sized_defaults(description(path), gait)
    assert sized is not None and sized.stretch > 1.0 and sized.fastest in robot.joint_names
    assert gait.period == pytest.approx(free.period * sized.stretch, rel=1e-9)
    assert gait.stride == pytest.approx(free.stride, rel=1e-9)
    ratio, _ = speed_ratio(robot, hexaleg.gait(robot, gait).v)  # 1000 samples
    assert ratio <= 1.0
    before, _ = speed_ratio(robot, hexaleg.gait(
        robot, dataclasses.replace(gait, period=free.period, samples=200)).v)
    assert before > 1.0  # the unlengthened gait would exceed the limit
    assert sized.froude < REFERENCE_FROUDE
    assert f"lengthened x{sized.stretch:.3g}" in (sized.note() or "")
    data = sized.as_dict()
    assert data["period_stretch"]["value"] == sized.stretch and data["period"]["unit"] == "s"


def test_speed_ratio_is_the_fastest_joint_over_its_limit(spider):
    v = np.ones((3, spider.model.nv))
    ratio, joint = speed_ratio(spider, v)
    assert ratio == pytest.approx(1 / 6) and joint == spider.joint_names[0]


def test_docs_state_the_reference_and_the_spiders_line():
    """docs/robots.md's numbers are the module's, and its example line is the spider's."""
    page = (SPIDER.parents[2] / "docs" / "robots.md").read_text()
    assert f"{REFERENCE_HIP_HEIGHT:.4f} m above the ground" in page
    assert f"`{REFERENCE_RELATIVE_STRIDE:.3f} h`" in page
    assert f"`v² / (g h)` = {REFERENCE_FROUDE:.4f}" in page
    sized = sized_defaults(description(str(SPIDER)), robot_gait(str(SPIDER), sized=False))
    assert sized is not None and f"warning: {sized.note()}\n" in page


def test_a_missing_urdf_is_a_named_error_not_a_traceback(tmp_path):
    from hexaleg.errors import RobotModelError

    toml = tmp_path / "gone.toml"
    toml.write_text('[robot]\nname = "gone"\nurdf = "gone.urdf"\n[[robot.legs]]\nname = "LF"\n'
                    'joints = ["a"]\nfoot = "f"\n[[robot.legs]]\nname = "RF"\njoints = ["b"]\n'
                    'foot = "g"\n')
    with pytest.raises(RobotModelError, match=r"gone\.urdf"):
        robot_gait(str(toml))


@pytest.mark.slow
def test_centauros_defaults_are_shortened_to_a_swing_within_its_joint_limits():
    """Centauro (issue #55): at the similar step height (0.25 m) its front hips' pitch leaves
    their limits in swing, and a lower step leaves a hind hip's yaw out at the ends of the
    stride; no single parameter works, the two shortened together do (hexaleg.motion.reach),
    and the sized defaults take them: a gait whose every leg joint is within its limits.
    ~10 s of CPU (the robot's meshes and two to six gaits)."""
    run = hexaleg.Scenario.load(str(Path(__file__).parents[1] / "data" / "centauro.toml"))
    assert (run.gait.step_height, run.gait.stride_length) == (0.14, 0.29)
    motion = run.motion()
    robot = run.model
    for leg in robot.legs:
        q = motion.q[:, leg.q_index]
        assert (q >= robot.model.lowerPositionLimit[leg.q_index]).all()
        assert (q <= robot.model.upperPositionLimit[leg.q_index]).all()


def xquad_with(where: Path, velocity: float | None = None) -> str:
    """The X-configured test quadruped (tests/data/xquad), optionally its joints' velocity
    limits replaced; returns the TOML path."""
    tree = ET.parse(XQUAD.parent / "xquad.urdf")
    if velocity is not None:
        for el in tree.getroot().iter("limit"):
            el.set("velocity", str(velocity))
    where.mkdir(parents=True, exist_ok=True)
    tree.write(where / "xquad.urdf")
    (where / "xquad.toml").write_text(XQUAD.read_text())
    return str(where / "xquad.toml")


def stand_constants(robot: hexaleg.Robot, gait: GaitParams) -> float:
    """ω₀ T of the trot's stand on a diagonal, T = (1 − β) · period (a diagonal stands while
    the other swings), ω₀ = √(g/h), h the centre of mass over the feet (Kajita et al. 2001)."""
    motion = hexaleg.gait(robot, dataclasses.replace(gait, samples=200))
    assert int(motion.stance.sum(axis=1).min()) == 2
    com = pin.centerOfMass(robot.model, robot.model.createData(), motion.q[0])
    h = com[2] - motion.feet[0, motion.stance[0], 2].mean()
    return math.sqrt(G / h) * (1.0 - gait.duty_factor) * gait.period


def test_a_trots_default_period_keeps_its_stands_to_what_balance_holds():
    """The X-configured quadruped's similar trot (2.34 s) stands 5.4 time constants on a
    diagonal and fell closed loop (#54): the default period is shortened to the one whose stand
    lasts HOLDS of them (0.86 s), not shorter, its joints within their limits; docs/robots.md
    shows its line."""
    robot = hexaleg.load(str(XQUAD))
    similar = robot_gait(str(XQUAD), sized=False)
    gait = robot_gait(str(XQUAD))
    sized = sized_defaults(description(str(XQUAD)), similar)
    assert sized is not None and sized.stretch == 1.0 and sized.bound is None
    froude_period = sized.stride / math.sqrt(REFERENCE_FROUDE * G * sized.hip_height)
    assert froude_period == pytest.approx(2.34, abs=0.01)  # the similar trot that fell
    assert stand_constants(robot, dataclasses.replace(gait, period=froude_period)) > 5.0
    assert gait.period == pytest.approx(sized.period, rel=1e-12)
    assert gait.period == pytest.approx(0.86, abs=0.01)
    assert stand_constants(robot, gait) == pytest.approx(HOLDS, rel=1e-6)
    assert sized.pendulum == pytest.approx(gait.period / froude_period, rel=1e-12)
    assert gait.stride == pytest.approx(REFERENCE_RELATIVE_STRIDE * sized.hip_height, rel=1e-9)
    ratio, _ = speed_ratio(robot, hexaleg.gait(robot, gait).v)
    assert ratio <= 1.0
    note = sized.note() or ""
    assert f"period shortened x{sized.pendulum:.3g}" in note and "Kajita" in note
    assert "won" not in note
    assert f"warning: {note}\n" in (SPIDER.parents[2] / "docs" / "robots.md").read_text()
    assert sized.as_dict()["stand"] == {"value": sized.stand, "unit": "1"}


def test_where_the_speed_limits_forbid_the_pendulums_period_they_win_and_say_so(tmp_path):
    """Joints limited to 5 rad/s: the trot that stands HOLDS time constants would run them at
    about 7.6 rad/s; the period is shortened only to what the limits allow, and the note says
    the velocity limit won and how long the stands then are."""
    path = xquad_with(tmp_path, velocity=5.0)
    robot = hexaleg.load(path)
    gait = robot_gait(path)
    sized = sized_defaults(description(path), robot_gait(path, sized=False))
    assert sized is not None and sized.bound is not None and "velocity limit" in sized.bound
    assert 0.86 < gait.period < 2.34 and sized.pendulum < 1.0
    ratio, _ = speed_ratio(robot, hexaleg.gait(robot, gait).v)
    assert 0.9 < ratio <= 1.0  # at the limit: not longer than it needs
    assert sized.stand == pytest.approx(stand_constants(robot, gait), rel=1e-6)
    assert sized.stand > HOLDS
    assert f"{sized.bound} won" in (sized.note() or "")


def test_a_runs_own_stance_pattern_is_what_the_sizing_checks():
    """A crawl on the X quadruped (``[gait] pattern = "crawl"``): its stands are on three feet,
    so no pendulum bound shortens its period (the trot's 0.86 s ran its swings at 14-20 rad/s
    over the joints' 10 and its crawl out of friction): the sizing checks the run's pattern,
    and the run's warnings describe that sizing."""
    table = {"pattern": "crawl"}
    trot = robot_gait(str(XQUAD))
    crawl = robot_gait(str(XQUAD), table=table).updated(table)
    assert trot.period == pytest.approx(0.86, abs=0.01)
    assert crawl.period == pytest.approx(2.34, abs=0.01)
    robot = hexaleg.load(str(XQUAD))
    ratio, _ = speed_ratio(robot, hexaleg.gait(robot, crawl).v)
    assert ratio <= 1.0
    sized = chosen_defaults(description(str(XQUAD)), crawl)
    assert sized is not None and sized.period == crawl.period and sized.pendulum == 1.0
