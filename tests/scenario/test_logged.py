"""``--motion FILE`` on ``hexaleg report``, ``design`` and ``simulate``: a log of a hexaleg gait
(written by ``write_motion_log``, one cycle at 100 samples) designs, simulates and reports as the
generated gait does; the gait parameters that no longer apply are refused by name."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import hexaleg
from hexaleg.cli import main
from hexaleg.design.chain.chain import DesignChain
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.recorded.write import write_motion_log
from hexaleg.scenario.logged import parse_cycle
from hexaleg.scenario.scenario import Scenario

SAMPLES = 100
FAMILIES = ["linear", "one_sided"]
DESIGN = {"families": FAMILIES, "pareto_fractions": [0.5]}
"""Two families, one Pareto point: the fast design of these tests."""


@pytest.fixture(scope="module")
def log(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The default robot's gait at 100 samples per cycle, written as a CSV log (one cycle)."""
    robot = hexaleg.load()
    motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=SAMPLES))
    return write_motion_log(robot, motion, tmp_path_factory.mktemp("log") / "log.csv")


def _config(path: Path, text: str) -> str:
    path.write_text(text, encoding="utf-8")
    return str(path)


def _numbers_have_units(tree: object) -> None:
    """Every number of ``motion_quality`` is ``{value, unit}``."""
    if isinstance(tree, dict):
        if "unit" in tree:
            assert set(tree) == {"value", "unit"} and isinstance(tree["unit"], str)
            return
        for v in tree.values():
            _numbers_have_units(v)
    elif isinstance(tree, list):
        for v in tree:
            assert not isinstance(v, (int, float)) or isinstance(v, bool)
    else:
        assert not isinstance(tree, (int, float)) or isinstance(tree, bool), tree


