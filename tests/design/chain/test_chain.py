"""Tests of hexaleg.design.chain.chain: the recommended design, its parts, maps and robust
design agree with fresh analyses through the public API."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import hexaleg
from hexaleg.design.springs.torsion_spring import D_STEP
from hexaleg.robot.payload import with_payload
from hexaleg.robot.springs import SpringSet
from hexaleg.scenario.condition import Condition, condition_gait


def _fresh(result, condition: Condition | None = None):
    """The condition's gait prepared from scratch, through the public API."""
    condition = condition or Condition()
    robot = hexaleg.load()
    if condition.payload:
        robot = with_payload(robot, condition.payload * robot.mass)
    gait = condition_gait(result.gait, condition)
    contact = hexaleg.ContactParams(mu=condition.mu if condition.mu else 0.6)
    return hexaleg.prepare(robot, hexaleg.gait(robot, gait),
                           motor=hexaleg.Scenario.load().actuator, contact=contact)


def test_recommended_saving_equals_a_fresh_evaluation(design_written):
    r = design_written[0].result
    rec = r.recommended
    a = _fresh(r).evaluate(rec.optimum.springs, "joule")
    for m in ("electrical", "joule"):
        assert a.savings["total"][m] == pytest.approx(rec.row[f"saving.{m}"], rel=1e-9)
    assert rec.row["saving.electrical"] > 0.05  # the springs pay on the default robot
    assert rec.net["electrical"] < rec.row["saving.electrical"]  # their mass costs energy


def test_the_recommendation_is_the_best_simulated_buildable_design(design_written):
    """Every family optimum and Pareto point is simulated under each controller of the design's
    servo (by default both; each design once a controller), and the recommendation is the
    buildable one whose worse controller's simulated saving net of its springs' mass (simulated
    gross + the predicted mass penalty) is the best."""
    r = design_written[0].result
    pool = {id(c) for c in [*r.candidates, *(c for _, c in r.pareto)]}
    assert r.design.controller == "both"
    for controller in ("feedforward", "position"):
        rows = [row for row in r.ranking if row.controller == controller]
        assert [id(row.candidate) for row in rows] == list(dict.fromkeys(
            id(row.candidate) for row in r.ranking))
        assert {id(row.candidate) for row in rows} == pool and len(rows) == len(pool)
    assert len(r.ranking) == 2 * len(pool)
    worse: dict[int, float] = {}
    for row in r.ranking:
        worse[id(row.candidate)] = min(worse.get(id(row.candidate), np.inf), row.net)
    walked = [row for row in r.ranking if row.simulated is not None and row.candidate.buildable
              and np.isfinite(worse[id(row.candidate)])]
    best = max(walked, key=lambda row: worse[id(row.candidate)]).candidate
    t = r.tolerance
    if t is None or t.worst["tolerant"] <= t.worst["blind"]:
        assert r.recommended is best
    else:  # the best simulated design, designed again for its stops' mounting error
        assert r.recommended.family == best.family
        assert r.recommended.optimum.groups == best.optimum.groups
    for row in walked:
        c = row.candidate
        assert row.net == pytest.approx(
            row.simulated + c.net["electrical"] - c.row["saving.electrical"], abs=1e-15)
        assert row.predicted == c.row["saving.electrical"]
        assert row.flagged == (row.simulated < 0.5 * row.predicted)
    assert [c.net["electrical"] for c in r.candidates] == sorted(
        (c.net["electrical"] for c in r.candidates), reverse=True)


def test_every_part_is_a_spring_of_the_rate_the_design_needs(design_written):
    rec = design_written[0].result.recommended
    assert rec.parts and rec.buildable
    for p in rec.parts:
        s = p.spring
        assert abs(s.rate / p.rate - 1) <= D_STEP / s.mean_diameter + 1e-12
        assert s.outer_diameter <= p.max_outer_diameter
        assert s.stress * s.design_factor <= s.yield_strength
        assert s.preload_angle == pytest.approx(p.preload_torque / s.rate)


