"""Tests of hexaleg.studies.design.stages: the stages of hexaleg design one by one."""

from __future__ import annotations

from hexaleg.design.robustness import Condition
from hexaleg.studies.design.candidates import class_geometry
from hexaleg.studies.design.config import DesignConfig
from hexaleg.studies.design.stages import corners


def test_the_robust_box_is_its_corners_and_the_nominal_gait_once():
    cfg = DesignConfig.from_mapping({"design": {
        "robust_period": [0.8, 1.25], "robust_stride": [1.0, 1.0],
        "robust_payload": [0.0, 0.2], "robust_mu": [0.6, 0.6]}})
    box = corners(cfg)
    assert box[0] == Condition()
    assert len(box) == 1 + 4 and len(set(box)) == len(box)
    assert {(c.period, c.payload) for c in box[1:]} == {(0.8, 0.0), (0.8, 0.2), (1.25, 0.0),
                                                      (1.25, 0.2)}


def test_class_geometry_is_each_class_once(written):
    r = written[0].result
    rec = r.recommended
    classes = {k: tuple(js) for k, js in rec.optimum.groups.items()}
    assert class_geometry(rec.optimum, classes) == rec.optimum.geometry


def test_the_stages_are_timed_in_order(written):
    r = written[0].result
    names = list(r.timings)
    assert names[0] == "prepare" and names[-1] == "simulate"
    assert names.index("pareto") < names.index("ranking") < names.index("maps")
    assert all(t >= 0 for t in r.timings.values())
