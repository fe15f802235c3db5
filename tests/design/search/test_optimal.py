"""optimal_springs: the global optimum of the magnitudes for a geometry, checked against brute
force, the cvxpy formulation, Prepared.evaluate and the old Nelder–Mead search."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

import hexaleg
from hexaleg.design.evaluator import Evaluator
from hexaleg.design.families import FAMILIES, ZERO_MAGNITUDE, family
from hexaleg.design.search.optimal import design_problem, optimal_springs
from hexaleg.design.studies.optimise import optimise
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.motion.scaling import robot_gait
from hexaleg.robot.springs import SpringSet

GEOMETRY = {"linear": {}, "dead_zone": {"theta_minus": -0.15, "theta_plus": 0.05},
            "preloaded": {"theta_minus": -0.12, "theta_plus": 0.03},
            "one_sided": {"contact": -0.1, "side": "above"},
            "stiffening": {"above_1": -0.1, "above_2": 0.05, "below_1": 0.1, "below_2": -0.05}}
CLASSES = ["coxa", "femur", "tibia"]


def _joule(prepared, joints, fam, x):
    """The cycle's Joule energy of magnitudes ``x`` on ``joints``, by the force program alone."""
    springs = {}
    for j in joints:
        q = prepared.q[:, prepared.robot.column(j)]
        springs[j] = family(fam).spring(GEOMETRY[fam], (q.min() + q.max()) / 2, x)
    _, tau, _ = prepared.solve(SpringSet(springs).torques(prepared.robot, prepared.motion.q))
    return prepared.metrics(tau)["total"]["joule"]


@pytest.mark.parametrize("fam", FAMILIES)
def test_optimum_equals_a_brute_force_grid_over_the_magnitudes(prepared200, fam):
    """One group (the femurs): a grid over the magnitudes, zoomed about its best point, never
    beats the program and comes within 1e-6 of it."""
    joints = prepared200.robot.joints("femur")
    res = optimal_springs(prepared200, {"femur": joints}, fam, geometry={"femur": GEOMETRY[fam]})
    nonneg = family(fam).nonnegative()
    x_opt = np.array(list(res.magnitudes["femur"].values()))
    active = np.flatnonzero(np.abs(x_opt) > 0) if np.any(x_opt) else np.arange(x_opt.size)
    width = np.where(np.arange(x_opt.size) == 0, 1.0, 0.2)  # stiffness N·m/rad, torques N·m
    centre = np.zeros(x_opt.size)
    points = 9 if active.size <= 2 else 5
    best = np.inf
    for _ in range(7):
        axes = [np.linspace(centre[i] - width[i], centre[i] + width[i], points)
                if i in active else np.array([0.0]) for i in range(x_opt.size)]
        axes = [np.unique(np.maximum(a, 0.0)) if nonneg[i] else a for i, a in enumerate(axes)]
        for x in itertools.product(*axes):
            value = _joule(prepared200, joints, fam, np.array(x))
            if value < best:
                best, centre = value, np.array(x)
        width = width * 2 / (points - 1)
    assert best >= res.value * (1 - 1e-9)
    assert (best - res.value) / res.value < 1e-6


@pytest.mark.parametrize("fam", FAMILIES)
def test_fast_path_equals_cvxpy_for_all_18_joints(prepared200, slippery200, fam):
    from hexaleg.design.search.program import solve_design
    from hexaleg.design.search.program_reference import solve_design_reference

    joints = prepared200.robot.joint_names
    for prepared in (prepared200, slippery200):
        res = optimal_springs(prepared, {j: [j] for j in joints}, fam,
                              geometry={j: GEOMETRY[fam] for j in joints})
        problem = design_problem(prepared, res.groups, fam, res.geometry)
        fast, ref = solve_design(problem), solve_design_reference(problem)
        assert abs(fast.value - ref.value) <= 1e-6 * ref.value
        np.testing.assert_allclose(fast.x, ref.x, atol=1e-6)
        np.testing.assert_allclose(fast.forces, ref.forces, atol=1e-6)
    assert fast.explicit.size > 0  # μ = 0.3: the active set was needed


@pytest.mark.parametrize("fam", FAMILIES)
def test_evaluate_reproduces_the_optimum(prepared, fam):
    res = optimal_springs(prepared, CLASSES, fam, geometry={c: GEOMETRY[fam] for c in CLASSES})
    again = prepared.evaluate(res.springs).metrics["total"]["joule"]
    assert abs(again - res.solver["program_value"]) <= 1e-9 * again
    assert res.value == again and res.saving == pytest.approx(1 - again / res.baseline)
    assert res.solver["explicit_samples"] == 0  # μ = 0.6: nothing binds, least squares only


def test_linear_optimum_is_a_constant_torque_spring_and_says_so(prepared):
    res = optimal_springs(prepared, CLASSES, "linear")
    femur = res.magnitudes["femur"]
    assert femur["k"] <= ZERO_MAGNITUDE < abs(femur["torque_at_reference"])
    assert any("femur" in n and "constant-torque" in n for n in res.notes)
    assert res.saving > 0.3  # gravity compensation: a third of the Joule energy (measured 35 %)