def test_pareto_points_keep_their_torque_bound(design_written):
    r = design_written[0].result
    assert r.pareto[-1][0] == 1.0
    for f, c in r.pareto[:-1]:
        assert np.abs(c.optimum.analysis.tau_spring).max() <= c.max_torque * (1 + 1e-6)
        assert f < 1


@pytest.mark.parametrize(("index", "cell"), [(0, (0, 1)), (0, (2, 0)), (1, (1, 0))])
def test_map_points_equal_a_fresh_analysis(design_written, index, cell):
    r = design_written[0].result
    mp = r.maps[index]
    cond = mp.condition(*cell)
    p = _fresh(r, cond)
    a = p.evaluate(r.recommended.optimum.springs, "joule")
    for m in ("electrical", "joule"):
        assert mp.saving[m][cell] == pytest.approx(a.savings["total"][m], rel=1e-9)
    worst, where = mp.worst("electrical")
    assert worst == np.nanmin(mp.saving["electrical"]) and where is not None


def test_slope_pattern_map_points_equal_a_fresh_public_analysis(design_written):
    """The third map: the recommended springs on each slope and pattern, analysed afresh through
    the public API (the pattern at its own duty factor, the slope along the heading)."""
    r = design_written[0].result
    mp = r.maps[2]
    assert mp.axes == ("slope", "pattern")
    assert list(mp.values[1]) == ["tripod", "ripple", "wave"]  # the hexapod's, nominal first
    assert (mp.status == "ok").all()
    robot = hexaleg.load()
    for i, j in ((1, 2), (0, 1), (1, 0)):
        params = r.gait.updated({"pattern": str(mp.values[1][j]),
                                 "slope": float(mp.values[0][i])})
        fresh = hexaleg.prepare(robot, hexaleg.gait(robot, params),
                                motor=hexaleg.Scenario.load().actuator)
        a = fresh.evaluate(r.recommended.optimum.springs, "joule")
        for m in ("electrical", "joule"):
            assert mp.saving[m][i, j] == pytest.approx(a.savings["total"][m], rel=1e-9)
    # the level tripod is the nominal gait: its cell is the recommendation's own saving
    assert mp.saving["joule"][0, 0] == pytest.approx(r.recommended.row["saving.joule"],
                                                     rel=1e-9)
    assert r.worst["electrical"][0] <= mp.worst("electrical")[0]
    assert not any("not conditions of the maps" in n for n in r.notes)


def test_a_map_condition_the_robot_cannot_walk_is_a_cell_not_the_end(design_written):
    """Out of reach (stride ×8) and steeper than the friction holds (40° at μ 0.6): cells with
    their reasons, outside the envelope (NaN), the worst case taken over the others."""
    from hexaleg.design.chain.config import design_params, design_run
    from hexaleg.design.chain.stages import nominal, robustness_maps

    r = design_written[0].result
    scenario = hexaleg.Scenario.from_tables("hexaleg", {"gait": {"samples": 120}, "design": {
        "samples": 120, "map_period": [1.0], "map_stride": [1.0, 8.0], "map_payload": [0.0],
        "map_mu": [0.6], "map_slope": [0.0, 0.7], "map_pattern": ["wave"]}})
    d = design_params(scenario)
    maps, worst = robustness_maps(nominal(design_run(scenario, d), d), r.recommended)
    assert maps[0].status[0, 1].startswith("no gait: GaitReachError: ")
    assert maps[2].status[1, 0].startswith("no gait: InfeasibleForcesError: the ground is "
                                           "inclined by γ = 40.1°")
    assert np.isnan(maps[0].saving["electrical"][0, 1])
    assert np.isnan(maps[2].saving["electrical"][1, 0])
    cells = [mp.saving["electrical"][0, 0] for mp in maps]
    assert worst["electrical"][0] == pytest.approx(min(cells))


