"""Tests of hexaleg.robot.builder: one source of truth for the committed URDF/SRDF."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexaleg.errors import ConfigError
from hexaleg.robot.builder import build, build_srdf, build_urdf, femur_si, load_params

REPO_URDF = Path(__file__).resolve().parents[2] / "urdf"


def test_committed_files_equal_a_fresh_build():
    params = load_params(REPO_URDF / "hexaleg.toml")
    assert (REPO_URDF / "hexaleg.urdf").read_text() == build_urdf(params), (
        "urdf/hexaleg.urdf is stale: run `python -m hexaleg.robot.builder`")
    assert (REPO_URDF / "hexaleg.srdf").read_text() == build_srdf(params), (
        "urdf/hexaleg.srdf is stale: run `python -m hexaleg.robot.builder`")


def test_build_writes_both_files(tmp_path):
    urdf, srdf = build(REPO_URDF / "hexaleg.toml", tmp_path)
    assert urdf.read_text().startswith('<?xml version="1.0"?>\n<robot name="hexaleg">')
    assert "group_state" in srdf.read_text()


def test_femur_is_converted_from_paper_units():
    f = femur_si(load_params(REPO_URDF / "hexaleg.toml"))
    assert f["length"] == pytest.approx(0.084)
    assert f["com"] == pytest.approx(0.047141)
    assert f["inertia_axis_com"] == pytest.approx(107.059e-6)


def test_bad_parameter_files(tmp_path):
    with pytest.raises(ConfigError, match="not found"):
        load_params(tmp_path / "missing.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("name = [")
    with pytest.raises(ConfigError, match="not valid TOML"):
        load_params(bad)
