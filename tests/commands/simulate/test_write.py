"""simulate.json and simulate.md: quantities everywhere, a run that did not walk reported with
its verdict, unwritable outputs named."""

from __future__ import annotations

import dataclasses
import json

import pytest

from hexaleg.commands.simulate.write import page, simulation_data, summary, write_simulation
from hexaleg.errors import OutputError
from hexaleg.simulation.run import Settings, simulate


def test_a_walking_simulation(feedforward, tmp_path):
    data = simulation_data(feedforward, design="test springs", notes=("a note",))
    assert data["difference"]["saving"]["unit"] == "percentage points"
    assert abs(data["difference"]["saving"]["value"]) < 1.0
    assert data["runs"]["springs"]["contact_losses"] == {"value": 0.0, "unit": "%"}
    js, md, html = write_simulation(tmp_path / "out", data)
    assert json.loads(js.read_text())["predicted"] == data["predicted"]
    assert "a note" in md.read_text() and "test springs" in md.read_text()
    assert "real time" in summary(data)
    page_ = html.read_text()  # the page: the JSON's numbers, the savings as every page's
    for key in ("predicted", "simulated"):
        assert f"{data[key]['saving']['value']:+.2f} %" in page_
        assert f"{data[key]['saving']['value']:+.2f} %" in summary(data)
    assert "The robot walks." in page_ and "a note" in page_ and "test springs" in page_
    assert "http" not in page_ and "<script" not in page_  # self-contained
    for code in ("theta_minus", "torque_at_reference", "feedforward servo", "[11."):
        assert code not in page_, code


def test_a_fallen_run_is_reported_not_compared(prepared):
    s = simulate(prepared.robot, prepared.motion, prepared.motor, None,
                 Settings(cycles=2, evaluate=1, force_samples=0, controller="position",
                          kp_scale=0.005, feedback="off"), prepared=prepared)
    data = simulation_data(s)
    assert data["verdict"] == "did not walk" and "simulated" not in data
    assert data["runs"]["baseline"]["verdict"] == "fell"
    assert "fell at t =" in page(data) and "fell at t =" in summary(data)
    from hexaleg.outputs.html import render_simulate_html

    html = render_simulate_html(data)
    assert "The simulation did not walk:" in html and "fell at t =" in html


def test_an_unwritable_directory_is_named(feedforward, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(OutputError, match="file"):
        write_simulation(blocker / "out", simulation_data(feedforward))


def test_settings_in_the_json(feedforward):
    data = simulation_data(dataclasses.replace(feedforward))
    assert data["settings"]["timestep"] == {"value": 5e-4, "unit": "s"}
    assert data["settings"]["ground"]["stiffness"]["unit"] == "N/m"
    assert len(data["settings"]["servo"]["kp"]["value"]) == 18


def test_a_link_in_the_out_directory_is_replaced_not_written_through(feedforward, tmp_path):
    target = tmp_path / "precious.txt"
    target.write_text("keep me")
    out = tmp_path / "out"
    out.mkdir()
    (out / "simulate.json").symlink_to(target)
    js, _, _ = write_simulation(out, simulation_data(feedforward))
    assert target.read_text() == "keep me" and not js.is_symlink()
    assert json.loads(js.read_text())["runs"]


def test_the_realtime_factor_says_what_it_counts(feedforward):
    """simulate.json's real-time factor is both runs' simulated time over their stepping's wall
    time (the two stepped at once: their spans' union, between the longer run and the sum);
    the whole simulation (analysis, models, measures) is timed beside it, and the CPU
    share says how much of the wall time the machine gave to other processes."""
    s = feedforward
    t = simulation_data(s)["timing"]
    runs = (s.with_springs, s.baseline)
    simulated = sum(r.trajectory.n for r in runs) * s.with_springs.sim.timestep
    assert t["simulated_time"]["value"] == pytest.approx(simulated, rel=1e-12)
    assert simulated == pytest.approx(2 * s.settings.cycles * s.motion.period, rel=1e-9)
    wall, cpu = t["stepping_wall"]["value"], t["stepping_cpu"]["value"]
    assert t["realtime_factor"]["value"] == pytest.approx(simulated / wall, rel=1e-12)
    assert t["realtime_factor"] == simulation_data(s)["realtime_factor"]
    assert t["cpu_realtime_factor"]["value"] == pytest.approx(simulated / cpu, rel=1e-12)
    walls = sum(r.wall for r in runs)  # each run's own; they stepped at once: their union
    spans = [(r.started, r.started + r.wall) for r in runs]
    assert max(r.wall for r in runs) <= wall <= walls
    assert wall == pytest.approx(max(b for _, b in spans) - min(a for a, _ in spans))
    assert 0 < cpu <= walls * 1.05 and t["cpu_share"]["value"] == pytest.approx(cpu / walls)
    assert t["simulation_wall"]["value"] > wall  # models and measures on top of the stepping
    assert t["simulation_realtime_factor"]["value"] < t["realtime_factor"]["value"]
    assert "s of stepping" in t["text"] and "the whole simulation" in t["text"]
    assert t["text"] in summary(simulation_data(s))


def test_the_centre_of_pressure_margin_is_written_for_soles_only(feedforward):
    """Point feet (the hexapod) write no ``cop_margin``, their page no line; a run on soles
    writes its margin, leg, edge, time and load as quantities, in simulate.md and the page."""
    from hexaleg.outputs.html import render_simulate_html
    from hexaleg.simulation.pressure import CopMargin

    data = simulation_data(feedforward)
    assert all("cop_margin" not in r for r in data["runs"].values())
    assert "Centre of pressure" not in page(data)
    assert "Centre of pressure" not in render_simulate_html(data)
    margin = CopMargin(0.0394573, "R1", "left", 1.925038, 132.692)
    soles = dataclasses.replace(feedforward, baseline=dataclasses.replace(
        feedforward.baseline, cop_margin=margin))
    data = simulation_data(soles)
    assert "cop_margin" not in data["runs"]["springs"]
    assert data["runs"]["baseline"]["cop_margin"] == {
        "distance": {"value": 0.0394573, "unit": "m"}, "leg": "R1", "edge": "left",
        "time": {"value": 1.925038, "unit": "s"}, "load": {"value": 132.692, "unit": "N"}}
    assert ("Centre of pressure, closest to a sole's edge: baseline: 39.5 mm from the R1 "
            "sole's left edge at 1.925 s (132.7 N on it).") in page(data)
    html = render_simulate_html(data)
    assert 'id="cop-baseline"' in html and "39.46 mm" in html and "R1 sole's left edge" in html
    assert "alone_margin" not in data["runs"]["baseline"] and "single support" not in html
    alone = CopMargin(0.0437, "L1", "toe", 2.5, 160.0)  # the robot's own, in single support
    data = simulation_data(dataclasses.replace(soles, baseline=dataclasses.replace(
        soles.baseline, alone_margin=alone)))
    assert data["runs"]["baseline"]["alone_margin"] == {
        "distance": {"value": 0.0437, "unit": "m"}, "leg": "L1", "edge": "toe",
        "time": {"value": 2.5, "unit": "s"}, "load": {"value": 160.0, "unit": "N"}}
    assert ("baseline: 39.5 mm from the R1 sole's left edge at 1.925 s (132.7 N on it), in "
            "single support 43.7 mm from the L1 sole's toe edge at 2.5 s (160 N on it).") \
        in page(data)
    html = render_simulate_html(data)
    assert "in single support (the robot's tipping margin) 43.70 mm, the L1 sole's toe edge" \
        in html
