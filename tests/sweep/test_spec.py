"""Tests of hexaleg.sweep.spec: spec files with tables, ranges and paper units, the grid
(product and each layouts), and bad specs named with the valid choices."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.sweep.optimal import OptimalSpec
from hexaleg.sweep.spec import SweepSpec
from hexaleg.units import deg_to_rad, nmm_per_deg_to_nm_per_rad


def test_spec_from_toml_tables_ranges_and_paper_units(tmp_path):
    path = tmp_path / "spec.toml"
    path.write_text("""
[sweep]
metric = "joule"
motor = "AX-12A"
chunk_size = 7
[gait]
samples = 40
period = [0.8, 1.0]
[springs.femur]
k_nmm_per_deg = {start = 1, stop = 100, num = 3, scale = "log"}
theta_k_deg = 7.32
offset_deg = [-5, 0]
[springs.front]
joints = ["LF_coxa", "RF_coxa"]
k = 0.2
dead_zone = 0.3
""")
    spec = SweepSpec.from_toml(path)
    assert spec.metric == "joule" and spec.run.actuator.name == "AX-12A" and spec.chunk_size == 7
    np.testing.assert_allclose(spec.springs["femur"]["k"],
                               nmm_per_deg_to_nm_per_rad([1.0, 10.0, 100.0]))
    assert spec.springs["femur"]["theta_k"] == pytest.approx(deg_to_rad(7.32))
    assert spec.joints == {"front": ("LF_coxa", "RF_coxa")}
    assert spec.n_points == 2 * 3 * 2
    assert len(spec.gaits()) == 2 and len(spec.designs()) == 6
    each = SweepSpec(springs=spec.springs, joints=spec.joints, layout="each")
    assert len(each.designs()) == 6 + 1
    assert [list(d) for d in each.designs()] == [["femur"]] * 6 + [["front"]]


@pytest.mark.parametrize("springs, error, match", [
    ({"femur": {"k": (), "theta_k": 0.1}}, InvalidParameterError, "non-empty"),
    ({"femur": {"k": 1.0, "stiffnes": 2.0, "theta_k": 0.1}}, UnknownNameError,
     "stiffnes.*valid spring parameters are:.*dead_zone.*k_nmm_per_deg.*theta_k"),
    ({"femur": {"theta_k": 0.1}}, InvalidParameterError, "femur.k"),
    ({"femur": {"k": 1.0}}, InvalidParameterError, "exactly one of theta_k, dead_zone"),
    ({"femur": {"k": 1.0, "theta_k": 0.1, "dead_zone": 0.2}}, InvalidParameterError,
     "exactly one"),
    ({"femur": {"k": -1.0, "theta_k": 0.1}}, InvalidParameterError, "femur.k"),
    ({"femur": {"k": 1.0, "dead_zone": 1.2}}, InvalidParameterError, r"\(0, 1\)"),
    ({"femur": {"k": 1.0, "dead_zone": (0.0, 0.5)}}, InvalidParameterError, r"\(0, 1\)"),
    ({"femur": {"k": 1.0, "theta_k": (0.0, 0.1)}}, InvalidParameterError, "femur.theta_k"),
    ({"femur": {"k": 1.0, "theta_minus": 0.1, "theta_plus": (0.2, 0.05)}}, InvalidParameterError,
     "theta_minus"),
])
def test_bad_spring_grids(springs, error, match):
    with pytest.raises(error, match=match):
        SweepSpec(springs=springs)


def test_bad_spec_tables():
    with pytest.raises(InvalidParameterError, match=r"empty grid"):
        SweepSpec.from_mapping({"springs": {"femur": {"k": [], "theta_k": 0.1}}})
    with pytest.raises(InvalidParameterError, match=r"num"):
        SweepSpec.from_mapping({"springs": {"femur": {"k": {"start": 0, "stop": 1, "num": 0},
                                                      "theta_k": 0.1}}})
    with pytest.raises(UnknownNameError, match=r"gait parameter 'perod'.*period"):
        SweepSpec.from_mapping({"gait": {"perod": [1.0]}})
    with pytest.raises(UnknownNameError, match=r"table.*'spring'.*springs"):
        SweepSpec.from_mapping({"spring": {}})
    with pytest.raises(UnknownNameError, match=r"metric 'energy'.*electrical"):
        SweepSpec(metric="energy")
    with pytest.raises(InvalidParameterError, match=r"period"):
        SweepSpec(gait={"period": (1.0, -1.0)})
    with pytest.raises(ConfigError, match=r"k_nmm_per_deg|given twice"):
        SweepSpec.from_mapping({"springs": {"femur": {"k": 1.0, "k_nmm_per_deg": 2.0,
                                                      "theta_k": 0.1}}})


def test_one_group_from_command_line_texts():
    spec = SweepSpec.one_group("femur", {"k": "0:1:3", "theta_k": "0.1,0.2", "offset": None},
                               period="0.8", samples=100)
    assert spec.springs == {"femur": {"k": (0.0, 0.5, 1.0), "theta_k": (0.1, 0.2)}}
    assert spec.gait == {"period": 0.8, "samples": 100} and spec.n_points == 6
    with pytest.raises(InvalidParameterError, match="--joints with --k or --family"):
        SweepSpec.one_group("femur", {"k": None})
    with pytest.raises(InvalidParameterError, match="--theta-k"):
        SweepSpec.one_group("femur", {"k": "1", "theta_k": "0.1:0.2"})


@pytest.mark.parametrize("spec", [
    SweepSpec(),
    SweepSpec(gait={"samples": 40, "period": (0.8, 1.0, 1.2)}),
    SweepSpec(springs={"coxa": {"k": (0.1, 0.2), "theta_k": (0.01, 0.02, 0.03)},
                       "femur": {"k": 1.0, "theta_k": 0.1}}, gait={"period": (0.8, 1.0)}),
    SweepSpec(springs={"coxa": {"k": (0.1, 0.2), "theta_k": 0.01},
                       "femur": {"k": (1.0, 2.0, 3.0), "theta_k": 0.1}}, layout="each"),
    *(SweepSpec(springs={"coxa": {}, "femur": {}, "tibia": {}}, gait={"period": (0.8, 1.0)},
                optimal=OptimalSpec(family=("linear", "preloaded"), sets=sets))
      for sets in ("each", "all", "every"))])
def test_grid_size_counts_the_grid_without_listing_it(spec):
    """The count from the axes' lengths (also ``n_points``) is the length of the listed grid."""
    assert spec.grid_size() == spec.n_points == len(spec.gaits()) * len(spec.points_of_gait())


