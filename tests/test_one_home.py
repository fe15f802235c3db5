"""One home per setting (issue #53): every command is fed the same tables, and each one is used
(the value reaches what the command computes with) or refused by name — never silently ignored.

The run's own tables are ``[gait]``, ``[contact]`` (μ's one home) and ``[motor]`` (the
actuator's one home). Before #53 the design designed with the robot's AX-18A under ``[motor]
base = "AX-12A"``, codesign ignored ``[contact]`` and ``[motor]``, and μ had four homes.
"""

from __future__ import annotations

import pytest

from hexaleg.commands.options import check_tables
from hexaleg.errors import ConfigError, HexalegError
from hexaleg.scenario.scenario import Scenario

TABLES = {"gait": {"period": 1.3}, "contact": {"mu": 0.45}, "motor": {"base": "AX-12A"}}
"""The same run tables for every command: a gait period, a floor's μ, another servo."""


@pytest.fixture(scope="module")
def run() -> Scenario:
    check_tables(TABLES, "same.toml")
    return Scenario.from_tables("hexaleg", TABLES, "same.toml")


def _uses(gait, contact, actuator) -> None:
    assert gait.period == 1.3
    assert contact.mu == 0.45
    assert actuator.name == "AX-12A"


def test_the_run_reads_them_once(run):
    _uses(run.gait, run.contact, run.actuator)


def test_report_and_view_use_them(run):
    """``hexaleg report`` and ``hexaleg view`` analyse with the run's own values."""
    from hexaleg.report.config import ReportConfig

    cfg = ReportConfig.from_scenario(run)
    _uses(cfg.gait, cfg.contact, cfg.motor)


def test_design_uses_them(run):
    """``hexaleg design``: the chain's run is the scenario's at ``[design] samples``."""
    from hexaleg.design.chain.chain import DesignChain

    chain = DesignChain(run)
    _uses(chain.scenario.gait, chain.scenario.contact, chain.scenario.actuator)
    assert chain.scenario.gait.samples == chain.design.samples


def test_simulate_uses_them(run):
    """``hexaleg simulate``: the prepared motion the simulation runs and predicts."""
    from hexaleg.commands.simulate.study import load_study

    study = load_study(run)
    p = study.prepared
    _uses(run.gait, p.contact, p.motor)
    assert p.motion.period == pytest.approx(1.3)


def test_codesign_uses_the_floor_and_actuator_and_refuses_the_gait(run):
    """``hexaleg codesign`` searches the gait (``[gait]`` refused by name); its floor is
    ``[contact]`` and its actuator ``[motor]``."""
    from hexaleg.commands.codesign.command import IGNORED
    from hexaleg.design.codesign.build import codesign_settings

    assert set(IGNORED) == {"gait"}
    kwargs = codesign_settings({}, "[codesign]", run)
    assert kwargs["constraints"].mu == 0.45 and run.actuator.name == "AX-12A"


def test_sweep_uses_them(tmp_path):
    """``hexaleg sweep``: its spec's ``[gait]`` is a (one-point) grid, its ``[contact]`` and
    ``[motor]`` the run's; ``[sweep] motor`` beside ``[motor]`` is refused by name."""
    from hexaleg.sweep.spec import SweepSpec

    text = ("[gait]\nperiod = 1.3\n[contact]\nmu = 0.45\n[motor]\nbase = \"AX-12A\"\n"
            "[springs.femur]\nk = 0.1\ntheta_k = 0.1\n")
    spec_file = tmp_path / "s.toml"
    spec_file.write_text(text)
    spec = SweepSpec.from_toml(spec_file)
    assert spec.gaits() == [{"period": 1.3}]
    _uses(spec.run.with_gait(spec.gaits()[0]).gait, spec.run.contact, spec.run.actuator)
    spec_file.write_text(text + "[sweep]\nmotor = \"AX-18A\"\n")
    with pytest.raises(ConfigError, match="the actuator has one home, \\[motor\\]"):
        SweepSpec.from_toml(spec_file)


def test_every_table_a_command_reads_is_checked_by_every_command():
    """A bad value in any table is the same named error whichever command reads the file."""
    from hexaleg.scenario.scenario import TABLES as ALL

    for table in ALL:
        bad = {"base": "AX-18A", "no_such_key": 1} if table == "motor" else {"no_such_key": 1}
        with pytest.raises(HexalegError) as err:  # as every command: load_run
            check_tables({table: bad}, "bad.toml")
            Scenario.from_tables("hexaleg", {table: bad}, "bad.toml")
        assert "no_such_key" in str(err.value) and "bad.toml" in str(err.value), table