@pytest.mark.slow  # 17 s: the README suite stays within its 5 minutes
def test_design_on_the_log_equals_the_design_on_the_generated_gait(log: Path, tmp_path: Path,
        capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    from hexaleg.scenario import logged

    reads: list[str] = []
    read = logged.load_motion
    monkeypatch.setattr(logged, "load_motion", lambda *a, **k: reads.append(a[1]) or read(*a, **k))
    toml = "[design]\nfamilies = " + json.dumps(FAMILIES) + "\npareto_fractions = [0.5]\n"
    config = _config(tmp_path / "c.toml", toml)
    out = tmp_path / "design"
    assert main(["design", "--config", config, "--motion", str(log), "--cycle", "whole",
                 "--out", str(out)]) == 0
    assert [str(r) for r in reads] == [str(log)]  # read once: the run's reading is the design's
    printed = capsys.readouterr().out
    assert "motion: log" in printed and "robustness maps and the robust design are left out" \
        not in printed  # the note is in design.json, the summary says it briefly
    assert "no robustness maps (logged motion)" in printed
    data = json.loads((out / "design.json").read_text(encoding="utf-8"))
    assert data["maps"] == [] and data["robust"] is None
    assert any("logged motion (--motion) has none to vary" in n for n in data["notes"])
    quality = data["motion_quality"]
    _numbers_have_units(quality)
    assert quality["period"] == {"value": pytest.approx(1.0, rel=1e-12), "unit": "s"}
    assert quality["stance_source"] == "plan" and quality["derivatives"] == "given"
    # design.json says the motion came from the log, not generated gait parameters
    gait = data["gait"]
    assert "parameters" not in gait and gait["motion"]["source"] == "log"
    assert gait["motion"]["path"] == str(log) and gait["motion"]["cycle"] == "whole"
    assert gait["motion"]["quality"] == quality and gait["samples"] == SAMPLES
    assert gait["stride"]["value"] == pytest.approx(0.06, rel=1e-9)
    assert gait["duty_factor"]["value"] == pytest.approx(0.5)
    assert hexaleg.load_design(out / "design.json").gait is None
    # The invariant: the same springs as on the generated gait it was written from.
    generated = DesignChain(Scenario.from_tables(
        "hexaleg",
        {"design": {**DESIGN, "samples": SAMPLES, "map_period": [1.0], "map_stride": [1.0],
                    "map_payload": [0.0], "map_mu": [0.6], "map_slope": [0.0],
                    "robust_period": [1.0, 1.0], "robust_stride": [1.0, 1.0],
                    "robust_payload": [0.0, 0.0], "robust_mu": [0.6, 0.6]}})).run()
    rec, gen = data["recommended"], generated.recommended
    assert rec["family"] == gen.family
    # %: the worst case over the stops' shifts is minimised (to the bundle's tolerance), and its
    # minimiser need not be unique: from starts that differ in the last bits (the log's samples
    # against the generated ones) the electrical saving agrees to 1e-4 points, the Joule saving,
    # which nothing minimises, to 1e-3 (3.7e-4 measured)
    for m, tol in (("electrical", 1e-4), ("joule", 1e-3)):
        assert data["baseline"][m]["value"] == pytest.approx(generated.baseline[m], rel=1e-9)
        assert rec["saving"][m]["value"] == pytest.approx(100 * gen.row[f"saving.{m}"], abs=tol)
        # net of the springs' mass: the log carried as logged, the same motion as generated
        assert rec["net_saving"][m]["value"] == pytest.approx(100 * gen.net[m], abs=tol)


def test_simulate_plays_the_log_forward(log: Path, tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "sim"
    status = main(["simulate", "--motion", str(log), "--cycle", "whole", "--cycles", "2",
                   "--out", str(out)])
    data = json.loads((out / "simulate.json").read_text(encoding="utf-8"))
    printed = capsys.readouterr().out
    assert "motion: log" in printed and "note: the motion is the log" in printed
    assert data["predicted"]["electrical"]["baseline"]["unit"] == "J"
    assert status == (0 if data["verdict"] == "walks" else 2)
    if data["verdict"] == "walks":
        assert data["simulated"]["electrical"]["with_springs"]["value"] > 0
    for run in ("springs", "baseline"):
        assert data["runs"][run]["verdict"] in ("walks", "fell", "drifted", "stalled",
                                                "did not walk") or data["runs"][run]["message"]
    _numbers_have_units(data["motion_quality"])
    assert data["motion_quality"]["rows"] == {"value": SAMPLES, "unit": "rows"}


def test_report_writes_its_files_on_the_log(log: Path, tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    config = _config(tmp_path / "c.toml", "[report]\nstiffness_points = 3\npaper_samples = 64\n")
    out = tmp_path / "report"
    assert main(["report", "--config", config, "--motion", str(log), "--cycle", "whole",
                 "--out", str(out)]) == 0
    assert "motion: log" in capsys.readouterr().out
    assert (out / "report.html").is_file()
    data = json.loads((out / "report.json").read_text(encoding="utf-8"))
    _numbers_have_units(data["motion_quality"])
    assert data["motion_quality"]["cycle"] == "whole"
    # the logged cycle is what was analysed: its samples, and the baseline of the same gait
    # generated at that sampling (the log is a hexaleg gait written out)
    assert data["gait"]["samples"] == SAMPLES and data["gait"]["logged"]
    robot = hexaleg.load()
    generated = hexaleg.prepare(robot, hexaleg.gait(robot, hexaleg.GaitParams(
        samples=SAMPLES))).baseline()["total"]["electrical"]
    baseline = data["energy"]["totals"]["electrical"]["baseline"]["value"]
    assert baseline == pytest.approx(generated, rel=1e-9)
    assert data["gait"]["stride_length"]["value"] == pytest.approx(0.06, rel=1e-9)


@pytest.mark.parametrize("command", ["report", "design", "simulate"])
def test_a_gait_table_with_motion_is_refused_by_name(command: str, log: Path, tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    config = _config(tmp_path / "c.toml", "[gait]\nperiod = 2.0\nstride = 0.05\n")
    assert main([command, "--config", config, "--motion", str(log),
                 "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "[gait]" in err and "period, stride" in err and "--motion" in err


def test_design_samples_with_motion_is_refused_by_name(log: Path, tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    config = _config(tmp_path / "c.toml", "[design]\nsamples = 120\n")
    assert main(["design", "--config", config, "--motion", str(log),
                 "--out", str(tmp_path / "o")]) == 2
    assert "[design] samples" in capsys.readouterr().err


def test_cycle_is_checked(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert parse_cycle("auto") == "auto" and parse_cycle("whole") == "whole"
    assert parse_cycle("2:3.5") == (2.0, 3.5)
    with pytest.raises(InvalidParameterError, match="T0:T1"):
        parse_cycle("weekly")
    assert main(["simulate", "--cycle", "whole", "--out", str(tmp_path)]) == 2
    assert "--cycle only with --motion" in capsys.readouterr().err


def test_the_logged_cycle_is_the_generated_gait(log: Path) -> None:
    robot = hexaleg.load()
    motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=SAMPLES))
    back = hexaleg.load_motion(robot, log, cycle="whole", periodic=True)
    assert back.n_samples == SAMPLES and back.period == pytest.approx(motion.period, rel=1e-12)
    assert np.abs(back.q - motion.q).max() < 1e-9


def test_carried_keeps_the_logged_motion_and_names_a_gait_it_cannot_make(
        log: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The springs' mass on a log: added to the robot, the logged motion unchanged; a carried
    gait that cannot be made is an error naming the gait and the springs' mass."""
    from hexaleg.design.chain import candidates
    from hexaleg.errors import HexalegError, InfeasibleForcesError

    robot = hexaleg.load()
    logged = hexaleg.load_motion(robot, log, cycle="whole", periodic=True)
    run, gait = Scenario.load("hexaleg"), hexaleg.GaitParams(samples=SAMPLES)
    heavy = candidates.carried(run, gait, {"LF_femur": 0.5}, logged)
    assert heavy.motion is logged and heavy.robot.mass == pytest.approx(robot.mass + 0.5)

    def refuse(*_args: object, **_kw: object) -> None:
        raise InfeasibleForcesError("no contact forces at sample 3")

    monkeypatch.setattr(candidates, "prepare", refuse)
    with pytest.raises(HexalegError, match=r"logged motion .*log\.csv.*500\.0 g: LF_femur "
                       r"500\.0 g.*InfeasibleForcesError: no contact forces"):
        candidates.carried(run, gait, {"LF_femur": 0.5}, logged)
    with pytest.raises(HexalegError, match=r"nominal gait \(period 1 s, stride 0\.06 m, 100 "
                       r"samples\)"):
        candidates.carried(run, gait, {"LF_femur": 0.5})
