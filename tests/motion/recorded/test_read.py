"""Reading logs: units in brackets, unknown columns named with the robot's joints."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.motion.recorded.read import read_log
from hexaleg.units import DEG, MM


def test_units_in_brackets_convert_to_si(robot, tmp_path):
    path = tmp_path / "log.csv"
    path.write_text("time [ms],LF_femur [deg],base_z [mm]\n0,90,100\n10,45,,\n"[:-2] + "\n")
    log = read_log(robot, path)
    assert np.allclose(log.t, [0.0, 0.01])
    assert log.columns["LF_femur"] == pytest.approx([90 * DEG, 45 * DEG])
    assert log.columns["base_z"][0] == pytest.approx(100 * MM)
    assert np.isnan(log.columns["base_z"][1])


def test_unknown_column_lists_the_joints(robot, tmp_path):
    path = tmp_path / "log.csv"
    path.write_text("time,LF_knee\n0,1\n")
    with pytest.raises(UnknownNameError, match="LF_femur"):
        read_log(robot, path)
    assert read_log(robot, path, ignore=("LF_knee",)).columns == {}


def test_bad_unit_names_the_allowed(robot, tmp_path):
    path = tmp_path / "log.csv"
    path.write_text("time,LF_femur [furlong]\n0,1\n")
    with pytest.raises(InvalidParameterError, match="'deg'"):
        read_log(robot, path)


def test_npz_reads_the_same_names(robot, tmp_path):
    np.savez(tmp_path / "log.npz", **{"time": np.arange(3.0), "LF_femur [deg]": np.ones(3)})
    log = read_log(robot, tmp_path / "log.npz")
    assert log.columns["LF_femur"] == pytest.approx(np.full(3, DEG))


def test_an_npz_array_that_is_not_a_column_is_named(robot, tmp_path):
    """Issue #42: a 2-D array and a short array are named, not 'got shapes …'."""
    np.savez(tmp_path / "a.npz", time=np.arange(3.0), LF_femur=np.ones((3, 2)))
    with pytest.raises(ConfigError, match=r"array 'LF_femur' is float64 of shape \(3, 2\)"):
        read_log(robot, tmp_path / "a.npz")
    np.savez(tmp_path / "b.npz", time=np.arange(3.0), LF_femur=np.ones(2))
    with pytest.raises(ConfigError, match=r"array 'LF_femur' has 2 values and 'time' 3"):
        read_log(robot, tmp_path / "b.npz")


@pytest.mark.parametrize("body, row, column", [
    ("0,1\n# a note, two commas, here\n0.01,2,3\n", 4, None),   # short row after a comment
    ("# a note\n\n0,1\n0.01,x\n", 5, 2),                         # a word after a blank line
    ("0,1 # inline, note\n0.01,2\n0.02\n", 4, None),             # an inline comment, short row
])
def test_a_bad_row_is_named_by_its_row_in_the_file_past_comments(robot, tmp_path, body, row,
                                                                 column):
    """A log another tool wrote may carry ``#`` comment lines, blank lines and inline comments
    (numpy skips them); a short row or a word is named by its row in the file (the header is
    row 1), not by its index among the data rows, and a comment line is never the bad row."""
    path = tmp_path / "log.csv"
    path.write_text("time,LF_femur\n" + body)
    at = f"row {row}, column {column} is not a number" if column else \
        f"row {row} does not have the header's 2"
    with pytest.raises(ConfigError, match=at):
        read_log(robot, path)


def test_comments_and_blank_lines_read_as_numpy_reads_them(robot, tmp_path):
    path = tmp_path / "log.csv"
    path.write_text("time,LF_femur\n# settle\n0,1 # first\n\n0.01,nan\n0.02,\n")
    log = read_log(robot, path)
    assert np.allclose(log.t, [0.0, 0.01, 0.02])
    assert log.columns["LF_femur"][0] == 1.0 and np.isnan(log.columns["LF_femur"][1:]).all()
