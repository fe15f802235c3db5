"""write_motion_log: every column of the motion at full precision, csv and npz only."""

from __future__ import annotations

import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.motion.recorded.read import read_log
from hexaleg.motion.recorded.write import write_motion_log


def test_written_csv_reads_back_bit_for_bit(robot, gait_100hz, tmp_path):
    log = read_log(robot, write_motion_log(robot, gait_100hz, tmp_path / "m.csv"))
    assert (log.columns["LF_femur"] == gait_100hz.q[:, 7 + robot.column("LF_femur")]).all()
    assert (log.columns["v_base_x"] == gait_100hz.v[:, 0]).all()


def test_other_suffix_is_refused(robot, gait_100hz, tmp_path):
    with pytest.raises(InvalidParameterError, match=r"\.csv or \.npz"):
        write_motion_log(robot, gait_100hz, tmp_path / "m.txt")
