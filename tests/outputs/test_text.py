"""Tests of hexaleg.outputs.text: the gait summary reports the margin and the joint peaks."""

from __future__ import annotations

import math

import numpy as np

from hexaleg.outputs.text import gait_summary


def test_summary_reports_margin_and_joint_peaks(robot, walk):
    text = gait_summary(robot, walk)
    assert f"static margin {walk.info['static_margin']:.4f} m" in text
    row = next(line for line in text.splitlines() if line.startswith("LF_femur"))
    col = robot.column("LF_femur")
    assert f"{np.abs(walk.v[:, 6 + col]).max():.3f}" in row
    assert f"{math.degrees(walk.q[:, 7 + col].max()):.1f}" in row
    assert len(text.splitlines()) == 4 + robot.nj
