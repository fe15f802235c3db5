"""``hexaleg simulate``: simulate.json with {value, unit} numbers, a design file, bad input."""

from __future__ import annotations

import json

import pytest

from hexaleg.cli import main
from hexaleg.simulation.motion_file import FILES, RUNS, read_motion


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    out = tmp_path_factory.mktemp("simulate")
    assert main(["simulate", "--cycles", "2", "--out", str(out)]) == 0
    return out, json.loads((out / "simulate.json").read_text())


def test_the_command_says_what_it_is_doing_unless_quiet(capsys, tmp_path):
    """Its stages on stderr — the inputs ready and what is simulated, then each run's verdict
    — before the answer on stdout (a 56-kg quadruped's simulate took 15 s quiet and printed
    nothing until the end); ``--quiet`` leaves the status lines out, not the answer."""
    args = ["simulate", "--cycles", "2", "--controller", "position"]
    assert main([*args, "--out", str(tmp_path / "a")]) == 0
    loud = capsys.readouterr()
    lines = [line for line in loud.err.splitlines() if line.startswith("hexaleg simulate: ")]
    assert len(lines) == 2, loud.err
    assert "simulating 2 cycles with the springs and without" in lines[0]
    assert "position servos" in lines[0]
    assert "simulated: springs walks, baseline walks" in lines[1]
    assert main([*args, "--quiet", "--out", str(tmp_path / "b")]) == 0
    quiet = capsys.readouterr()
    assert "hexaleg simulate: " not in quiet.err
    def answer(out):  # the answer line up to its timing
        return out.splitlines()[-2].split("× real time")[0].rsplit("; ", 1)[0]

    assert answer(quiet.out) == answer(loud.out) and "predicted saving" in answer(loud.out)


def _quantities(node, path=""):
    """Every {value, unit} leaf of a JSON tree, with its path."""
    if isinstance(node, dict) and set(node) == {"value", "unit"}:
        yield path, node
    elif isinstance(node, dict):
        for k, v in node.items():
            yield from _quantities(v, f"{path}.{k}")


def test_simulate_json_has_predicted_and_simulated_energies(written):
    out, data = written
    for side in ("predicted", "simulated"):
        for metric in ("electrical", "joule"):
            for key in ("with_springs", "baseline", "saving"):
                assert data[side][metric][key]["unit"] in ("J", "%")
        assert data[side]["saving"]["unit"] == "%"
    for key in ("distance_per_cycle", "planned_distance_per_cycle"):
        assert data[key]["unit"] == "m" and data[key]["value"] > 0.05
    assert data["realtime_factor"]["value"] > 1
    assert data["verdict"] == "walks"
    assert {(e["joint"], e["family"]) for e in data["springs"]} >= {("LF_femur", "linear")}
    assert all(q["unit"] for _, q in _quantities(data))
    page = (out / "simulate.md").read_text()
    assert "| electrical saving (%) |" in page and "walks" in page
    html = (out / "simulate.html").read_text()
    assert f"{data['simulated']['saving']['value']:+.2f} %" in html


def test_the_motion_of_each_run_is_written(written):
    """One file per run for ``hexaleg view --simulation``: 2 cycles of 1 s at 100 rows per s."""
    out, _ = written
    for run in RUNS:
        m = read_motion(out / FILES[run])
        assert (m.run, m.robot, len(m.t)) == (run, "hexaleg", 200)


def test_a_design_file_is_simulated(written, tmp_path, capsys):
    """The default run's springs (the report's answer), written as a design file, give its
    prediction back."""
    _, default = written
    path = tmp_path / "design.json"
    path.write_text(json.dumps({"robot": "hexaleg", "springs": default["springs"]}))
    out = tmp_path / "out"
    assert main(["simulate", "--springs", str(path), "--cycles", "2", "--controller", "position",
                 "--out", str(out)]) == 0
    data = json.loads((out / "simulate.json").read_text())
    assert data["predicted"]["saving"] == pytest.approx(default["predicted"]["saving"])
    assert data["controller"] == "position" and str(path) in data["design"]
    assert "position servo" in capsys.readouterr().out


@pytest.mark.parametrize("args, message", [
    (["--timestep", "0.001"], "sample spacing"),
    (["--cycles", "1"], "cycles"),
])
def test_bad_input_is_a_named_error(args, message, tmp_path, capsys):
    assert main(["simulate", *args, "--out", str(tmp_path)]) == 2
    assert message in capsys.readouterr().err


def test_a_design_for_another_robot_is_refused(tmp_path, capsys):
    path = tmp_path / "design.json"
    path.write_text(json.dumps({"robot": "solo12", "springs": {}}))
    assert main(["simulate", "--springs", str(path), "--out", str(tmp_path)]) == 2
    assert "solo12" in capsys.readouterr().err


def test_config_simulate_table_is_checked(tmp_path, capsys):
    config = tmp_path / "c.toml"
    config.write_text("[simulate]\ntimestpe = 1e-4\n")
    assert main(["simulate", "--config", str(config), "--out", str(tmp_path)]) == 2
    assert "timestpe" in capsys.readouterr().err


def test_controller_choices_are_the_controllers_and_mujoco_loads_lazily():
    """``simulate --controller`` offers :data:`CONTROLLERS`, spelled out in the parser so that
    neither building it, ``import hexaleg`` nor ``import hexaleg.commands.simulate`` loads MuJoCo
    (it is imported where a model is built)."""
    import argparse
    import subprocess
    import sys

    from hexaleg.cli import build_parser
    from hexaleg.simulation.controllers import CONTROLLERS

    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    choices = {a.dest: a.choices for a in sub.choices["simulate"]._actions}
    assert tuple(choices["controller"]) == CONTROLLERS
    code = ("import sys, hexaleg, hexaleg.commands.simulate, hexaleg.cli as c; c.build_parser(); "
            "print('mujoco' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "False"


def test_unknown_controller_is_refused_by_the_parser(capsys):
    with pytest.raises(SystemExit):
        main(["simulate", "--controller", "pid"])
    assert "feedforward" in capsys.readouterr().err