def test_map_slope_and_pattern_settings_are_checked():
    import math

    from hexaleg.design.chain.config import DesignParams
    from hexaleg.errors import InvalidParameterError, UnknownNameError

    d = DesignParams()
    assert d.map_pattern is None
    np.testing.assert_allclose(np.degrees(d.map_slope), [-15, -7.5, 0, 7.5, 15])
    assert DesignParams(map_pattern=["wave"], map_slope=[0.1]).map_pattern == ("wave",)
    with pytest.raises(InvalidParameterError, match=r"design\.map_slope = 1\.6.*\(−π/2, π/2\)"):
        DesignParams(map_slope=[0.0, 1.6])
    with pytest.raises(InvalidParameterError, match=r"design\.map_slope"):
        DesignParams(map_slope=[-math.pi / 2])
    with pytest.raises(UnknownNameError, match=r"design\.map_pattern 'gallop'.*tripod, trot"):
        DesignParams(map_pattern=["tripod", "gallop"])
    for bad in ([], "wave"):
        with pytest.raises(InvalidParameterError, match=r"design\.map_pattern"):
            DesignParams(map_pattern=bad)


def test_robust_design_never_worse_in_its_worst_case(design_written):
    rb = design_written[0].result.robust
    d = rb.design
    assert len(rb.conditions) == 5  # nominal + 4 corners
    assert d.worst >= d.nominal_worst - 1e-9
    np.testing.assert_allclose(rb.savings[d.metric]["robust"], d.saving, rtol=1e-9)
    # the robust springs through a fresh analysis of one corner
    corner = rb.conditions[-1]
    fresh = _fresh(design_written[0].result, corner).evaluate(SpringSet(d.springs), "joule")
    assert fresh.savings["total"][d.metric] == pytest.approx(d.saving[-1], rel=1e-9)


def test_summary_names_the_design(design_written):
    r = design_written[0].result
    rec, text = r.recommended, r.summary()
    assert text.startswith(f"fit {rec.label} springs on {', '.join(rec.optimum.groups)}: ")
    assert f"electrical saving {100 * rec.row['saving.electrical']:+.2f} %" in text
    assert f"({100 * rec.net['electrical']:+.2f} % net of {1e3 * rec.spring_mass:.1f} g" in text
    worst, where = r.worst["electrical"]
    assert worst == min(mp.worst("electrical")[0] for mp in r.maps)
    assert f"worst case over the maps {100 * worst:+.2f} % at {where}; " in text
    ff, pos = r.simulation
    assert text.endswith(f"simulated electrical saving feedforward + PD "
                         f"{100 * ff['simulated']:+.2f} %, position only "
                         f"{100 * pos['simulated']:+.2f} % (predicted "
                         f"{100 * rec.row['saving.electrical']:+.2f} %)")


def test_the_recommendation_is_proven_in_a_forward_simulation(design_written):
    """Issue #16's bar: with feedforward + PD on firm ground the simulated saving of the
    recommended design is within 1 percentage point of the predicted one, and each energy within
    −10 %…+5 %; the position-only servo is simulated too (its saving may differ: it is shown,
    not bounded). The predicted numbers are the recommendation's own."""
    r = design_written[0].result
    rec = r.recommended
    ff, pos = r.simulation
    assert (ff["controller"], pos["controller"]) == ("feedforward", "position")
    assert ff["verdict"] == pos["verdict"] == "walks"
    assert ff["predicted"] == pytest.approx(rec.row["saving.electrical"], rel=1e-9)
    assert ff["predicted_electrical"] == pytest.approx(rec.row["electrical"], rel=1e-9)
    assert abs(ff["simulated"] - ff["predicted"]) < 0.01
    for simulated, predicted in ((ff["electrical"], ff["predicted_electrical"]),
                                 (ff["baseline"], ff["predicted_baseline"])):
        assert -0.10 < simulated / predicted - 1 < 0.05
    assert abs(ff["distance_per_cycle"] / (r.gait.stride) - 1) < 0.02
    assert pos["simulated"] is not None


