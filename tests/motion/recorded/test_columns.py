"""Tests of hexaleg.motion.recorded.columns: a log's column names, kinds, units and the Log."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import UnknownNameError
from hexaleg.motion.recorded import read
from hexaleg.motion.recorded.columns import (
    BASE_POSITION,
    BASE_QUATERNION,
    BASE_VELOCITY,
    UNITS,
    Log,
    column_kind,
)
from hexaleg.units import DEG, MM


@pytest.mark.parametrize(("name", "kind"), [
    ("time", "time"), ("base_z", "length"), ("base_qw", "one"), ("contact_LF", "one"),
    ("stance_RM", "one"),
    ("LF_femur", "angle"), ("v_LF_femur", "rate"), ("a_RH_tibia", "angular acceleration"),
    ("v_base_x", "speed"), ("a_base_y", "acceleration"), ("v_base_rz", "rate"),
    ("a_base_rx", "angular acceleration"),
])
def test_every_column_has_its_kind(robot, name, kind):
    assert column_kind(robot, name) == kind
    assert kind in UNITS


@pytest.mark.parametrize("name", ["LF_knee", "contact_XX", "stance_XX", "v_base_qx", "a_time",
                                  "base"])
def test_a_name_that_is_no_column_of_the_robot_lists_the_valid_ones(robot, name):
    with pytest.raises(UnknownNameError, match="LF_femur") as info:
        column_kind(robot, name)
    assert name in str(info.value) and "contact_LF" in str(info.value)


def test_the_first_unit_of_each_kind_is_si_and_the_others_convert():
    assert all(next(iter(table.values())) == 1.0 for table in UNITS.values())
    assert UNITS["angle"]["deg"] == DEG and UNITS["length"]["mm"] == MM
    assert UNITS["time"]["ms"] == pytest.approx(1e-3)


def test_base_names():
    assert BASE_POSITION == ("base_x", "base_y", "base_z")
    assert BASE_QUATERNION == ("base_qx", "base_qy", "base_qz", "base_qw")
    assert BASE_VELOCITY[:3] == BASE_POSITION and len(BASE_VELOCITY) == 6


def test_a_log_stacks_its_columns():
    log = Log(t=np.arange(3.0), columns={"a": np.array([1.0, 2.0, 3.0]), "b": np.zeros(3)})
    assert log.has(["a", "b"]) and not log.has(("a", "c"))
    np.testing.assert_array_equal(log.matrix(["b", "a"]), [[0, 1], [0, 2], [0, 3]])
    assert log.matrix([]).shape == (3, 0)


def test_the_csv_reader_imports_them():
    assert read.Log is Log and read.column_kind is column_kind and read.UNITS is UNITS
