"""Tests of hexaleg.design.chain.stages: the stages of hexaleg design one by one."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.design.chain.candidates import class_geometry
from hexaleg.design.chain.config import DesignParams, design_params, design_run
from hexaleg.design.chain.robust_stage import corners
from hexaleg.scenario.condition import Condition
from hexaleg.scenario.scenario import Scenario


def _nominal_of(tables):
    """The stages' nominal of a parsed document: its run at [design] samples and settings."""
    from hexaleg.design.chain.stages import nominal

    scenario = Scenario.from_tables("hexaleg", tables)
    d = design_params(scenario)
    return nominal(design_run(scenario, d), d)


def test_the_robust_box_is_its_corners_and_the_nominal_gait_once():
    box = corners(DesignParams(
        robust_period=[0.8, 1.25], robust_stride=[1.0, 1.0],
        robust_payload=[0.0, 0.2], robust_mu=[0.6, 0.6]))
    assert box[0] == Condition()
    assert len(box) == 1 + 4 and len(set(box)) == len(box)
    assert {(c.period, c.payload) for c in box[1:]} == {(0.8, 0.0), (0.8, 0.2), (1.25, 0.0),
                                                      (1.25, 0.2)}


def test_class_geometry_is_each_class_once(design_written):
    r = design_written[0].result
    rec = r.recommended
    classes = {k: tuple(js) for k, js in rec.optimum.groups.items()}
    assert class_geometry(rec.optimum, classes) == rec.optimum.geometry


def test_the_stages_are_timed_in_order(design_written):
    r = design_written[0].result
    names = list(r.timings)
    assert names[0] == "prepare" and names[-1] == "simulate"
    assert names.index("pareto") < names.index("ranking") < names.index("maps")
    assert all(t >= 0 for t in r.timings.values())


def test_a_max_outer_diameter_for_a_class_the_robot_lacks_is_named():
    """A typo in a [design] max_outer_diameter class was ignored (the springs came out larger
    than asked); now it is an error listing the robot's classes, before anything is prepared."""
    from hexaleg.errors import UnknownNameError

    with pytest.raises(UnknownNameError, match="coxa, femur, tibia"):
        _nominal_of({"design": {"max_outer_diameter": {"femr": 0.01}}})


def test_families_designed_in_parallel_are_the_ones_designed_in_turn(monkeypatch):
    """The forked workers compute exactly what one process computes: the same magnitudes,
    geometry and savings to the last bit, in the families' order of rank; a robustness map's
    cells too (one of them a gait the robot cannot make)."""
    from hexaleg.design.chain.stages import family_candidates
    from hexaleg.design.robust.maps import robustness_map
    from hexaleg.parallel import workers

    axes = {"period": [0.5, 1.0], "stride": [1.0, 40.0]}

    nom = _nominal_of({"gait": {"samples": 100}, "design": {
        "samples": 100, "families": ["linear", "one_sided"], "classes": ["femur", "tibia"]}})
    said: list[str] = []
    parallel, left_out = family_candidates(nom, lambda name, msg: said.append(name))
    with monkeypatch.context() as m:
        m.setattr(workers, "default_workers", lambda: 1)
        serial, _ = family_candidates(nom, lambda name, msg: None)
        cells = robustness_map(nom.run, parallel[0].optimum.springs, axes)
    assert sorted(said) == ["family linear", "family one_sided"] and left_out == []
    assert [c.family for c in parallel] == [c.family for c in serial]
    for a, b in zip(parallel, serial, strict=True):
        assert a.optimum.magnitudes == b.optimum.magnitudes
        assert a.optimum.geometry == b.optimum.geometry
        assert a.row == b.row and a.net == b.net
        assert a.optimum.analysis.robot is nom.robot  # by reference, not a pickled copy
    forked = robustness_map(nom.run, parallel[0].optimum.springs, axes, mapper=nom.fork_map)
    assert forked.status.tolist() == cells.status.tolist()
    for metric, saving in cells.saving.items():
        assert np.array_equal(forked.saving[metric], saving, equal_nan=True)


@pytest.mark.slow
def test_per_joint_springs_ahead_of_the_class_design_are_said_with_both_figures(monkeypatch):
    """The evidence note gives the per-joint design's net saving and the class design's, and
    the per-joint figure is what [design] grouping = "joint" designs; on the wheeled test
    quadruped's trot at 1.44 s (its period sized by similarity alone: its default is shorter
    since #54) per joint is +2.5 points ahead (its arm loads the legs unequally): said at the
    2-point bar, not at 5 (issue #55)."""
    import re
    from pathlib import Path

    import hexaleg
    from hexaleg.design.chain import stages
    from hexaleg.design.chain.config import DesignParams

    robot = str(Path(__file__).resolve().parents[2] / "data" / "wheeled.toml")
    params = DesignParams(families=("one_sided",), robustness=False, samples=100)
    scenario = hexaleg.Scenario.load(robot).with_gait({"period": 1.4428})
    chain = hexaleg.DesignChain(scenario, design=params)
    rec = chain.candidates()[0]
    note = stages.per_joint_evidence(chain.nominal(), rec)
    assert note is not None and 'grouping = "joint"' in note
    fine, coarse = (float(x) for x in re.findall(r"([+-]\d+\.\d+) %", note))
    assert coarse == pytest.approx(100 * rec.net["electrical"], abs=0.005)
    assert 2 < fine - coarse < 5
    joint = hexaleg.DesignChain(scenario, design=DesignParams(
        families=("one_sided",), robustness=False, samples=100, grouping="joint"))
    assert fine == pytest.approx(100 * joint.candidates()[0].net["electrical"], abs=0.005)
    monkeypatch.setattr(stages, "PER_JOINT_EVIDENCE", 0.05)
    assert stages.per_joint_evidence(chain.nominal(), rec) is None
