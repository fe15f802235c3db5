import math

import pytest

from hexaleg.design.springs.table import magnitudes_table


def test_every_number_has_si_and_paper_units():
    t = magnitudes_table({"contact": 0.1, "side": "above"}, {"k": 2.0, "preload": 0.05})
    assert t["side"] == "above"
    assert t["contact"]["paper"] == {"value": pytest.approx(math.degrees(0.1)), "unit": "deg"}
    assert t["k"]["si"] == {"value": 2.0, "unit": "N·m/rad"}
    assert t["k"]["paper"]["value"] == pytest.approx(2.0 * 1e3 * math.pi / 180)
    assert t["preload"]["paper"] == {"value": pytest.approx(50.0), "unit": "N·mm"}
