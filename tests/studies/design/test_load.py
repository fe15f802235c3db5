"""Tests of hexaleg.studies.design.load: a design.json read back is the springs, the gait and the
saving the design computed — and ``hexaleg simulate --springs`` predicts that saving."""

from __future__ import annotations

import json

import pytest

import hexaleg
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.studies.simulate.study import load_study


def test_a_design_reads_back_as_its_springs_gait_and_saving(written):
    result, out = written[0].result, written[1]
    d = hexaleg.load_design(out / "design.json")
    assert d.robot == "hexaleg" and d.metric == "electrical" and d.pays is True
    assert d.gait == result.gait
    assert set(d.springs) == set(result.recommended.optimum.springs)
    for j, s in result.recommended.optimum.springs.items():
        assert d.springs[j] == s
    assert d.saving == pytest.approx(result.recommended.row["saving.electrical"], rel=1e-12)


def test_simulate_predicts_the_designs_own_saving(written):
    """One gait sampling: the study of ``hexaleg simulate --springs design.json`` runs on the
    design's gait (its samples), so its prediction is the design's to the last digits."""
    result, out = written[0].result, written[1]
    study = load_study(springs=out / "design.json")
    assert study.prepared.motion.n_samples == result.gait.samples
    predicted = study.prepared.evaluate(study.springs, "joule").savings["total"]["electrical"]
    assert predicted == pytest.approx(result.recommended.row["saving.electrical"], abs=5e-4)
    assert any("the gait of the design file" in n for n in study.notes)


def test_a_config_gait_replaces_the_designs_and_says_so(written, tmp_path):
    out = written[1]
    config = tmp_path / "c.toml"
    config.write_text("[gait]\nsamples = 100\n")
    study = load_study(config=config, springs=out / "design.json")
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
def test_a_damaged_design_file_is_named(written, tmp_path, edit, error, says):
    data = json.loads((written[1] / "design.json").read_text())
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

    from hexaleg.studies.design.load import GAIT_UNITS

    numeric = {f.name for f in dataclasses.fields(hexaleg.GaitParams)
               if any(t in str(f.type) for t in ("float", "tuple[float"))}
    assert numeric == set(GAIT_UNITS)


def test_a_gait_with_a_speed_is_written_with_the_stride_it_walks():
    """#41: codesign.json wrote a co-designed gait's stride_length as its unused default
    (0.06 m) where it walks speed × period = 0.102 m a cycle; read back, it walks the same."""
    from hexaleg.motion.params import GaitParams
    from hexaleg.studies.design.load import design_gait, gait_parameters

    gait = GaitParams(speed=0.06, period=1.7)
    written = gait_parameters(gait)
    assert written["stride_length"] == {"value": pytest.approx(0.102), "unit": "m"}
    back = design_gait({"gait": {"parameters": written}}, "hexaleg", "test")
    assert back is not None and back.stride == pytest.approx(gait.stride)
    assert back.period == gait.period and back.speed == gait.speed