def test_a_design_that_does_not_pay_for_its_mass_says_so(design_written):
    r = design_written[0].result
    assert r.pays and r.summary().startswith("fit ")
    rec = r.recommended
    heavy = dataclasses.replace(rec, net={**rec.net, "electrical": -0.01})
    worse = dataclasses.replace(r, recommended=heavy)
    assert not worse.pays
    assert worse.summary().startswith("no springs pay here; the best would be")


def test_the_recommendation_holds_over_its_stops_mounting_error(design_written):
    """The recommendation is the tolerant design when it keeps more in its worst case; its
    saving at every common stop shift within the tolerance, evaluated afresh, is ≥ 0.8 of the
    nominal (the issue's bar) and its nominal is the recommendation's own saving."""
    from hexaleg.design.search.setup import motion_centres
    from hexaleg.design.search.tolerance import shifted_springs

    r = design_written[0].result
    t = r.tolerance
    assert t is not None and t.tolerance == r.design.stop_tolerance
    assert t.worst["tolerant"] > t.worst["blind"]
    rec = r.recommended
    assert t.nominal["tolerant"] == pytest.approx(rec.row["saving.electrical"], rel=1e-9)
    fresh = _fresh(r)
    joints = [j for js in rec.optimum.groups.values() for j in js]
    centres = motion_centres(fresh, joints)
    for shift in (-t.tolerance, t.tolerance):
        springs = shifted_springs(rec.optimum, centres, dict.fromkeys(joints, shift))
        kept = fresh.evaluate(springs, "joule").savings["total"]["electrical"]
        assert kept >= 0.8 * t.nominal["tolerant"]


def test_the_front_is_the_family_that_simulates_best(monkeypatch):
    """The Pareto front is built for the family optimum the ranking would recommend among the
    family optima (the best simulated net saving under the worse controller), not for the best
    predicted one; the ranking then reuses those simulations, in its order; without the ranking
    the front is the best predicted buildable family's. Catches a front whose family flips
    with a hair of the motion when two families' predicted net savings are close
    (docs/optimal.md, "Starts above the search box")."""
    import copy

    from hexaleg.design.chain import chain as chain_module
    from hexaleg.design.chain.chain import DesignChain
    from hexaleg.design.chain.ranking import Simulated

    tables = {"design": {"samples": 100, "families": ["linear", "one_sided"],
                         "pareto_fractions": [0.5], "controller": "position"}}
    fronts: list[str] = []
    simulated: list[list[str]] = []

    def front(_nominal, optimum):
        fronts.append(optimum.family)
        return [(0.5, copy.copy(optimum)), (1.0, optimum)]  # a point of its own

    def simulate(_prepared, candidates, servo, _metric):
        simulated.append([c.family for c in candidates])
        # the family predicted second walks best: the front must be its own
        return [Simulated(c, "position", 0.3, 0.3, "walks", 0.2 if k == 0 else 0.25)
                for k, c in enumerate(candidates)]

    monkeypatch.setattr(chain_module, "pareto_front", front)
    monkeypatch.setattr(chain_module, "simulate_candidates", simulate)
    run = hexaleg.Scenario.from_tables("hexaleg", tables)
    chain = DesignChain(run)
    ranked = chain.candidates()
    assert len(ranked) == 2 and all(c.buildable for c in ranked)
    chain.run(("candidates", "pareto", "ranking"))
    assert fronts == [ranked[1].family]
    assert simulated[0] == [c.family for c in sorted(
        ranked, key=lambda c: -chain_module.rank(c, chain.design.metric))]
    assert len(simulated) == 2 and simulated[1] == [ranked[1].family]  # only the front's point
    rows, rec, _ = chain.ranking()
    assert len(rows) == 3 and rec is ranked[1]
    fronts.clear()
    DesignChain(run).run(("candidates", "pareto"))
    assert fronts == [ranked[0].family]
