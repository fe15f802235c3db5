"""design.json: springs per joint as family and parameters, read back exactly; bad files named."""

from __future__ import annotations

import json

import numpy as np
import pytest

from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.robot.springs import SpringSet
from hexaleg.studies.simulate.design_file import design_table, read_design

from ...simulation.test_springs import FAMILIES


def _write(tmp_path, data) -> str:
    path = tmp_path / "design.json"
    path.write_text(json.dumps(data))
    return str(path)


@pytest.mark.parametrize("family", FAMILIES)
def test_every_family_round_trips(family, tmp_path, robot, walk):
    springs = SpringSet({"LF_femur": FAMILIES[family][0], "RH_tibia": FAMILIES[family][0]})
    back = read_design(_write(tmp_path, design_table(springs, "hexaleg")), robot, "hexaleg")
    assert dict(back) == dict(springs)
    assert np.array_equal(back.torques(robot, walk.q[:50]), springs.torques(robot, walk.q[:50]))


def test_paper_units_are_converted(tmp_path, robot):
    data = {"springs": [{"family": "dead_zone", "joint": "LF_femur", "parameters": {
        "stiffness": {"value": 400, "unit": "N·mm/deg"}, "theta_k": {"value": 7.32, "unit": "deg"},
        "damping": {"value": 1, "unit": "N·mm·s/deg"}, "convention": "eq14"}}]}
    spring = read_design(_write(tmp_path, data), robot)["LF_femur"]
    assert spring.stiffness == pytest.approx(400 * 1e-3 * 180 / np.pi)
    assert spring.theta_k == pytest.approx(np.deg2rad(7.32))
    assert spring.convention == "eq14"


@pytest.mark.parametrize("data, error, match", [
    ({"robot": "solo12", "springs": {}}, InvalidParameterError, "solo12"),
    ({"springs": {"LF_femur": {"family": "coil", "parameters": {}}}}, UnknownNameError, "coil"),
    ({"springs": {"LF_femur": {"family": "linear", "parameters": {
        "k": {"value": 1, "unit": "N·m/rad"}}}}}, UnknownNameError, "'k'"),
    ({"springs": {"LF_femur": {"family": "linear", "parameters": {
        "stiffness": {"value": 1, "unit": "N/m"}}}}}, ConfigError, "N/m"),
    ({"robot": {"name": "go2"}, "recommended": {"springs": []}}, InvalidParameterError, "go2"),
    ({"springs": [{"family": "linear", "parameters": {}}]}, ConfigError, "joint"),
    ({"springs": {"LF_femur": {"family": "linear", "parameters": {
        "stiffness": {"value": -1, "unit": "N·m/rad"}}}}}, InvalidParameterError, "stiffness"),
    ({"springs": {"LF_knee": {"family": "linear", "parameters": {
        "stiffness": {"value": 1, "unit": "N·m/rad"}}}}}, UnknownNameError, "LF_knee"),
    ({"springs": {"LF_femur": {"family": "linear", "parameters": {"stiffness": 1.0}}}},
     ConfigError, "unit"),
    ({"designs": {}}, ConfigError, "springs"),
    ({"springs": [{"family": "linear", "joint": "LF_femur", "parameters": {
        "stiffness": {"value": 1, "unit": "N·m/rad"}}}] * 2}, ConfigError,
     "two springs on LF_femur"),
])
def test_bad_design_files_are_named(data, error, match, tmp_path, robot):
    with pytest.raises(error, match=match):
        read_design(_write(tmp_path, data), robot, "hexaleg")


def test_the_design_json_of_hexaleg_design(tmp_path, robot, optimal):
    """``hexaleg design`` writes its recommended springs as spring_json entries: read those."""
    from hexaleg.design.spring_json import spring_entry

    data = {"robot": {"name": "hexaleg", "title": "…"}, "candidates": [],
            "recommended": {"label": "test", "springs": [spring_entry(j, s) for j, s in
                                                         optimal.springs.items()]}}
    assert dict(read_design(_write(tmp_path, data), robot, "hexaleg")) == dict(optimal.springs)


def test_missing_or_broken_files_are_config_errors(tmp_path, robot):
    with pytest.raises(ConfigError, match="not found"):
        read_design(tmp_path / "none.json", robot)
    (tmp_path / "bad.json").write_text("{")
    with pytest.raises(ConfigError, match="cannot read"):
        read_design(tmp_path / "bad.json", robot)
