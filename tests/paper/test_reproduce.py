"""Tests of hexaleg.paper.reproduce: the content of ``paper.json``."""

from __future__ import annotations

import json
import math

import pytest

from hexaleg.paper.joint import PaperJoint
from hexaleg.paper.metrics import JOINT_METRICS
from hexaleg.paper.readings import PAPER_K_E, PAPER_K_M

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


def test_simulation_section_keys_units_and_the_librarys_optimum(forward):
    """``paper.json["simulation"]``: every number a quantity in SI (stiffnesses also in eq. 19
    units), the optimum the library's, the unit question stated."""
    from hexaleg.paper.forward import COLUMNS, NAMED
    from hexaleg.paper.readings import EQ19_UNIT, paper_number_to_si
    from hexaleg.paper.reproduce import simulation_section

    sim = simulation_section(forward)
    json.dumps(sim)
    assert set(sim) == {"columns", "unit_question", "model", "grid", "curves",
                        "required_torque", "optima", "period_check"}
    assert tuple(sim["columns"]) == COLUMNS
    assert "N·mm/deg" in sim["unit_question"] and EQ19_UNIT in sim["unit_question"]
    assert sim["grid"]["k_paper"] == {"value": list(forward.grid), "unit": EQ19_UNIT}
    assert sim["grid"]["k"]["unit"] == "N·m/rad"
    assert sim["model"]["contact_stiffness"]["unit"] == "N/m^2.2"
    assert sim["model"]["timestep"] == {"value": 2e-4, "unit": "s"}
    units = {"mean_abs": "N·m", "epsilon": "1/s²"}
    for name, curve in sim["curves"].items():
        for c in COLUMNS:
            assert curve[c]["unit"] == curve["at_k_0"][c]["unit"] == units[name]
            assert curve[c]["value"] == list(forward.curves[name][COLUMNS.index(c)])
    assert list(sim["required_torque"]) == [key for key, _, _ in NAMED]
    assert sim["required_torque"]["rigid"]["peak"]["simulated"]["unit"] == "N·m"
    for name, o in forward.optima.items():
        section = sim["optima"][name]
        for column, k in (("analytic_closed_form", o.closed_form), ("simulated", o.simulated),
                          ("friction", o.friction), ("paper_adams_reading", o.paper),
                          ("paper_printed", o.printed)):
            assert section[column]["k_paper"] == {"value": k, "unit": EQ19_UNIT}
            assert section[column]["k"] == {"value": paper_number_to_si(k), "unit": "N·m/rad"}
        assert section["simulated"]["bracketed"] == o.bracketed[0]
        assert section["saving_at_grid_best"]["friction"] == {"value": 100 * o.saving[2],
                                                              "unit": "%"}
    labelled = sim["optima"]["mean_abs"]["paper_adams_reading"]["read_as_N_mm_per_deg"]
    assert labelled == {"value": pytest.approx(740 * 1e-3 * 180 / math.pi), "unit": "N·m/rad"}