def test_max_torque_and_max_deflection_hold(prepared):
    res = optimal_springs(prepared, CLASSES, "linear", max_torque=0.03)
    assert np.abs(res.analysis.tau_spring).max() <= 0.03 + 1e-9
    free = optimal_springs(prepared, CLASSES, "linear")
    assert res.value >= free.value
    d = optimal_springs(prepared, CLASSES, "linear", max_deflection=0.8)
    for j, s in d.springs.items():
        q = prepared.q[:, prepared.robot.column(j)]
        if s.stiffness > 0:
            assert np.abs(q - s.equilibrium).max() <= 0.8 + 1e-9
        else:
            assert s.torque_at_reference == pytest.approx(0.0, abs=1e-9)
    p = optimal_springs(prepared, ["femur"], "preloaded", max_deflection=0.3,
                        geometry={"femur": GEOMETRY["preloaded"]})
    for j, s in p.springs.items():  # deflection from the free position: compression + P/k
        q = prepared.q[:, prepared.robot.column(j)]
        comp = max(q.max() - s.neutral - s.th_plus, 0.0)
        if s.stiffness > 0 and comp > 0:
            assert comp + s.preload / s.stiffness <= 0.3 + 1e-7


def test_never_worse_than_nelder_mead_on_the_same_geometry(prepared200):
    ev = Evaluator(prepared200)
    for cls in ("femur", "tibia"):
        old = optimise(ev, cls, prepared200.robot.joints(cls), "joule", grid=(5, 4, 3),
                       offset_bounds=(-1.0, 1.0))
        geometry = {"theta_minus": old.offset - old.theta_k, "theta_plus": old.offset + old.theta_k}
        new = optimal_springs(prepared200, [cls], "dead_zone", geometry={cls: geometry})
        assert new.value <= old.value * (1 + 1e-9)


def test_search_is_never_worse_than_a_given_geometry(prepared200):
    given = optimal_springs(prepared200, ["tibia"], "dead_zone",
                            geometry={"tibia": GEOMETRY["dead_zone"]})
    searched = optimal_springs(prepared200, ["tibia"], "dead_zone")
    assert searched.value <= given.value * (1 + 1e-12)
    assert searched.solver["geometry_evaluations"] > 1


def test_non_quadratic_objective_goes_through_the_stacked_program(prepared200):
    res = optimal_springs(prepared200, ["femur"], "linear", objective="electrical")
    assert res.solver["path"] == "cvxpy stacked program" and res.metric == "electrical"
    joule = optimal_springs(prepared200, ["femur"], "linear")
    electrical_of_joule = joule.analysis.metrics["total"]["electrical"]
    assert res.value <= electrical_of_joule * (1 + 1e-3)  # up to the ε Σ τ² regulariser
    assert res.value < res.baseline


def test_table_in_si_and_paper_units(prepared200):
    res = optimal_springs(prepared200, ["femur"], "dead_zone",
                          geometry={"femur": GEOMETRY["dead_zone"]})
    row = res.table()["femur"]
    assert row["theta_minus"]["paper"]["unit"] == "deg"
    k = row["k_plus"]
    assert k["paper"]["unit"] == "N·mm/deg"
    assert k["paper"]["value"] == pytest.approx(k["si"]["value"] * 1e3 * np.pi / 180)


def test_bad_input(prepared200):
    with pytest.raises(InvalidParameterError, match="group femur"):
        optimal_springs(prepared200, {"femur": []})
    with pytest.raises(InvalidParameterError, match="LF_femur"):
        optimal_springs(prepared200, {"a": ["LF_femur"], "b": ["LF_femur", "RF_femur"]})
    with pytest.raises(UnknownNameError, match="spring family"):
        optimal_springs(prepared200, ["femur"], "helical")
    with pytest.raises(UnknownNameError, match="geometry parameter"):
        optimal_springs(prepared200, ["femur"], "dead_zone",
                        geometry={"femur": {"theta_minus": -0.1, "theta_plus": 0.1, "k2": 1}})
    with pytest.raises(InvalidParameterError, match="theta_minus"):
        optimal_springs(prepared200, ["femur"], "dead_zone",
                        geometry={"femur": {"theta_minus": 0.1, "theta_plus": -0.1}})
    with pytest.raises(InvalidParameterError, match="geometry of group femur"):
        optimal_springs(prepared200, ["femur"], "dead_zone", geometry={})
    for solve in (optimal_springs, design_problem):  # never silently ignored
        with pytest.raises(UnknownNameError, match="geometry group"):
            solve(prepared200, ["femur"], "dead_zone", geometry={
                "femur": GEOMETRY["dead_zone"], "knee": GEOMETRY["dead_zone"]})
    for value in (0.0, -1.0, float("nan")):
        with pytest.raises(InvalidParameterError, match="max_deflection"):
            optimal_springs(prepared200, ["femur"], max_deflection=value)
        with pytest.raises(InvalidParameterError, match="max_torque"):
            optimal_springs(prepared200, ["femur"], max_torque=value)
    with pytest.raises(UnknownNameError, match="knee"):
        optimal_springs(prepared200, {"a": ["knee"]})
    with pytest.raises(InvalidParameterError, match="objective"):
        optimal_springs(prepared200, ["femur"], objective="power")


