"""Tests of hexaleg.design.springs.parts: a design's elements as torsion springs to buy."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from hexaleg.design.search.optimal import optimal_springs
from hexaleg.design.springs.parts import (
    ARBOR_LINK_FRACTION,
    PartOptions,
    arbor_for,
    motion_centres,
    spring_masses,
    spring_outer_diameter,
    spring_parts,
)
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot.catalogue import CATALOGUE, OUTPUT_HUBS, OutputHub
from hexaleg.robot.motor_set import MotorSet
from hexaleg.robot.registry import description

OUTER = {"coxa": 0.03, "femur": 0.02, "tibia": 0.02}


def _relative_range(prepared, joints):
    q = prepared.q[:, [prepared.robot.column(j) for j in joints]]
    centre = (q.min(0) + q.max(0)) / 2
    return float((q.min(0) - centre).min()), float((q.max(0) - centre).max())


def test_a_linear_spring_crossing_zero_is_an_antagonistic_pair(prepared200):
    best = optimal_springs(prepared200, ["coxa"], "linear")  # k > 0, free inside the motion
    parts = spring_parts(best, prepared200, OUTER)
    assert [p.role for p in parts] == ["pair (1 of 2)", "pair (1 of 2)"]
    assert {p.side for p in parts} == {"above", "below"}
    k, tau0 = best.magnitudes["coxa"]["k"], best.magnitudes["coxa"]["torque_at_reference"]
    lo, hi = _relative_range(prepared200, best.groups["coxa"])
    u = np.linspace(lo, hi, 51)
    # above: pushes down, −(k/2)(u − free); below: pushes up, (k/2)(free − u); both stay wound
    above = next(p for p in parts if p.side == "above")
    below = next(p for p in parts if p.side == "below")
    t_above, t_below = above.rate * (u - above.free), below.rate * (below.free - u)
    assert np.all(t_above >= -1e-12) and np.all(t_below >= -1e-12)
    np.testing.assert_allclose(t_below - t_above, tau0 - k * u, atol=1e-12)
    assert above.max_torque == pytest.approx(t_above.max())
    assert above.preload_torque == pytest.approx(t_above.min(), abs=1e-12)
    for p in parts:
        assert p.spring is not None and p.spring.outer_diameter <= OUTER["coxa"]


def test_one_sided_parts_follow_the_law_at_the_ends_of_the_motion(prepared200):
    best = optimal_springs(prepared200, ["tibia"], "one_sided", max_deflection=np.pi)
    (part,) = spring_parts(best, prepared200, OUTER)
    lo, hi = _relative_range(prepared200, best.groups["tibia"])
    m = best.magnitudes["tibia"]
    assert part.rate == pytest.approx(m["k"])
    assert part.side == best.geometry["tibia"]["side"]
    assert part.max_torque <= m["preload"] + m["k"] * (hi - lo) + 1e-12
    assert part.max_torque / part.rate <= np.pi + 1e-9  # max_deflection holds


def test_constant_torque_is_flagged_not_bought(prepared200):
    best = optimal_springs(prepared200, ["femur"], "one_sided")  # no max_deflection: k → 0
    (part,) = spring_parts(best, prepared200, OUTER)
    assert part.constant_torque and part.spring is None
    assert "constant-torque spring" in part.problem


def test_a_part_that_does_not_fit_names_the_nearest(prepared200):
    best = optimal_springs(prepared200, ["tibia"], "one_sided", max_deflection=np.pi)
    (part,) = spring_parts(best, prepared200, {"tibia": 0.004})
    assert part.spring is None and part.nearest is not None
    assert "max_outer_diameter" in part.problem
    assert spring_masses((part,))["LF_tibia"] == part.nearest.mass
    stainless = spring_parts(best, prepared200, OUTER, PartOptions(materials=("stainless_302",)))
    assert stainless[0].spring.material == "stainless_302"


def test_outer_diameter_from_the_links_or_the_description(robot):
    desc = description("hexaleg")
    assert spring_outer_diameter(desc, robot, "femur") == pytest.approx(
        (0.02, "width of its links (collision geometry)"))
    assert spring_outer_diameter(desc, robot, "coxa")[0] == pytest.approx(0.03)
    given = dataclasses.replace(desc, max_outer_diameter={"tibia": 0.012})
    assert spring_outer_diameter(given, robot, "tibia") == (0.012, "hexaleg description")
    with pytest.raises(UnknownNameError, match="coxa, femur, tibia"):
        spring_outer_diameter(desc, robot, "knee")
    with pytest.raises(UnknownNameError, match="coxa, femur, tibia"):
        dataclasses.replace(desc, joint_kinds=("coxa", "femur", "tibia"),
                            max_outer_diameter={"knee": 0.01})


def test_arbor_from_the_description_the_servo_or_the_links(robot, monkeypatch):
    desc = description("hexaleg")
    # (c): no servo gives its hub, so a quarter of the narrowest link, saying why
    d, src = arbor_for(robot, desc, CATALOGUE["AX-18A"], "femur")
    assert d == pytest.approx(ARBOR_LINK_FRACTION * 0.02) and "AX-18A output hub not sourced" in src
    assert arbor_for(robot, desc, "ax-18a", "coxa")[0] == pytest.approx(ARBOR_LINK_FRACTION * 0.03)
    assert "no catalogue servo" in arbor_for(robot, desc, None, "tibia")[1]
    # (b): a catalogue servo with a sourced hub, also through a motor set
    hubs = dict(OUTPUT_HUBS, **{"AX-18A": OutputHub(6e-3, "a drawing")})
    monkeypatch.setattr("hexaleg.design.springs.parts.OUTPUT_HUBS", hubs)
    assert arbor_for(robot, desc, "AX-18A", "femur") == (6e-3, "AX-18A output hub (a drawing)")
    motors = MotorSet.per_class(robot.joint_classes, robot.joint_names,
                                {k: CATALOGUE["AX-18A"] if k == "femur" else CATALOGUE["MX-28"]
                                 for k in robot.joint_classes})
    assert arbor_for(robot, desc, motors, "femur")[0] == 6e-3
    assert arbor_for(robot, desc, motors, "tibia")[0] == pytest.approx(ARBOR_LINK_FRACTION * 0.02)

    # (a): the description's own, whatever the servo; checked like max_outer_diameter
    given = dataclasses.replace(desc, joint_kinds=("coxa", "femur", "tibia"),
                                arbor_diameter={"femur": 4e-3, "coxa": 0})
    assert arbor_for(robot, given, "AX-18A", "femur") == (4e-3, "hexaleg description")
    assert arbor_for(robot, given, "AX-18A", "coxa") == (0.0, "hexaleg description")
    with pytest.raises(UnknownNameError, match="arbor_diameter joint class"):
        dataclasses.replace(given, arbor_diameter={"knee": 4e-3})
    with pytest.raises(InvalidParameterError, match=r"arbor_diameter\.femur"):
        dataclasses.replace(given, arbor_diameter={"femur": -1e-3})
    with pytest.raises(UnknownNameError, match="coxa, femur, tibia"):
        arbor_for(robot, desc, None, "knee")


def test_per_group_arbors_reach_the_springs(prepared200):
    best = optimal_springs(prepared200, ["tibia"], "one_sided", max_deflection=np.pi)
    (free,) = spring_parts(best, prepared200, OUTER)
    arbor = 1.2 * free.spring.wound_inner_diameter  # the unconstrained coil would bind on it
    (part,) = spring_parts(best, prepared200, OUTER, arbor={"tibia": arbor})
    assert part.spring.arbor_diameter == arbor
    assert part.spring.wound_inner_diameter >= 1.1 * arbor * (1 - 1e-12)
    (loose,) = spring_parts(best, prepared200, OUTER, PartOptions(arbor_margin=0.0),
                            arbor={"tibia": free.spring.wound_inner_diameter})
    assert loose.spring.wound_inner_diameter >= free.spring.wound_inner_diameter * (1 - 1e-12)
    centres = motion_centres(prepared200, best.groups["tibia"])
    lo, hi = _relative_range(prepared200, best.groups["tibia"])
    for j, c in centres.items():
        q = prepared200.q[:, prepared200.robot.column(j)]
        assert c == pytest.approx((q.min() + q.max()) / 2)
        assert lo - 1e-12 <= q.min() - c and q.max() - c <= hi + 1e-12


def test_a_part_without_a_stroke_is_a_problem_not_a_crash():
    """G1's design stopped on a part whose torque did not rise over the motion
    (max_torque = preload_torque to rounding): such a part is a part with a problem, the
    design going on; an outer diameter the user set under the thinnest wire's coil is still
    the user's named error (issue #55)."""
    from hexaleg.design.springs.parts import SpringPart, _buy

    part = SpringPart(group="knee", joints=("L_knee",), side="above", role="one-sided",
                      rate=0.05, preload_torque=0.0012524008774, max_torque=0.0012524008774071,
                      engage=0.1, free=0.0, constant_torque=False, max_outer_diameter=0.02)
    flat = _buy(part, PartOptions(), 0.0)
    assert flat.spring is None and "without a stroke" in flat.problem
    with pytest.raises(InvalidParameterError, match="thinnest preferred wire"):
        _buy(dataclasses.replace(part, max_torque=0.01, max_outer_diameter=1e-4),
             PartOptions(), 0.0)
    assert _buy(dataclasses.replace(part, max_torque=0.01), PartOptions(), 0.0).spring is not None


