"""write_motion_log: every column of the motion at full precision, csv and npz only."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import hexaleg
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


def test_the_stance_reads_back_as_written_where_a_switchs_would_be_refined(robot, gait_100hz,
                                                                           tmp_path):
    """The writer's stance is the motion's (``stance_<LEG>``), which the reader takes as it is:
    here each stance is held 3 samples past lift-off, where the foot has barely risen (an
    optimal cycle rebuilt in task space lifts so, between knots). Written as contact switches
    the reader's edge refinement takes samples of them off the feet the body does not need
    (12 of the 18 measured), as it read
    ``codesign --motion optimal``'s file of the motion without springs 1.1 % dearer (16.57
    against the row's 16.38 J/m). Catches a writer of contact columns, or a reader that refines
    a plan's stance."""
    stance = gait_100hz.stance.copy()
    for j in range(stance.shape[1]):
        lift = np.flatnonzero(stance[:, j] & ~np.roll(stance[:, j], -1))
        for k in lift:
            stance[(k + np.arange(1, 4)) % len(stance), j] = True
    motion = dataclasses.replace(gait_100hz, stance=stance)
    path = write_motion_log(robot, motion, tmp_path / "m.csv")
    back = hexaleg.load_motion(robot, path, cycle="whole", periodic=True)
    assert back.info["quality"]["stance_source"] == "plan"
    np.testing.assert_array_equal(back.stance, stance)
    switches = tmp_path / "switches.csv"
    switches.write_text(path.read_text().replace("stance_", "contact_"))
    refined = hexaleg.load_motion(robot, switches, cycle="whole", periodic=True)
    assert (refined.stance != stance).sum() >= stance.shape[1]


def test_a_plans_stance_for_some_legs_only_is_refused(robot, gait_100hz, tmp_path):
    path = write_motion_log(robot, gait_100hz, tmp_path / "m.csv")
    lines = path.read_text().splitlines()
    lines[0] = lines[0].replace("stance_LF", "contact_LF")
    partial = tmp_path / "partial.csv"
    partial.write_text("\n".join(lines) + "\n")
    with pytest.raises(InvalidParameterError, match=r"stance_LM.*all of stance_LF"):
        hexaleg.load_motion(robot, partial, cycle="whole", periodic=True)
