"""hexaleg simulate's inputs: the robot's own gait and servo, a config file's tables, the
command line over them, the default optimal springs or a design file."""

from __future__ import annotations

import json

import pytest

from hexaleg.commands.simulate.study import load_study
from hexaleg.design.chain.design_file import design_table
from hexaleg.errors import UnknownNameError
from hexaleg.scenario.scenario import Scenario


def test_defaults_are_the_optimal_femur_springs():
    study = load_study(Scenario.load("hexaleg"))
    assert set(study.springs) == set(study.prepared.robot.joints("femur"))
    assert "optimal linear springs on the femur" in study.design
    assert study.prepared.motor.name == "AX-18A" and study.settings.controller == "feedforward"


def test_config_tables_and_overrides(tmp_path, optimal):
    config = tmp_path / "c.toml"
    config.write_text('[gait]\nsamples = 500\n[springs]\ndesign = "paper"\n[simulate]\n'
                      'controller = "position"\ncycles = 3\nstiffness = 5e4\n')
    design = tmp_path / "d.json"
    design.write_text(json.dumps(design_table(optimal.springs)))
    study = load_study(Scenario.load("hexaleg", config), design, {"cycles": 5, "timestep": None})
    assert study.prepared.motion.n_samples == 500
    assert (study.settings.controller, study.settings.cycles, study.settings.stiffness) == \
        ("position", 5, 5e4)
    assert dict(study.springs) == dict(optimal.springs)
    assert any("[springs]" in note and "not simulated" in note for note in study.notes)


def test_an_unknown_table_key_is_named(tmp_path):
    config = tmp_path / "c.toml"
    config.write_text("[simulate]\nground = 1\n")
    with pytest.raises(UnknownNameError, match="ground"):
        load_study(Scenario.load("hexaleg", config))


def test_a_design_made_on_a_log_says_without_motion_that_the_gait_is_not_its_own(tmp_path,
                                                                                optimal):
    """A design.json of ``hexaleg design --motion walk.csv`` has no gait parameters to re-make;
    simulating it without --motion plays the generated gait, and the note says so and how to
    play the log instead (the design's gait.motion.path)."""
    design = tmp_path / "d.json"
    design.write_text(json.dumps({**design_table(optimal.springs),
                                  "gait": {"motion": {"source": "log", "path": "walk.csv",
                                                      "cycle": "auto"}}}))
    study = load_study(Scenario.load("hexaleg"), design)
    assert any("designed on the motion log walk.csv" in n and "give --motion walk.csv" in n
               for n in study.notes), study.notes
    plain = tmp_path / "p.json"
    plain.write_text(json.dumps(design_table(optimal.springs)))
    assert not any("motion log" in n for n in load_study(Scenario.load("hexaleg"), plain).notes)
