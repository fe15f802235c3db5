import math

import pytest

from hexaleg.design.families import IDLE
from hexaleg.design.springs.table import magnitudes_table
from hexaleg.outputs.html import environment


def test_every_number_has_si_and_paper_units():
    t = magnitudes_table({"contact": 0.1, "side": "above"}, {"k": 2.0, "preload": 0.05},
                         "one_sided")
    assert t["side"] == "above"
    assert t["contact"]["paper"] == {"value": pytest.approx(math.degrees(0.1)), "unit": "deg"}
    assert t["k"]["si"] == {"value": 2.0, "unit": "N·m/rad"}
    assert t["k"]["paper"]["value"] == pytest.approx(2.0 * 1e3 * math.pi / 180)
    assert t["preload"]["paper"] == {"value": pytest.approx(50.0), "unit": "N·mm"}


def test_an_angle_past_which_nothing_acts_has_no_value():
    """The coxa's stiffening optimum: its second stages have zero stiffness, so their angles (the
    geometry search's leftovers, +0.373 rad) are no property of the design. design.json wrote
    them as numbers and design.html printed them; now null with the reason, and — on the page."""
    geometry = {"above_1": -0.049, "above_2": 0.373, "below_1": 0.049, "below_2": -0.373}
    magnitudes = {"k_above_1": 0.095, "k_above_2": 0.0, "k_below_1": 0.095, "k_below_2": 6.8e-10}
    t = magnitudes_table(geometry, magnitudes, "stiffening")
    for idle in ("above_2", "below_2"):
        assert t[idle] == {"si": {"value": None, "unit": "rad"},
                           "paper": {"value": None, "unit": "deg"}, "note": IDLE}
    assert t["above_1"]["si"] == {"value": -0.049, "unit": "rad"}
    assert t["k_above_2"]["si"] == {"value": 0.0, "unit": "N·m/rad"}  # the stiffness stays
    page = environment().from_string('{% import "design_macros.html.j2" as mc %}'
                                     "{{ mc.magnitudes(t) }}").render(t=t)
    assert "above_1 -2.807 deg, above_2 —, below_1 2.807 deg, below_2 —" in page
    assert page.count("(—: nothing acts past it: any angle gives the same spring)") == 1
    # a solver's zero (the stiffening tibia's 6.8e-10 N·m/rad) reads 0, as its angle reads —; the
    # page judged it in N·mm/deg and printed 0.00000001187 N·mm/deg beside the —
    assert "21.37" not in page and "k_below_2 0 N·mm/deg" in page
