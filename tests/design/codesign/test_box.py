"""The co-design's search box from its options (``duty_high``, ``body_high``): the box both
searches get reaches each bound, and a bound outside its range is refused by name before any
evaluation."""

from __future__ import annotations

import dataclasses

import pytest

from hexaleg.design.codesign import build
from hexaleg.design.codesign.box import DUTY_CEILING, default_space, edges
from hexaleg.design.codesign.build import codesign
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.params import GaitParams

WAVE_TOP = round(5 / 6 + 0.05, 12)
"""A wave's lowest ``duty_high``: its default gait's β₀ = 5/6, plus 0.05."""


@pytest.mark.parametrize(
    ("key", "cases", "unit", "bad"),
    [pytest.param(
        "duty_factor",
        # (keywords, the box's (low, top) in units of the scale): 0.8 by default, the default
        # gait's + 0.05 where that is higher (a wave's 5/6), the low end the pattern's β₀
        [({}, 0.5, 0.8), ({"duty_high": 0.9}, 0.5, 0.9),
         ({"pattern": "wave"}, 5 / 6, WAVE_TOP)],
        1.0,
        [({"duty_high": 0.99}, r"\[codesign\] duty_high.*\[0\.55, 0\.95\]"),
         ({"duty_high": 0.52}, r"\[codesign\] duty_high.*\[0\.55, 0\.95\]"),
         ({"duty_high": float("nan")}, r"\[codesign\] duty_high.*\[0\.55, 0\.95\]"),
         ({"duty_high": "0.9"}, r"duty_high.*'0\.9'.*number"),
         ({"pattern": "wave", "duty_high": 0.85}, r"duty_high.*\[0\.8833.*, 0\.95\]")],
        id="duty_high"),
     pytest.param(
        "body_height",
        # × the default gait's body height: 1.3 × by default, the low end stays 0.7 ×
        [({}, 0.7, 1.3), ({"body_high": 1.5}, 0.7, 1.5), ({"body_high": 1}, 0.7, 1.0)],
        0.0913,  # the default gait's body height, m
        [({"body_high": 2.01}, r"\[codesign\] body_high.*\[1, 2\]"),
         ({"body_high": 0.99}, r"\[codesign\] body_high.*\[1, 2\]"),
         ({"body_high": float("inf")}, r"\[codesign\] body_high.*\[1, 2\]"),
         ({"body_high": "1.5"}, r"body_high.*'1\.5'.*number")],
        id="body_high")])
def test_each_bound_is_the_search_box_s(monkeypatch, key, cases, unit, bad):
    """``duty_high`` is the searches' highest duty factor, ``body_high`` their highest body
    height × the default gait's: the box the search gets reaches the bound asked for (or its
    default), its low end unchanged; a value outside its range (``duty_high``: [the default
    gait's + 0.05, 0.95], so a wave's range is its own; ``body_high``: [1, 2]), or not a
    number, is refused naming it and that range, before any evaluation. Catches a box whose top
    stays at the default whatever is asked (the option ignored), one scaled by the wrong height,
    a low end moved with the top, or a check made after the search starts."""
    seen = []

    def stop(_evaluate, base, _speed, space, **_):
        scale = base.body_height if key == "body_height" else 1.0
        seen.append((space.bounds[key], scale))
        raise InvalidParameterError("search", "stopped here", "the test's stop")

    monkeypatch.setattr(build, "search", stop)
    for kwargs, low, top in cases:
        with pytest.raises(InvalidParameterError, match="stopped here"):
            codesign(speed=0.06, curve=False, simulate=False, rules=False, **kwargs)
        (lowest, highest), scale = seen[-1]
        assert (lowest, highest) == (pytest.approx(low * scale), pytest.approx(top * scale))
    assert seen[0][1] == pytest.approx(unit, abs=1e-4)
    count = len(seen)
    for kwargs, message in bad:
        with pytest.raises(InvalidParameterError, match=message):
            codesign(speed=0.06, curve=False, simulate=False, rules=False, **kwargs)
    assert len(seen) == count  # refused before the search


def test_the_box_keeps_its_pattern_s_support_and_its_ceiling():
    """Called directly, the box's duty factor stays in [β₀, max(β₀ + 0.05, min(duty_high,
    0.95))] whatever ``duty_high`` says: a tripod's (β₀ 0.5) top is 0.8 by default and 0.95
    at most; a bound below β₀ + 0.05 still leaves a box. Catches a ceiling not applied or a
    box that closes (low = high) under a low bound."""
    tripod = GaitParams(duty_factor=0.5, body_height=0.09, foot_radius=0.19)
    assert default_space(tripod, 0.015).bounds["duty_factor"] == (0.5, 0.8)
    assert default_space(tripod, 0.015, duty_high=0.99).bounds["duty_factor"] == \
        (0.5, DUTY_CEILING)
    low, high = default_space(tripod, 0.015, duty_high=0.5).bounds["duty_factor"]
    assert (low, high) == (0.5, pytest.approx(0.55))


def test_the_edges_are_the_bounds_the_chosen_gait_lies_on():
    """:func:`edges` names each parameter of a gait that lies on its box's bound, the side and
    the option that moves it: the body height at its top (``--body-high``), the duty factor at
    its top (``--duty-high``), the step height at its floor (``min_foot_clearance``), the foot
    radius at its fixed floor; a point one search step (1/32 of a range) inside lies on none,
    and a top already at the options' ceiling has none to move it. Catches an edge tested on
    the wrong side, a step inside taken for the edge, or an option named past its ceiling."""
    tripod = GaitParams(duty_factor=0.5, body_height=0.1, foot_radius=0.2, step_height=0.03)
    space = default_space(tripod, 0.015, duty_high=0.8, body_high=1.3)
    # lo + 1.0 * (hi - lo), as the search's Space.values makes a clipped point: not hi bit for bit
    top = space.values(space.scaled({"body_height": 0.13, "foot_radius": 0.14,
                                     "step_height": 0.015, "duty_factor": 0.8, "period": 1.5}))
    found = edges(space, dataclasses.replace(tripod, **top), duty_high=0.8, body_high=1.3)
    assert [(e.parameter, e.side) for e in found] == [
        ("body_height", "top"), ("foot_radius", "floor"), ("step_height", "floor"),
        ("duty_factor", "top")]
    assert [e.moved_by for e in found] == [
        "--body-high, up to 2 × the default gait's", None,
        "[codesign.constraints] min_foot_clearance", "--duty-high, up to 0.95"]
    assert found[0].value == pytest.approx(0.13)
    inside = {n: lo + (hi - lo) * (1 - 1 / 32) for n, (lo, hi) in space.bounds.items()}
    assert edges(space, dataclasses.replace(tripod, **inside)) == ()
    ceiling = default_space(tripod, 0.015, duty_high=DUTY_CEILING, body_high=2.0)
    at_ceiling = {"body_height": 0.2, "duty_factor": DUTY_CEILING}
    assert [e.moved_by for e in edges(ceiling, dataclasses.replace(tripod, **at_ceiling),
                                      duty_high=DUTY_CEILING, body_high=2.0)] == [None, None]