def test_a_grid_too_large_for_memory_is_refused_naming_its_axes():
    with pytest.raises(InvalidParameterError, match=r"sweep grid \(points: gaits × designs\) = "
                                                    r"2000000; allowed: .*1048576\].*gait\.period "
                                                    r"\(1000\) × coxa\.k \(2000\)"):
        SweepSpec(gait={"period": tuple(np.linspace(0.5, 2, 1000))},
                  springs={"coxa": {"k": tuple(np.linspace(0, 1, 2000)), "theta_k": 0.1}})


def test_a_robot_toml_in_a_spec_is_relative_to_the_spec_file(tmp_path):
    """``robot = "spider.toml"`` in ``[sweep]`` is found beside the spec, whatever the cwd."""
    import shutil
    from pathlib import Path

    data = Path(__file__).parents[1] / "data"
    for name in ("spider.toml", "spider.urdf"):
        shutil.copy(data / name, tmp_path / name)
    path = tmp_path / "spec.toml"
    path.write_text('[sweep]\nrobot = "spider.toml"\n[springs.femur]\nk = 0.1\ntheta_k = 0.1\n')
    spec = SweepSpec.from_toml(path)
    assert spec.run.robot == str(tmp_path / "spider.toml")
    assert spec.run.description.name == "spider"
