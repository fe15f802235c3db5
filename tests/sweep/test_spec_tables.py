"""Tests of hexaleg.sweep.spec_tables: each table of a spec file read into SI values,
and its bad keys named with the valid choices (the spec built from them: test_spec.py)."""

from __future__ import annotations

import pytest

from hexaleg.errors import ConfigError, UnknownNameError
from hexaleg.sweep.spec_tables import gait_table, spring_tables, sweep_table
from hexaleg.units import deg_to_rad, nmm_per_deg_to_nm_per_rad


def test_the_sweep_table_splits_the_run_from_the_sweep_keys():
    run, rest = sweep_table({"sweep": {"robot": "solo12", "metric": "joule", "chunk_size": 3},
                             "contact": {"mu": 0.4}}, "spec.toml")
    assert run.robot == "solo12" and run.contact.mu == 0.4
    assert rest == {"metric": "joule", "chunk_size": 3}
    with pytest.raises(UnknownNameError, match=r"key in spec.toml \[sweep\] 'metrik'.*metric"):
        sweep_table({"sweep": {"metrik": "joule"}}, "spec.toml")


def test_gait_values_and_samples_as_integers():
    gait = gait_table({"period": [0.5, 1.0], "samples": [40.0, 80.0], "step_height": 0.02})
    assert gait == {"period": (0.5, 1.0), "samples": (40, 80), "step_height": 0.02}
    assert all(isinstance(n, int) for n in gait["samples"])


def test_paper_units_become_si_and_joints_are_kept():
    springs, joints = spring_tables({"femur": {"k_nmm_per_deg": [10.0, 20.0],
                                               "theta_k_deg": 5.0},
                                     "front": {"joints": ["LF_coxa"], "k": 0.1, "dead_zone": 0.5}},
                                    "spec.toml")
    assert springs["femur"]["k"] == pytest.approx(tuple(nmm_per_deg_to_nm_per_rad([10.0, 20.0])))
    assert springs["femur"]["theta_k"] == pytest.approx(deg_to_rad(5.0))
    assert springs["front"] == {"k": 0.1, "dead_zone": 0.5} and joints == {"front": ("LF_coxa",)}


@pytest.mark.parametrize(("tables", "error", "match"), [
    ({"femur": 1.0}, ConfigError, r"\[springs.femur\]: expected a table"),
    ({"femur": {"joints": []}}, ConfigError, r"springs.femur.joints = \[\]; expected a non-empty"),
    ({"femur": {"theta_kk": 0.1}}, UnknownNameError, r"theta_kk.*theta_k_deg"),
    ({"femur": {"theta_k": 0.1, "theta_k_deg": 5.0}}, ConfigError, r"theta_k given twice")])
def test_bad_spring_tables_are_named(tables, error, match):
    with pytest.raises(error, match=match):
        spring_tables(tables, "spec.toml")
