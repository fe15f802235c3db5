"""Tests of optimal-spring sweeps (hexaleg.sweep.optimal and runner.optimal_chunk): each
point is optimal_springs' answer for its gait, family and set of groups, on every executor, from
TOML and from the command line; bad tables are named."""

from __future__ import annotations

import math

import pandas as pd
import pytest

import hexaleg
from hexaleg.cli import main
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.sweep.optimal import OptimalSpec
from hexaleg.sweep.runner import run_sweep
from hexaleg.sweep.spec import SweepSpec
from hexaleg.sweep.summary import summary

SPEC = {"optimal": {"family": ["linear", "one_sided"], "sets": "every", "max_deflection": 1.5},
        "gait": {"samples": 60, "period": [0.8, 1.0]},
        "springs": {"femur": {}, "hind_tibiae": {"joints": ["LH_tibia", "RH_tibia"]}}}


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    spec = SweepSpec.from_mapping(SPEC)
    return spec, run_sweep(spec, tmp_path_factory.mktemp("opt") / "s", executor="serial").table


def test_points_are_gaits_by_families_by_sets(swept):
    spec, table = swept
    assert spec.n_points == 2 * 2 * 3 == len(table) and spec.metric == "joule"
    assert list(table["family"][:6]) == ["linear"] * 3 + ["one_sided"] * 3
    assert list(table["springs"][:3]) == ["femur", "hind_tibiae", "femur+hind_tibiae"]
    assert (table["status"] == "ok").all()
    assert math.isnan(table.loc[0, "hind_tibiae.k"]) and table.loc[0, "femur.k"] >= 0
    assert table.loc[3, "femur.side"] in ("above", "below")


def test_each_row_is_the_optimum_of_its_point(swept, robot):
    """A row equals optimal_springs called directly on its gait (an independent call path)."""
    _, table = swept
    row = table.iloc[11]  # second gait, one_sided, femur+hind_tibiae
    assert (row["gait.period"], row["family"], row["springs"]) == (1.0, "one_sided",
                                                                 "femur+hind_tibiae")
    prepared = hexaleg.prepare(robot, hexaleg.gait(robot, hexaleg.GaitParams(
        samples=60, period=1.0)))
    direct = hexaleg.optimal_springs(prepared, {"femur": robot.joints("femur"), "hind_tibiae":
                                                ["LH_tibia", "RH_tibia"]}, "one_sided",
                                     max_deflection=1.5)
    assert row["joule"] == pytest.approx(direct.value, rel=1e-12)
    assert row["saving.joule"] == pytest.approx(direct.saving, rel=1e-12)
    assert row["femur.preload"] == pytest.approx(direct.magnitudes["femur"]["preload"], rel=1e-9,
                                                 abs=1e-12)


def test_summary_per_family_and_set(swept):
    _, table = swept
    text = summary(table, "joule")  # two periods: compared per metre walked
    assert "linear femur: joule per metre =" in text
    assert "one_sided femur+hind_tibiae: joule per metre =" in text and " J/m " in text
    assert "femur.side = " in text


def test_process_pool_gives_the_same_table(swept, tmp_path):
    spec, table = swept
    pooled = run_sweep(spec, tmp_path / "pool", executor="process", workers=2).table
    pd.testing.assert_frame_equal(pooled, table)


