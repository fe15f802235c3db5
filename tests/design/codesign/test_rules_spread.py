"""How far the springs to buy move with the motion they were designed on: the same design named
the same on every repeat, its figures' ranges by kind, a repeat that buys other springs or none
counted apart."""

from __future__ import annotations

import dataclasses
import math

from hexaleg.design.codesign.rules_spread import KINDS, bought, rules_spread


def _moved(r, stop_by: float = 0.0, diameter_by: float = 0.0, wire_by: float = 0.0):
    """``r`` with its first part's hard stop, coil diameter and wire moved (rad, m, m)."""
    e0, *envelope = r.envelope
    (p0, f0), *fatigue = r.fatigue
    if e0.stop is not None:
        e0 = dataclasses.replace(e0, stop=dataclasses.replace(
            e0.stop, angle_from_centre=e0.stop.angle_from_centre + stop_by))
    spring = dataclasses.replace(p0.spring, mean_diameter=p0.spring.mean_diameter + diameter_by,
                                 wire_diameter=p0.spring.wire_diameter + wire_by)
    return dataclasses.replace(r, envelope=(e0, *envelope),
                               fatigue=((dataclasses.replace(p0, spring=spring), f0), *fatigue))


def test_the_springs_to_buy_move_by_their_repeats_ranges(ruled):
    """On a design and four repeats: the design itself (nothing moves), one whose first part's
    coil is 0.03 mm wider and its stop 0.5° further, one whose wire is another size (other
    springs: counted, its figures left out of the ranges), and one whose alternation kept the
    gait. The line says 2 of 4 buy the same springs, the coil diameter moves by 0.03 mm and the
    hard stop by 0.5° (where the part has one), the savings by 0; codesign.json holds it.
    Catches ranges taken over a repeat that buys other springs, a repeat without a design
    counted as the same, a range of zero said where no repeat was compared, or a figure moved
    in the wrong unit (m for mm, rad for °)."""
    answer = ruled.rules
    stride = ruled.chosen.stride
    mine = bought(answer, stride)
    assert mine is not None and mine.names[0] == answer.recommended.family
    wider = _moved(answer, stop_by=math.radians(0.5), diameter_by=3e-5)
    other = _moved(answer, wire_by=1e-4)
    spread = rules_spread(answer, [answer, wider, other, None], (-2e-9, -1e-9, 1e-9, 2e-9),
                          stride)
    assert spread is not None
    assert spread.same == (True, True, False, None)
    assert spread.why == ("", "", "", "the repeat kept the gait")
    assert set(spread.moved) <= set(KINDS) and list(spread.moved) == [
        k for k in KINDS if k in spread.moved]
    assert math.isclose(spread.moved["coil diameter"], 0.03, rel_tol=1e-9)
    if answer.envelope[0].stop is not None:
        assert math.isclose(spread.moved["hard stop"], 0.5, rel_tol=1e-9)
    assert spread.moved["saving"] == spread.moved["net saving"] == 0.0
    line = spread.line()
    assert line.startswith("on the row's repeats (its start moved by -2e-09, -1e-09, +1e-09, "
                           "+2e-09 m) the full rules buy the same springs (family, groups, each "
                           "part's wire and turns) on 2 of 4 (the repeat kept the gait)")
    assert "coil diameter 0.03 mm" in line and line.endswith("not the method's")
    data = spread.data()
    assert data["said"] == line and data["same"] == [True, True, False, None]
    assert data["moved"]["coil diameter"] == {"value": spread.moved["coil diameter"],
                                              "unit": "mm"}
    assert rules_spread("NumericalError: no design", [answer], (1e-9,), stride) is None
    failed = rules_spread(answer, ["NumericalError: no design"], (1e-9,), stride)
    assert failed is not None and failed.same == (None,)
    assert failed.why == ("no design on a repeat: NumericalError: no design",)
    assert failed.moved == {}  # nothing measured: no range said
    assert failed.line().endswith("on 0 of 1 (no design on a repeat: NumericalError: no design)")
