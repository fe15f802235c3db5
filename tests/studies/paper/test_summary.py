"""Tests of hexaleg.studies.paper.summary: the Markdown summary, a line per claim of the paper."""

from __future__ import annotations

from hexaleg.studies.paper.metrics import JOINT_METRICS
from hexaleg.studies.paper.summary import markdown_summary


def test_one_row_per_claim_and_per_metric(paper_result):
    text = markdown_summary(paper_result, ["fig05_rigid_torque.png"])
    lines = text.splitlines()
    assert lines[0] == "# hexaleg paper: the single elastic joint, reproduced"
    assert "| eq. 19, §4.2 | k_M = 713.547 N·mm/deg | 713.544 eq. 19 units" in text
    assert "| §4.2 | k_E = 784.717 |" in text and "| §4.2 | up to 52.81% energy saved |" in text
    for m in JOINT_METRICS:
        assert sum(line.startswith(f"| {m} | ") for line in lines) == 1, m
    assert lines[-1] == "Figures: fig05_rigid_torque.png"
