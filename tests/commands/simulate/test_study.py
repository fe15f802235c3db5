"""hexaleg simulate's inputs: the robot's own gait and servo, a config file's tables, the
command line over them, the default optimal springs or a design file."""

from __future__ import annotations

import json

import pytest

from hexaleg.commands.simulate.study import load_study
from hexaleg.design.chain.design_file import design_table
from hexaleg.errors import UnknownNameError
from hexaleg.scenario.scenario import Scenario


def test_defaults_are_the_report_s_answer():
    """Plain ``hexaleg simulate`` simulates the springs ``hexaleg report`` leads with (#43):
    the same springs, and a prediction within 0.2 point of the report's saving on its gait."""
    from hexaleg.report.build import build_report

    study = load_study(Scenario.load("hexaleg"))
    robot = study.prepared.robot
    assert set(study.springs) == set(robot.joints("femur")) | set(robot.joints("tibia"))
    assert study.design.startswith("hexaleg report's quick answer: linear springs on femur, "
                                   "tibia")
    assert study.prepared.motor.name == "AX-18A" and study.settings.controller == "feedforward"
    report = build_report()
    answer = report.data["design"]
    assert dict(study.springs) == dict(report.analysis.springs)
    predicted = 100 * study.prepared.evaluate(study.springs, study.objective).savings[
        "total"]["electrical"]
    assert predicted == pytest.approx(answer["report_gait"]["saving"]["value"], abs=1e-9)
    assert predicted == pytest.approx(answer["saving"]["value"], abs=0.2)


def test_without_a_report_answer_the_optimal_linear_springs_with_a_note(tmp_path):
    """A run the report has no answer for (a payload) simulates the optimal linear springs on
    the spring class and says why."""
    config = tmp_path / "c.toml"
    config.write_text("[payload]\nmass = 0.1\n")
    study = load_study(Scenario.load("hexaleg", config))
    assert set(study.springs) == set(study.prepared.robot.joints("femur"))
    assert "optimal linear springs on the femur" in study.design
    assert any("payload" in n for n in study.notes), study.notes
    assert any("hexaleg report has no answer on this run" in n for n in study.notes)


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


def test_docs_quote_what_plain_simulate_gives():
    """docs/simulate.md's numbers of plain ``hexaleg simulate`` (predicted and simulated saving
    of the report's answer, feedforward + PD, the default 4 cycles): the prediction to its
    printed digits, the simulation within 0.15 % of its value (a forward simulation's
    tolerance across floating-point paths, tests/test_examples.py)."""
    import re
    from pathlib import Path

    text = " ".join((Path(__file__).resolve().parents[3] / "docs" / "simulate.md").read_text()
                    .split())
    m = re.search(r"predicted ([+−-][\d.]+) % as the report says, simulated ([+−-][\d.]+) % "
                  r"under feedforward \+ PD servos", text)
    assert m, "docs/simulate.md no longer quotes plain hexaleg simulate's saving"
    predicted, simulated = (float(g.replace("−", "-")) for g in m.groups())
    s = load_study(Scenario.load("hexaleg")).run()
    assert f"{100 * s.predicted()[2]:+.2f}" == f"{predicted:+.2f}"
    assert 100 * s.simulated()[2] == pytest.approx(simulated, rel=1.5e-3, abs=0.005)