def test_cli_family_flag(tmp_path, capsys):
    out = tmp_path / "cli"
    assert main(["sweep", "--joints", "tibia", "--family", "preloaded", "--max-torque", "0.5",
                 "--samples", "40", "--executor", "serial", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "1 points" in text and "preloaded tibia: joule =" in text
    assert main(["sweep", "--joints", "tibia", "--family", "preloaded", "--k", "0.1",
                 "--out", str(tmp_path / "bad")]) == 2
    assert "--k" in capsys.readouterr().err
    assert main(["sweep", "--joints", "tibia", "--max-torque", "0.5", "--k", "0.1",
                 "--out", str(tmp_path / "bad")]) == 2
    assert "without --family" in capsys.readouterr().err


@pytest.mark.parametrize(("table", "error", "match"), [
    ({"family": "springy"}, UnknownNameError, "spring families are: dead_zone, linear"),
    ({"family": []}, InvalidParameterError, "optimal.family"),
    ({"sets": "some"}, UnknownNameError, "all, each, every"),
    ({"max_deflection": 0.0}, InvalidParameterError, "max_deflection"),
    ({"max_torque": -1.0}, InvalidParameterError, "max_torque"),
    ({"preload": 1.0}, UnknownNameError, "family, max_deflection"),
])
def test_bad_optimal_tables_are_named(table, error, match):
    with pytest.raises(error, match=match):
        SweepSpec.from_mapping({"optimal": table, "springs": {"femur": {}}})


def test_optimal_groups_carry_no_design_and_exist():
    with pytest.raises(InvalidParameterError, match=r"springs\.femur.*no design parameters"):
        SweepSpec.from_mapping({"optimal": {}, "springs": {"femur": {"k": 0.1}}})
    with pytest.raises(InvalidParameterError, match="at least one"):
        SweepSpec(optimal=OptimalSpec())


def test_manifest_names_the_optimal_table():
    spec = SweepSpec.from_mapping(SPEC)
    assert spec.to_dict()["optimal"] == {"family": ["linear", "one_sided"], "sets": "every",
                                         "max_torque": None, "max_deflection": 1.5}
    assert "optimal" not in SweepSpec(springs={"coxa": {"k": 0.1, "theta_k": 0.1}}).to_dict()


def test_a_class_shares_one_physical_spring_across_the_mirror(tmp_path, robot):
    """The right coxas count their angle the other way round (hexaleg.robot.mirror): a coxa
    row is optimal_springs with those joints mirrored, as hexaleg design groups them, not one
    law on both sides (which forces the left and right constant torques to cancel: on this
    gait 0.3420 % against 0.3430 % of the Joule loss; 12.2 % against 0.2 % on a URDF that
    mirrors its thighs and knees, tests/design/test_mirrored_quadruped.py)."""
    from hexaleg.robot.mirror import mirror

    spec = SweepSpec.from_mapping({"optimal": {"family": "linear"}, "gait": {"samples": 60},
                                   "springs": {"coxa": {}}})
    row = run_sweep(spec, tmp_path / "m", executor="serial").table.iloc[0]
    prepared = hexaleg.prepare(robot, hexaleg.gait(robot, hexaleg.GaitParams(samples=60)))
    groups = {"coxa": robot.joints("coxa")}
    shared = hexaleg.optimal_springs(prepared, groups, "linear",
                                     mirrored=mirror(robot).mirrored)
    unshared = hexaleg.optimal_springs(prepared, groups, "linear")
    assert set(mirror(robot).mirrored) == {"RF_coxa", "RM_coxa", "RH_coxa"}
    assert row["saving.joule"] == pytest.approx(shared.saving, rel=1e-9)
    assert shared.saving > unshared.saving
    assert row["saving.joule"] != pytest.approx(unshared.saving, rel=1e-4)


def test_an_angle_past_which_nothing_acts_is_nan(tmp_path):
    """A stop whose magnitudes are all at most the design's zero has no angle in the table (NaN,
    as design.json's null and the terminal's —): the tibia's preloaded θ⁺ (k⁺ = P⁺ = 0) and the
    femur's dead-zone θ⁻ (k⁻ = 0) were written as whatever the geometry search left there.
    Every other angle of a sprung group keeps its value."""
    from hexaleg.design.families import family

    spec = SweepSpec.from_mapping({"optimal": {"family": ["preloaded", "dead_zone"]},
                                   "gait": {"samples": 60},
                                   "springs": {"tibia": {}, "femur": {}}})
    table = run_sweep(spec, tmp_path / "s", executor="serial").table
    idle = []
    for _, row in table.iterrows():
        fam, group = family(row["family"]), row["springs"]
        magnitudes = {m: row[f"{group}.{m}"] for m in fam.magnitudes}
        for angle in fam.angles:
            value = row[f"{group}.{angle}"]
            assert math.isnan(value) == (angle in fam.idle(magnitudes)), (group, angle)
            idle += [(row["family"], group, angle)] * math.isnan(value)
    assert ("preloaded", "tibia", "theta_plus") in idle
    assert ("dead_zone", "femur", "theta_minus") in idle
