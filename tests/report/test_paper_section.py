"""Tests of hexaleg.report.paper_section: the paper's single-joint numbers on the report
come from the paper module."""

from __future__ import annotations

import pytest

from hexaleg.paper.joint import PaperJoint
from hexaleg.paper.readings import PAPER_K_M, k_M_paper_number


def _v(q):
    assert set(q) == {"value", "unit"}, q
    return q["value"]


def test_paper_reference_numbers_come_from_the_paper_module(data):
    p = data["paper"]
    assert _v(p["k_M_printed"]) == PAPER_K_M
    assert _v(p["k_M_paper_number"]) == pytest.approx(k_M_paper_number())
    assert _v(p["k_M"]) == pytest.approx(PaperJoint().k_M())
    assert p["k_M"]["unit"] == "N·m/rad"
    lo, hi = _v(p["peak_flat_interval"])
    assert lo == pytest.approx(PaperJoint().k_M())  # k_M is the lower end of the flat optimum
    assert hi > lo
    assert _v(p["peak_saving"]) == pytest.approx(100 * PaperJoint().closed_form_peak_saving())
    assert p["k_E_verdict"].startswith(("reproduced", "not reproduced"))
    assert p["saving_verdict"].startswith(("reproduced", "not reproduced"))
