"""Tests of hexaleg.paper.readings: the paper's printed numbers, its eq. 19 unit and the
readings of k_E and of the 52.81 % saving."""

from __future__ import annotations

import math

import pytest

from hexaleg.paper.joint import PaperJoint
from hexaleg.paper.readings import (
    PAPER_K_M,
    k_E_readings,
    k_M_paper_number,
    paper_number_to_si,
    si_to_paper_number,
    stiffness_units,
)

J0 = PaperJoint()


def test_k_M_paper_number_within_table6_rounding():
    # Table 6 rounding: m = 3.611e-2 ± 5e-6 kg, l = 47.141 ± 5e-4 mm, I = 107.059 ± 5e-4 kg·mm².
    m, l_mm, i_mm = 3.611e-2, 47.141, 107.059
    tol = 4 / 1.05 * (5e-6 * l_mm**2 + 2 * m * l_mm * 5e-4 + 5e-4)
    assert abs(k_M_paper_number() - 713.547) <= tol
    assert k_M_paper_number() == pytest.approx(4 * (m * l_mm**2 + i_mm) / 1.05, rel=1e-12)


def test_eq19_unit_is_1e6_of_SI():
    assert k_M_paper_number(J0) == pytest.approx(si_to_paper_number(J0.k_M()), rel=1e-12)
    assert paper_number_to_si(PAPER_K_M) == pytest.approx(PAPER_K_M * 1e-6, rel=1e-15)
    units = stiffness_units(J0.k_M())
    assert units["N_m_per_rad"] == J0.k_M()
    assert units["N_mm_per_deg"] == pytest.approx(J0.k_M() * 1000 * math.pi / 180, rel=1e-12)
    assert units["paper_number_kg_mm2_per_s2_rad"] == pytest.approx(713.544, abs=1e-3)


def test_eq21_from_contact_to_quarter_period_has_no_minimum():
    assert k_E_readings()["eq21_time_tk_to_quarter"]["k_SI"] is None