def test_a_round_off_spring_is_no_part(prepared200):
    """A one-sided element whose torque stays below ZERO_TORQUE over the whole motion — the
    round-off of a magnitude the program set to 0 (Solo-12: 4e-9 N·m/rad, 5e-12 N·m) — is no
    part: before, it was sized as a metre-wide coil and its grams counted in the spring mass.
    The same rate engaged over the whole motion is a part."""
    best = optimal_springs(prepared200, ["tibia"], "one_sided", max_deflection=np.pi)
    lo, hi = _relative_range(prepared200, best.groups["tibia"])
    side = best.geometry["tibia"]["side"]
    edge, near = (hi, lo) if side == "above" else (lo, hi)
    step = -1e-3 if side == "above" else 1e-3  # engaged over the last milliradian only
    tiny = {"tibia": {"k": 4e-9, "preload": 3e-15}}
    grazing = dataclasses.replace(best, magnitudes=tiny,
                                  geometry={"tibia": {"contact": edge + step, "side": side}})
    assert spring_parts(grazing, prepared200, OUTER) == ()
    assert spring_masses(spring_parts(grazing, prepared200, OUTER)) == {}
    engaged = dataclasses.replace(best, magnitudes=tiny,
                                  geometry={"tibia": {"contact": near, "side": side}})
    (part,) = spring_parts(engaged, prepared200, OUTER)
    assert part.max_torque == pytest.approx(4e-9 * (hi - lo))


