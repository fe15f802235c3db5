"""Tests of where each spring mounts on each joint (hexaleg.design.springs.mounting).

The angles a builder reads are joint angles, from the joint's zero; the design's geometry is
relative to each joint's centre of motion. The recommended design's mounting is checked against
the spring laws of design.json — made by the families from the geometry, not by this module —
so a relative angle written where a joint angle belongs fails (issue #57: the femur's stop would
have sat 31° off).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from hexaleg.design.springs.envelope import HardStop, PartEnvelope
from hexaleg.design.springs.mounting import mountings
from hexaleg.design.springs.parts import SpringPart
from hexaleg.design.springs.torsion_spring import TorsionRequirement, design_torsion_spring

RATE, PRELOAD = 0.02, 0.05


def _part(side: str, contact: float, engage: float | None) -> SpringPart:
    s = 1 if side == "above" else -1
    spring = design_torsion_spring(TorsionRequirement(rate=RATE, max_torque=0.08,
                                                      preload_torque=PRELOAD,
                                                      max_outer_diameter=0.02))
    return SpringPart(group="g", joints=("a", "b"), side=side, role="one-sided", rate=RATE,
                      preload_torque=PRELOAD, max_torque=0.08, engage=engage,
                      free=contact - s * PRELOAD / RATE, constant_torque=False,
                      max_outer_diameter=0.02, spring=spring, contact=contact)


def _q() -> np.ndarray:
    """Joint a swings 0.2…0.6 rad (centre 0.4), b −1.0…−0.2 (centre −0.6)."""
    t = np.linspace(0, 1, 61)  # the sine reaches its peaks at t = 1/4, 3/4
    return np.column_stack([0.4 + 0.2 * np.sin(2 * np.pi * t), -0.6 + 0.4 * np.cos(2 * np.pi * t)])


def test_each_angle_is_the_joints_centre_plus_the_relative_angle():
    m = mountings([_part("above", -0.1, None)], _q(), {"a": 0, "b": 1})
    assert [x.joint for x in m] == ["a", "b"]
    a, b = m
    assert (a.low, a.high, a.centre) == pytest.approx((0.2, 0.6, 0.4))
    assert (b.low, b.high, b.centre) == pytest.approx((-1.0, -0.2, -0.6))
    assert a.contact == pytest.approx(0.3) and b.contact == pytest.approx(-0.7)
    assert a.free == pytest.approx(0.3 - PRELOAD / RATE)
    assert a.engaged_throughout and a.side == b.side == "above"  # engage None: throughout
    assert a.hard_stop is None
    t = a.table()
    assert t["contact"] == {"value": pytest.approx(0.3), "unit": "rad"}
    assert t["contact_from_centre"]["value"] == pytest.approx(-0.1)


def test_a_mirrored_joint_counts_the_other_way_and_its_side_swaps():
    m = mountings([_part("below", 0.15, 0.15)], _q(), {"a": 0, "b": 1},
                  mirrored=frozenset({"b"}))
    a, b = m
    assert a.contact == pytest.approx(0.55) and a.side == "below"
    assert b.contact == pytest.approx(-0.75) and b.side == "above" and b.mirrored
    assert not a.engaged_throughout
    assert b.free == pytest.approx(-0.6 - (0.15 + PRELOAD / RATE))


def test_the_hard_stop_is_the_envelopes_and_a_part_without_spring_is_left_out():
    part = _part("above", -0.1, None)
    stop = HardStop(angle_from_centre=0.5, angles={"a": 0.9, "b": -0.1}, windup=3.0, torque=0.1)
    env = PartEnvelope(group="g", side="above", role="one-sided", max_windup=4.0, max_torque=0.1,
                       stress=1e9, yield_strength=1e9, safety_factor=1.0, design_factor=1.2,
                       joint="a", angle=2.0, angle_from_centre=1.6, source="URDF limits",
                       by_source={}, wound_inner_diameter=0.007, arbor_diameter=0.005, stop=stop)
    bare = SpringPart(group="h", joints=("a",), side="above", role="constant torque", rate=0.0,
                      preload_torque=0.1, max_torque=0.1, engage=None, free=None,
                      constant_torque=True, max_outer_diameter=0.02)
    m = mountings([bare, part], _q(), {"a": 0, "b": 1}, envelope=[env])
    assert [(x.part, x.joint, x.hard_stop) for x in m] == [(1, "a", 0.9), (1, "b", -0.1)]


def test_design_json_mounts_each_spring_where_its_law_engages(design_written):
    """Every mounting entry's contact is the joint's spring law's contact angle (design.json
    ``springs``), its centre that joint's centre of motion, and its hard stop the envelope's."""
    data = json.loads((design_written[1] / "design.json").read_text())
    rec = data["recommended"]
    assert rec["family"] == "one_sided"
    laws = {s["joint"]: s["parameters"] for s in rec["springs"]}
    stops = {(e["group"], e["side"]): e["hard_stop"] for e in data["envelope"]}
    assert {m["joint"] for m in data["mounting"]} == set(laws)
    for m in data["mounting"]:
        law = laws[m["joint"]]
        assert m["contact"]["value"] == pytest.approx(law["contact"]["value"], abs=1e-12)
        assert m["side"] == law["side"]
        c = m["centre"]["value"]
        assert c == pytest.approx((m["low"]["value"] + m["high"]["value"]) / 2)
        assert m["contact_from_centre"]["value"] == pytest.approx(m["contact"]["value"] - c)
        group = rec["groups"][m["group"]]["design"]
        assert m["contact_from_centre"]["value"] == pytest.approx(group["contact"]["si"]["value"])
        stop = stops[(m["group"], m["side"])]
        if stop is None:
            assert m["hard_stop"] is None
        else:
            assert m["hard_stop"]["value"] == stop["angles"][m["joint"]]["value"]
        # the preload wind-up between the free leg and the stop is P / k of the law
        wind = abs(m["contact"]["value"] - m["free"]["value"])
        assert wind == pytest.approx(law["preload"]["value"] / law["stiffness"]["value"])
        assert math.isfinite(wind)