def test_electrical_metric_beats_the_joule_design_and_every_bounded_point(prepared200):
    """metric="electrical": on one geometry, its electrical saving (Prepared.evaluate, Joule
    forces) ≥ the Joule-optimal magnitudes' and every torque-bounded Joule point's — strictly
    above the Joule design's, so a Joule objective would fail."""
    groups = {"femur": "femur", "tibia": "tibia"}
    geometry = {"femur": {"contact": -0.2, "side": "above"},
                "tibia": {"contact": 0.19, "side": "below"}}
    base = prepared200.baseline("joule")["total"]["electrical"]

    def electrical(o):
        return 1 - o.analysis.metrics["total"]["electrical"] / base

    best = optimal_springs(prepared200, groups, "one_sided", geometry=geometry,
                           metric="electrical")
    assert best.metric == "electrical" and best.solver["explicit_samples"] == 0
    assert best.saving == pytest.approx(electrical(best), rel=1e-12)
    joule = optimal_springs(prepared200, groups, "one_sided", geometry=geometry)
    peak = float(np.abs(joule.analysis.tau_spring).max())
    assert best.saving > electrical(joule) + 1e-3
    for f in (0.25, 0.5, 0.75, 0.9):
        bounded = optimal_springs(prepared200, groups, "one_sided", geometry=geometry,
                                  max_torque=f * peak)
        assert best.saving >= electrical(bounded) - 1e-9


def test_reversed_urdf_axes_do_not_change_the_physical_design(tmp_path):
    """The same robot with its right legs' femur and tibia axes reversed (a mirrored URDF) is the
    same machine: with the mirrored joints found (hexaleg.robot.mirror) one design per class
    saves exactly what it saves on the unflipped robot, the springs on both sides act alike;
    without mirroring the class design saves nothing (the two sides cancel)."""
    from conftest import RIGHT_PITCH, SPIDER, flipped_spider

    from hexaleg.robot.mirror import mirror
    from hexaleg.robot.registry import description

    def run(robot, desc, mirrored):
        motion = hexaleg.gait(robot, robot_gait(desc).updated({"samples": 60}))
        p = hexaleg.prepare(robot, motion, motor=desc.actuator(robot))
        classes = {k: robot.joint_classes[k] for k in ("femur", "tibia")}
        return optimal_springs(p, classes, "linear", metric="electrical", mirrored=mirrored)

    plain_robot = hexaleg.robot.registry.load(str(SPIDER))
    flipped = flipped_spider(tmp_path, RIGHT_PITCH)
    desc = description(str(tmp_path / "spider.toml"))
    reference = run(plain_robot, description(str(SPIDER)), mirror(plain_robot).mirrored)
    found = run(flipped, desc, mirror(flipped).mirrored)
    assert found.saving > 0.02
    assert found.saving == pytest.approx(reference.saving, rel=1e-6, abs=1e-9)
    assert found.mirrored == frozenset(RIGHT_PITCH)
    tau = np.abs(found.analysis.tau_spring).max(axis=0)
    for left, right in (("a_j3", "d_j3"), ("a_j2", "d_j2")):
        assert tau[flipped.column(left)] == pytest.approx(tau[flipped.column(right)], rel=1e-6)
    assert run(flipped, desc, ()).saving < 1e-6


def test_the_constant_torque_note_reads_the_one_design_zero(prepared):
    """The note "k = 0 with a constant torque" takes k at most ZERO_MAGNITUDE for 0 and a torque
    above it for a torque: k exactly at the zero is noted (the old strict ``k < ZERO_STIFFNESS``
    missed it), twice it is not, and a torque at the zero is no torque (the old ``> 0`` noted a
    round-off torque)."""
    from hexaleg.design.search.optimal import springs_result
    from hexaleg.design.search.program import DesignSolution
    from hexaleg.design.search.setup import design_setup

    setup = design_setup(prepared, ["femur"], "linear", "joule", None, None)

    def notes(k, torque):
        solution = DesignSolution(x=np.array([k, torque]), value=0.0, explicit=np.zeros(0),
                                  rounds=0, forces=np.zeros((1, 18)))
        return springs_result(setup, {"femur": {}}, solution, 1, 1.0).notes

    assert any("constant-torque" in n for n in notes(ZERO_MAGNITUDE, 0.05))
    assert not any("constant-torque" in n for n in notes(2 * ZERO_MAGNITUDE, 0.05))
    assert not any("constant-torque" in n for n in notes(0.0, ZERO_MAGNITUDE))
    assert any("constant-torque" in n for n in notes(0.0, 2 * ZERO_MAGNITUDE))