def test_the_parts_read_the_one_design_zero():
    """A stiffness or torque at most ZERO_MAGNITUDE is none, above it a spring: a linear term of
    k = ZERO_MAGNITUDE with a torque is a constant-torque spring (the old strict ``k <
    ZERO_STIFFNESS`` made it a single spring free 5e7 rad away), and one of 2·ZERO_MAGNITUDE is a
    spring; a constant torque at the zero is no part, twice it is one; a one-sided stiffness at
    the zero with a preload is a constant torque, twice it a one-sided spring."""
    from hexaleg.design.families import ZERO_MAGNITUDE
    from hexaleg.design.springs.parts import _elements

    zero = ZERO_MAGNITUDE
    (flat,) = _elements("linear", {}, np.array([zero, 0.05]), -0.5, 0.5)
    assert flat["role"] == "constant torque" and flat["rate"] == 0.0
    assert all(e["role"] != "constant torque"
               for e in _elements("linear", {}, np.array([2 * zero, 0.05]), -0.5, 0.5))
    assert _elements("linear", {}, np.array([0.0, zero]), -0.5, 0.5) == []
    (held,) = _elements("linear", {}, np.array([0.0, 2 * zero]), -0.5, 0.5)
    assert held["role"] == "constant torque"
    geometry = {"contact": -0.2, "side": "above"}
    (pushed,) = _elements("one_sided", geometry, np.array([zero, 0.05]), -0.5, 0.5)
    assert pushed["role"] == "constant torque" and pushed["free"] is None
    (sprung,) = _elements("one_sided", geometry, np.array([2 * zero, 0.05]), -0.5, 0.5)
    assert sprung["role"] == "one-sided" and sprung["rate"] == 2 * zero
    assert _elements("one_sided", geometry, np.array([0.0, zero]), -0.5, 0.5) == []
