"""The quality report prints and serialises every figure."""

from __future__ import annotations

import json

from hexaleg.motion.recorded.quality import MotionQuality


def test_report_is_json_and_text():
    q = MotionQuality(path="x.csv", rows=10, rate=100.0, resampled=False, filled=0,
                      derivatives="smoothed", noise=1e-3, cutoff=5.0, window=11, cycle="auto",
                      period=1.0, cycles=3, correlation=0.99, spread=1e-3, steady_from=2.0,
                      stance_source="kinematics", stance_height=3e-4, stance_speed=5e-3,
                      stance_fractions={"LF": 0.5}, base_source="log", slip=1e-3,
                      slip_max=2e-3, warnings=("w",))
    assert json.loads(json.dumps(q.to_dict()))["cutoff"] == {"value": 5.0, "unit": "Hz"}
    assert any("cut-off 5.00 Hz" in line for line in q.lines())
    assert json.loads(json.dumps(q.to_dict()))["steady_from"] == {"value": 2.0, "unit": "s"}
    assert any("steady from t = 2.000 s" in line for line in q.lines())
