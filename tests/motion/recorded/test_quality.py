"""The quality report prints and serialises every figure."""

from __future__ import annotations

import dataclasses
import json

from hexaleg.motion.recorded.quality import UNITS, MotionQuality

REPORT = MotionQuality(
    path="x.csv", rows=10, rate=100.0, resampled=False, filled=0, derivatives="smoothed",
    noise=1e-3, cutoff=5.0, window=11, position_cutoff=2.0, attitude_cutoff=None, cycle="auto",
    period=1.0, cycles=3, correlation=0.99, spread=1e-3, steady_from=2.0,
    stance_source="kinematics", stance_height=3e-4, stance_speed=5e-3,
    stance_fractions={"LF": 0.5}, touch_fractions={"LF": 0.56}, base_source="log", slip=1e-3,
    slip_max=2e-3, warnings=("w",))


def test_report_is_json_and_text():
    data = json.loads(json.dumps(REPORT.to_dict()))
    assert data["cutoff"] == {"value": 5.0, "unit": "Hz"}
    assert data["position_cutoff"] == {"value": 2.0, "unit": "Hz"}
    assert data["attitude_cutoff"] is None  # no logged attitude: None, not a value of None
    assert data["steady_from"] == {"value": 2.0, "unit": "s"}
    assert data["stance_fractions"] == {"LF": {"value": 0.5, "unit": "1"}}
    assert data["touch_fractions"] == {"LF": {"value": 0.56, "unit": "1"}}
    lines = REPORT.lines()
    assert any("cut-off 5.00 Hz (base position 2.00 Hz)" in line for line in lines)
    assert any("steady from t = 2.000 s" in line for line in lines)
    assert any("LF 0.50; touching the ground LF 0.56" in line for line in lines)


def test_every_number_has_a_unit():
    numbers = {f.name for f in dataclasses.fields(MotionQuality)
               if f.type in ("int", "float", "float | None", "int | None")}
    assert numbers == set(UNITS)
