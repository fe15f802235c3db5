"""Tests of the fold into the sphere and back with the springs to buy (hexaleg.design.fold).

Invariants: the joints' net work folding out is the rise of potential energy m g Δz_com and
folding back its fall; a conservative spring moves the motors' net work by exactly its stored
energy's change, which is the opposite way back (zero out and back). The break-even distance and
the mission saving are checked against their formulas at their limits.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pinocchio as pin
import pytest

from hexaleg.design.fold import Fold, FoldWay, Mission, fold, reversed_motion
from hexaleg.dynamics.prepare import prepare
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.motion.transform import transform_motion
from hexaleg.robot.springs import OneSidedSpring, SpringSet


@pytest.fixture(scope="module")
def springs(robot):
    """A one-sided spring on every femur, engaged over the whole fold (as the design's are)."""
    return SpringSet({j: OneSidedSpring(stiffness=0.02, contact=-1.0, side="above",
                                        preload=0.03)
                      for j in robot.joint_classes["femur"]})


def test_the_way_back_is_the_way_out_reversed(robot):
    out = transform_motion(robot)
    back = reversed_motion(out)
    assert np.array_equal(back.q[0], out.q[-1]) and np.array_equal(back.q[-1], out.q[0])
    assert np.array_equal(back.v, -out.v[::-1]) and np.array_equal(back.a, out.a[::-1])
    assert np.array_equal(back.supported, out.supported[::-1]) and not back.periodic
    # the reversed samples are a motion: v is the derivative of q (central differences)
    dq = np.diff(back.q[:, 7:], axis=0) / np.diff(back.t)[:, None]
    mid = 0.5 * (back.v[1:, 6:] + back.v[:-1, 6:])
    assert np.abs(dq - mid).max() < 1e-3 * np.abs(back.v).max()


def test_net_work_is_the_potential_energy_both_ways_and_a_spring_gives_back(robot, springs):
    out = transform_motion(robot)
    data = robot.model.createData()
    z0, z1 = (pin.centerOfMass(robot.model, data, out.q[k])[2] for k in (0, -1))
    rise = robot.mass * float(np.linalg.norm(robot.model.gravity.linear)) * (z1 - z0)
    works = {}
    for name, motion in (("out", out), ("back", reversed_motion(out))):
        a = prepare(robot, motion).evaluate(springs, "joule")
        base = a.baseline["total"]["net_work"]
        works[name] = base
        expected = rise if name == "out" else -rise
        assert base == pytest.approx(expected, rel=2e-3, abs=1e-4)
        # a conservative spring: motor net work with it = without it + its stored energy's rise
        stored = a.spring_energy.sum(axis=1)
        assert a.metrics["total"]["net_work"] - base == pytest.approx(
            stored[-1] - stored[0], rel=1e-3, abs=1e-5)
    assert works["out"] == pytest.approx(-works["back"], rel=2e-3)


def test_fold_both_ways_with_and_without_springs(robot, springs):
    f = fold(robot, robot_motor(robot), default_contact(), springs, (20.0, 25.0), 10.0)
    assert f is not None and [w.label for w in f.ways] == ["stand → sphere", "sphere → stand"]
    for w in f.ways:
        assert w.error == "" and w.electrical is not None and w.baseline is not None
        assert 0 < w.torque_share < 1 and 0 < w.baseline_share < 1
    out_base = f.ways[0].baseline
    assert out_base == pytest.approx(0.569, abs=0.01)  # the report's stand → sphere baseline
    totals = f.totals()
    assert totals is not None and f.extra == pytest.approx(totals[0] - totals[1])
    data = f.table()
    json.dumps(data)  # every number a plain float
    assert data["break_even"]["unit"] == "m" and data["mission"]["saving"]["unit"] == "%"


def robot_motor(robot):
    from hexaleg.robot.catalogue import motor

    return motor("AX-18A")


def default_contact():
    from hexaleg.dynamics.contact import ContactParams

    return ContactParams()


def _fold(extra_out: float, extra_back: float, walking=(20.0, 25.0), metres=None) -> Fold:
    ways = (FoldWay("stand → sphere", 2.0, 0.5 + extra_out, 0.5, 0.1, 0.1),
            FoldWay("sphere → stand", 2.0, 0.4 + extra_back, 0.4, 0.1, 0.1))
    return Fold(ways=ways, walking=walking, metres_per_fold=metres)


def test_break_even_is_the_extra_fold_energy_over_the_walking_saving():
    f = _fold(1.2, 0.3)  # 1.5 J more; walking saves 5 J/m
    assert f.extra == pytest.approx(1.5) and f.break_even == pytest.approx(0.3)
    assert "pay for a fold after 0.30 m of walking" in f.line()
    cheaper = _fold(-0.1, -0.05)
    assert cheaper.break_even == 0.0 and "cheaper too" in cheaper.line()
    assert _fold(1.0, 0.0, walking=(25.0, 25.0)).break_even is None  # nothing saved walking
    stuck = Fold(ways=(FoldWay("stand → sphere", 2.0, None, 0.5, None, 0.1, "TorqueLimitError"),
                       FoldWay("sphere → stand", 2.0, 0.4, 0.4, 0.1, 0.1)),
                 walking=(20.0, 25.0))
    assert stuck.extra is None and stuck.break_even is None
    assert "not within the servos' torque with the springs" in stuck.line()


def test_the_mission_saving_runs_from_the_folds_to_the_walkings():
    f = _fold(1.2, 0.3)
    walking = 1 - 20.0 / 25.0
    folding = 1 - (0.9 + 1.5) / 0.9
    assert f.mission_saving(1e9) == pytest.approx(walking, abs=1e-6)
    assert f.mission_saving(0.0) == pytest.approx(folding)
    # at the break-even distance the mission saves what walking alone saves, net of nothing
    d = f.break_even
    assert d is not None
    assert f.mission_saving(d) == pytest.approx(1 - (d * 20 + 2.4) / (d * 25 + 0.9))
    assert (d * 25 + 0.9) - (d * 20 + 2.4) == pytest.approx(0.0, abs=1e-12)


def test_the_mission_table_is_checked():
    assert Mission().metres_per_fold is None and Mission(12).metres_per_fold == 12.0
    for bad in (0, -1.0, math.inf):
        with pytest.raises(InvalidParameterError, match="metres_per_fold"):
            Mission(bad)


def test_design_json_has_the_fold_and_its_break_even(design_written):
    data = json.loads((design_written[1] / "design.json").read_text())
    fo = data["fold"]
    assert [w["label"] for w in fo["ways"]] == ["stand → sphere", "sphere → stand"]
    assert fo["break_even"] is None or fo["break_even"]["unit"] == "m"
    html = (design_written[1] / "design.html").read_text()
    assert 'id="fold-table"' in html and 'id="break-even"' in html


def test_a_mission_key_reaches_the_design():
    from hexaleg.commands.options import check_tables
    from hexaleg.design.chain.chain import DesignChain
    from hexaleg.scenario.scenario import Scenario

    scenario = Scenario.from_tables("hexaleg", {"mission": {"metres_per_fold": 15.0}})
    assert DesignChain(scenario).mission.metres_per_fold == 15.0
    with pytest.raises(InvalidParameterError, match=r"\[mission\] metres_per_fold"):
        check_tables({"mission": {"metres_per_fold": -2.0}}, "m.toml")
    with pytest.raises(UnknownNameError, match="metres_per_fold"):
        check_tables({"mission": {"metres": 2.0}}, "m.toml")
