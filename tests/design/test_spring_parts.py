"""Tests of hexaleg.design.spring_parts: a design's elements as torsion springs to buy."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from hexaleg.design.codesign import optimal_springs
from hexaleg.design.spring_parts import (
    PartOptions,
    spring_masses,
    spring_outer_diameter,
    spring_parts,
)
from hexaleg.errors import UnknownNameError
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
