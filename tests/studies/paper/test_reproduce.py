"""Tests of hexaleg.studies.paper.reproduce: the content of ``paper.json``."""

from __future__ import annotations

import json

import pytest

from hexaleg.studies.paper.joint import PaperJoint
from hexaleg.studies.paper.metrics import JOINT_METRICS
from hexaleg.studies.paper.readings import PAPER_K_E, PAPER_K_M

J0 = PaperJoint()


def test_k_M_in_both_units_and_the_papers_range(paper_result):
    r = paper_result
    assert r["k_M_paper_printed"] == PAPER_K_M
    assert r["k_M_paper_units"] == pytest.approx(713.544, abs=1e-3)
    assert r["k_M_SI_Nm_per_rad"] == J0.k_M()
    assert r["k_M_eq7_convention_SI_Nm_per_rad"] == pytest.approx(J0.k_M() / 1.05, rel=1e-15)
    lo, hi = r["paper_range_over_k_M_SI"]
    assert 8000 < lo < hi < 97000  # the simulated springs are ~10⁴ × k_M (docs/paper.md)
    assert r["model"]["samples_per_period"] == 256 and r["model"]["convention"] == "eq14"


def test_optima_closed_forms_verdicts_and_crosscheck(paper_result):
    r = paper_result
    assert set(r["optima"]) == {"no_gravity", "gravity_hanging", "gravity_upright"}
    for optima in r["optima"].values():
        assert tuple(optima) == JOINT_METRICS
    cf = r["closed_forms_no_gravity"]
    assert cf["int_sq"]["N_m_per_rad"] == J0.closed_form_int_sq()
    assert cf["peak_flat_interval_N_m_per_rad"] == list(J0.closed_form_peak_interval())
    assert r["k_E"]["paper_printed"] == PAPER_K_E and r["k_E"]["reproduced_by"] == []
    assert r["saving_52_81"]["reproduced_by"] == []
    assert "not reproduced" in r["saving_52_81"]["verdict"]
    assert r["pinocchio_check"]["max_relative_error"] <= 1e-9
    json.dumps(r)  # JSON-serialisable
