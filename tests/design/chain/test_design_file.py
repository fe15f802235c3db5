"""design.json: springs per joint as family and parameters, read back exactly; bad files named."""

from __future__ import annotations

import json
import os

import numpy as np
import pytest

import hexaleg
from hexaleg.commands.simulate.study import load_study
from hexaleg.design.chain.design_file import design_table, read_design
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.robot.springs import SpringSet
from hexaleg.scenario.scenario import Scenario

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
    ({"designs": {}}, UnknownNameError,
     "unknown key in the design file .* .designs.; valid keys.*gait, robot, springs"),
    ({"springs": [{"family": "linear", "joint": "LF_femur", "parameters": {
        "stiffness": {"value": 1, "unit": "N·m/rad"}}}] * 2}, ConfigError,
     "two springs on LF_femur"),
])
def test_bad_design_files_are_named(data, error, match, tmp_path, robot):
    with pytest.raises(error, match=match):
        read_design(_write(tmp_path, data), robot, "hexaleg")


def test_the_design_json_of_hexaleg_design(tmp_path, robot, optimal):
    """``hexaleg design`` writes its recommended springs as spring_json entries: read those."""
    from hexaleg.design.springs.law_json import spring_entry

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


def test_design_files_get_the_checks_config_files_get(tmp_path, robot):
    """--springs /dev/zero used to fill memory, a named pipe to hang: refused by name."""
    fifo = tmp_path / "design.json"
    os.mkfifo(fifo)
    for path in ("/dev/zero", fifo, tmp_path):
        with pytest.raises(ConfigError, match=r"is not a regular file"):
            read_design(path, robot)
    nan = tmp_path / "nan.json"
    nan.write_text('{"springs": {"LF_femur": {"family": "linear", "parameters": '
                   '{"stiffness": {"value": NaN, "unit": "N·m/rad"}}}}}')
    with pytest.raises(ConfigError, match=r"NaN is not a JSON number"):
        read_design(nan, robot)


@pytest.mark.parametrize("data", [
    {"robot": {"name": "hexaleg"}, "recommended": {"label": "x"}},
    {"robot": {"name": "hexaleg"}, "recommended": {"label": "x", "springs": []}},
    {"robot": "hexaleg", "springs": []}, {"springs": {}}])
def test_a_design_without_springs_is_refused(tmp_path, robot, data):
    """A design.json with its springs removed used to simulate as a "springs" run with none."""
    with pytest.raises(ConfigError, match=r"no springs .*at least one spring"):
        read_design(_write(tmp_path, data), robot)


def test_a_one_sided_spring_beyond_the_joint_range_is_refused_in_files(tmp_path, robot):
    """Degrees written as radians: the contact at 90 rad lies beyond the femur's range."""
    data = {"springs": [{"family": "one_sided", "joint": "LF_femur", "parameters": {
        "stiffness": {"value": 0.5, "unit": "N·m/rad"}, "contact": {"value": 90.0, "unit": "rad"},
        "side": "above"}}]}
    with pytest.raises(InvalidParameterError, match=r"OneSidedSpring on LF_femur .*acts above "
                                                    r"90 rad.*can never engage"):
        read_design(_write(tmp_path, data), robot)


def test_a_design_reads_back_as_its_springs_gait_and_saving(design_written):
    result, out = design_written[0].result, design_written[1]
    d = hexaleg.load_design(out / "design.json")
    assert d.robot == "hexaleg" and d.metric == "electrical" and d.pays is True
    assert d.gait == result.gait
    assert set(d.springs) == set(result.recommended.optimum.springs)
    for j, s in result.recommended.optimum.springs.items():
        assert d.springs[j] == s
    assert d.saving == pytest.approx(result.recommended.row["saving.electrical"], rel=1e-12)


def test_simulate_predicts_the_designs_own_saving(design_written):
    """One gait sampling: the study of ``hexaleg simulate --springs design.json`` runs on the
    design's gait (its samples), so its prediction is the design's to the last digits."""
    result, out = design_written[0].result, design_written[1]
    study = load_study(Scenario.load(), springs=out / "design.json")
    assert study.prepared.motion.n_samples == result.gait.samples
    predicted = study.prepared.evaluate(study.springs, "joule").savings["total"]["electrical"]
    assert predicted == pytest.approx(result.recommended.row["saving.electrical"], abs=5e-4)
    assert any("the gait of the design file" in n for n in study.notes)


def test_a_config_gait_replaces_the_designs_and_says_so(design_written, tmp_path):
    out = design_written[1]
    config = tmp_path / "c.toml"
    config.write_text("[gait]\nsamples = 100\n")
    study = load_study(Scenario.load(config=config), springs=out / "design.json")
    assert study.prepared.motion.n_samples == 100
    assert any("replaces it here (100 samples)" in n for n in study.notes)


@pytest.mark.parametrize(("edit", "error", "says"), [
    (lambda d: d["gait"].update(parameters=[1, 2]), ConfigError, "gait.parameters"),
    (lambda d: d["gait"]["parameters"]["period"].update(value=-1.0), InvalidParameterError,
     "period"),
    (lambda d: d["gait"]["parameters"]["period"].update(unit="ms"), InvalidParameterError,
     "period.unit"),
    (lambda d: d["gait"]["parameters"].update(speeed=1.0), UnknownNameError, "speeed"),
    (lambda d: d["recommended"]["saving"]["electrical"].update(value="nan"),
     InvalidParameterError, "saving"),
    (lambda d: d["robot"].update(name="solo12"), InvalidParameterError, "robot"),
    (lambda d: d["recommended"].update(saving=15.4), InvalidParameterError,
     r"recommended\.saving = 15\.4"),
])
def test_a_damaged_design_file_is_named(design_written, tmp_path, edit, error, says):
    data = json.loads((design_written[1] / "design.json").read_text())
    edit(data)
    path = tmp_path / "design.json"
    path.write_text(json.dumps(data))
    with pytest.raises(error, match=says):
        hexaleg.load_design(path, robot="hexaleg")


def test_a_missing_or_unreadable_file_is_named(tmp_path):
    with pytest.raises(ConfigError, match="not found"):
        hexaleg.load_design(tmp_path / "none.json")
    (tmp_path / "bad.json").write_text("{")
    with pytest.raises(ConfigError, match="cannot read"):
        hexaleg.load_design(tmp_path / "bad.json")


def test_every_numeric_gait_field_has_its_unit():
    """A numeric field added to GaitParams must get its unit here (design.json's rule)."""
    import dataclasses

    from hexaleg.design.chain.design_file import GAIT_UNITS

    numeric = {f.name for f in dataclasses.fields(hexaleg.GaitParams)
               if any(t in str(f.type) for t in ("float", "tuple[float"))}
    assert numeric == set(GAIT_UNITS)


def test_a_gait_with_a_speed_is_written_with_the_stride_it_walks():
    """#41: codesign.json wrote a co-designed gait's stride_length as its unused default
    (0.06 m) where it walks speed × period = 0.102 m a cycle; read back, it walks the same."""
    from hexaleg.design.chain.design_file import design_gait, gait_parameters
    from hexaleg.motion.params import GaitParams

    gait = GaitParams(speed=0.06, period=1.7)
    params = gait_parameters(gait)
    assert params["stride_length"] == {"value": pytest.approx(0.102), "unit": "m"}
    back = design_gait({"gait": {"parameters": params}}, "hexaleg", "test")
    assert back is not None and back.stride == pytest.approx(gait.stride)
    assert back.period == gait.period and back.speed == gait.speed
