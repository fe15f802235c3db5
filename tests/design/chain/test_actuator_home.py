"""The actuator has one home, ``[motor]`` (issue #53): ``hexaleg design --config`` with
``[motor] base = "AX-12A"`` designs with the AX-12A (it used to design with the robot's AX-18A and
say so in design.json); ``[design] motor`` is deprecated with a warning saying where it went and
is refused beside ``[motor]``."""

from __future__ import annotations

import json

import pytest

from hexaleg.commands.options import load_run
from hexaleg.design.chain.chain import DesignChain
from hexaleg.design.chain.config import design_params, design_run
from hexaleg.errors import ConfigError
from hexaleg.scenario.scenario import Scenario

TINY = """
[design]
samples = 60
families = ["linear"]
"""


def test_a_motor_table_is_the_designs_actuator(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text('[motor]\nbase = "AX-12A"\nresistance = 9.5\n' + TINY)
    chain = DesignChain(load_run("hexaleg", path))
    actuator = chain.scenario.actuator
    assert actuator.name.startswith("AX-12A")
    assert actuator.resistance == 9.5  # the table's override, not the catalogue's value
    r = chain.run(stages=("candidates",))
    data = json.loads(r.to_json())
    assert data["actuator"] == actuator.name
    # the baseline is the AX-12A's: its Joule loss differs from the robot's own AX-18A
    own = DesignChain(Scenario.from_tables("hexaleg", {"design": {"samples": 60,
                                                                  "families": ["linear"]}})
                      ).run(stages=("candidates",))
    assert own.actuator == "AX-18A"
    assert r.baseline["joule"] != pytest.approx(own.baseline["joule"], rel=1e-3)
    tables = {"motor": {"base": "AX-12A"}}
    assert Scenario.from_tables("hexaleg", tables).actuator.name == "AX-12A"


def test_the_old_home_warns_and_two_homes_are_refused(tmp_path):
    with pytest.warns(DeprecationWarning, match=r"the actuator's one home is \[motor\]"):
        s = Scenario.from_tables("hexaleg", {"design": {"motor": "AX-12A"}})
        d = design_params(s)
    assert design_run(s, d).actuator.name == "AX-12A"
    path = tmp_path / "both.toml"
    path.write_text('[motor]\nbase = "AX-12A"\n[design]\nmotor = "AX-12A"\n')
    with pytest.raises(ConfigError, match=r"one home, \[motor\]; remove \[design\] motor"), \
            pytest.warns(DeprecationWarning):
        design_params(load_run("hexaleg", path))


def test_joints_without_a_named_motor_get_the_sourced_band_and_its_saving(design_written):
    """Issue #59: where a joint's motor is not named (the test hexapod's generic actuator from
    its URDF limits), design.json gives the sourced band without springs and with the
    recommendation, and the saving with each sourced actuator — each 1 − E_springs / E_baseline
    of that actuator's own energies; the built-in robot (AX-18A named) has none."""
    from pathlib import Path

    spider = str(Path(__file__).resolve().parents[2] / "data" / "spider.toml")
    scenario = Scenario.from_tables(spider, {"design": {"samples": 60, "families": ["linear"]}})
    r = DesignChain(scenario).run(stages=("candidates",))
    data = json.loads(r.to_json())
    s = data["sourced"]
    assert s is not None and s["baseline"]["joints"] == s["with_springs"]["joints"]
    base, rec = (s[k]["sourced_band"]["electrical"] for k in ("baseline", "with_springs"))
    band = s["saving_band"]
    assert band is not None and set(band["by_actuator"]) == set(base) & set(rec)
    for name, saving in band["by_actuator"].items():
        assert saving["value"] == pytest.approx(
            100 * (1 - rec[name]["value"] / base[name]["value"]))
    values = [v["value"] for v in band["by_actuator"].values()]
    assert band["low"]["value"] == min(values) and band["high"]["value"] == max(values)
    from collections import defaultdict

    from hexaleg.outputs.html import render_design_html

    # the page's line, on the session's small design with this robot's figures
    html = render_design_html({**design_written[0].data, "sourced": s}, defaultdict(str))
    assert f"No motor is named for {len(s['baseline']['joints'])} joints:" in html
    assert "a band on\nsourced constants, not a bound" in html
    assert s["baseline"]["sourced_band"]["from_law"] == [] and s["baseline"]["sourced_band"][
        "law"]["assumed"] is True
    law_band = {**s["baseline"]["sourced_band"], "from_law": ["scaling law (low)"]}
    html = render_design_html({**design_written[0].data, "sourced": {
        **s, "baseline": {**s["baseline"], "sourced_band": law_band}}}, defaultdict(str))
    assert "No sourced actuator is of their class: with the Joule scaling law's" in html
    assert "a band on\nassumed constants, not a bound" in html  # #59: never "sourced"
    own = DesignChain(Scenario.from_tables("hexaleg", {"design": {"samples": 60,
                                                                  "families": ["linear"]}})
                      ).run(stages=("candidates",))
    assert json.loads(own.to_json())["sourced"] is None
