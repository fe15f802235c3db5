"""DesignSetup: the checked design inputs shared by codesign and the geometry search."""

from __future__ import annotations

import ast
import math
from pathlib import Path

import numpy as np
import pytest

import hexaleg.design.search.geometry as search_module
from hexaleg.design.families import family
from hexaleg.design.search.setup import DesignSetup, design_setup, shifted
from hexaleg.errors import InvalidParameterError, UnknownNameError


def test_search_imports_the_setup_not_codesign():
    """The old cycle: search took codesign's private setup under TYPE_CHECKING."""
    tree = ast.parse(Path(search_module.__file__).read_text(encoding="utf-8"))
    modules = {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}
    assert "hexaleg.design.search.setup" in modules
    assert "hexaleg.design.search.optimal" not in modules


def test_setup_ranges_and_problem(prepared200):
    setup = design_setup(prepared200, ["femur"], "one_sided", "joule", None, math.pi)
    assert isinstance(setup, DesignSetup) and not setup.condensed
    j = prepared200.robot.joints("femur")[0]
    q = prepared200.q[:, prepared200.robot.column(j)]
    assert setup.centre[j] == pytest.approx((q.min() + q.max()) / 2)
    problem = setup.problem(setup.check_geometry({"femur": {"contact": 0.0, "side": "above"}}))
    assert problem.B.shape == (200, 6, 2) and "max_deflection" in problem.labels


def test_shifted_moves_every_angle_of_a_group():
    fam = family("preloaded")
    geo = {"a": {"theta_minus": -0.1, "theta_plus": 0.2}, "b": {"theta_minus": 0.0,
                                                               "theta_plus": 0.1}}
    out = shifted(fam, geo, {"a": 0.01})
    assert out["a"] == {"theta_minus": pytest.approx(-0.09), "theta_plus": pytest.approx(0.21)}
    assert out["b"] == geo["b"]
    assert shifted(family("one_sided"), {"a": {"contact": 0.1, "side": "below"}},
                   {"a": -0.1})["a"] == {"contact": 0.0, "side": "below"}


def test_worst_case_over_shifts_is_no_better_than_each_shift(prepared200):
    base = design_setup(prepared200, ["femur"], "one_sided", "joule", None, math.pi,
                        "electrical")
    geo = base.check_geometry({"femur": {"contact": -0.15, "side": "above"}})
    shifts = ({"femur": -0.02}, {}, {"femur": 0.02})
    robust = design_setup(prepared200, ["femur"], "one_sided", "joule", None, math.pi,
                          "electrical", shifts)
    worst = robust.solve(geo).value
    for s in shifts:  # each shift alone can do at least as well as the worst case
        alone = base.solve(shifted(base.fam, geo, s)).value
        assert alone <= worst * (1 + 1e-7)
    assert np.isfinite(worst)


def test_bad_setup_is_named(prepared200):
    with pytest.raises(UnknownNameError, match="metric"):
        design_setup(prepared200, ["femur"], "one_sided", "joule", None, None, "power")
    with pytest.raises(InvalidParameterError, match="joule with a metric"):
        design_setup(prepared200, ["femur"], "one_sided", "torque_squared", None, None,
                     "electrical")
    with pytest.raises(UnknownNameError, match="stop shift group"):
        design_setup(prepared200, ["femur"], "one_sided", "joule", None, None, "electrical",
                     [{"tibia": 0.01}])
    with pytest.raises(InvalidParameterError, match="stop shift of femur"):
        design_setup(prepared200, ["femur"], "one_sided", "joule", None, None, "electrical",
                     [{"femur": float("nan")}])


def test_relative_angles_are_from_each_centre_and_reflected_where_mirrored(prepared200):
    """The angle a design's stops are placed on: q − c, and c − q on a mirrored joint."""
    import numpy as np

    from hexaleg.design.search.setup import design_setup

    joints = prepared200.robot.joints("femur")
    setup = design_setup(prepared200, ["femur"], "one_sided", "joule", None, None,
                         mirrored=[joints[0]])
    r = setup.relative("femur")
    q = prepared200.q[:, [prepared200.robot.column(j) for j in joints]]
    c = (q.min(0) + q.max(0)) / 2
    assert r.shape == q.shape
    np.testing.assert_array_equal(r[:, 0], c[0] - q[:, 0])
    np.testing.assert_array_equal(r[:, 1:], q[:, 1:] - c[1:])


def test_shifted_problems_share_each_groups_part_bit_for_bit(prepared200):
    """problems() builds each group's part once per distinct shifted geometry (the shifts
    repeat it) — the same arrays as each shifted problem built on its own."""
    shifts = ({"coxa": -0.02, "femur": 0.01}, {"coxa": 0.0, "femur": 0.01}, {"coxa": 0.0},
              {"coxa": -0.02, "femur": -0.01})
    setup = design_setup(prepared200, ["coxa", "femur"], "preloaded", "joule", None, math.pi,
                         "electrical", shifts)
    geo = setup.check_geometry({g: {"theta_minus": -0.05, "theta_plus": 0.04}
                                for g in ("coxa", "femur")})
    for s, shared in zip(shifts, setup.problems(geo), strict=True):
        alone = setup.problem(shifted(setup.fam, geo, s))
        assert alone.B.tobytes() == shared.B.tobytes()
        assert alone.G.tobytes() == shared.G.tobytes()
        assert alone.h.tobytes() == shared.h.tobytes() and alone.labels == shared.labels
