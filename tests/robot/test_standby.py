"""Tests of hexaleg.robot.standby: every catalogue servo's standby figure and its source, the
idle draw summed per joint by hand, and a set's draw the sum of its joints' actuators' own."""

from __future__ import annotations

import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.robot.catalogue import CATALOGUE
from hexaleg.robot.motor import generic_actuator
from hexaleg.robot.motor_set import MotorSet
from hexaleg.robot.standby import STANDBY, Idle, Standby, combined, standby, standby_draw


def test_a_standby_figure_outside_its_range_is_refused():
    with pytest.raises(InvalidParameterError, match=r"0\.08"):
        Standby(0.08, "x", low=0.017, high=0.060)
    with pytest.raises(InvalidParameterError, match=r"-0\.01"):
        Standby(-0.01, "x")
    assert Standby(None, "none").low is None


def test_every_catalogue_servo_says_where_its_standby_figure_comes_from():
    assert set(STANDBY) == set(CATALOGUE)
    for name, entry in STANDBY.items():
        assert entry.source and (entry.current is None or 0.0 < entry.current < 1.0), name
        if entry.current is not None:
            assert "emanual.robotis.com" in entry.source, name
            assert "Standby Current" in entry.source or "대기 전류" in entry.source, name
            assert entry.own or "family" in entry.source


def test_idle_power_sums_per_joint_and_names_the_servos_without_a_figure():
    """XM540-W150: 40 mA at 12 V = 0.48 W a joint; AX-18A its family's 50 mA (17–60 mA) at
    12 V; MX-64 none published."""
    xm, ax, mx = CATALOGUE["XM540-W150"], CATALOGUE["AX-18A"], CATALOGUE["MX-64"]
    both = MotorSet.per_class({"a": ("j0", "j1"), "b": ("j2",)}, ("j0", "j1", "j2"),
                              {"a": xm, "b": xm})
    assert both.idle_power(3).power == pytest.approx(3 * 0.48)
    with_ax = MotorSet.per_class({"a": ("j0", "j1"), "b": ("j2",)}, ("j0", "j1", "j2"),
                                 {"a": xm, "b": ax})
    idle = with_ax.idle_power(3)
    assert idle.power == pytest.approx(2 * 0.48 + 0.6)
    assert idle.low == pytest.approx(2 * 0.48 + 0.017 * 12) and idle.family == ("AX-18A",)
    assert idle.high == pytest.approx(2 * 0.48 + 0.060 * 12)
    mixed = MotorSet.per_class({"a": ("j0", "j1"), "b": ("j2",)}, ("j0", "j1", "j2"),
                               {"a": xm, "b": mx})
    idle = mixed.idle_power(3)
    assert idle.power is None and idle.missing == ("MX-64",)
    assert set(idle.sources) == {"XM540-W150", "MX-64"}
    generic = generic_actuator(3.0, 5.0)
    assert generic.idle_power(2).missing == ("generic",)
    assert "not a catalogue servo" in standby("generic").source
    with pytest.raises(InvalidParameterError, match="motor joints"):
        mixed.idle_power(4)


def test_a_sets_idle_power_is_its_joints_summed_in_column_order_to_the_bit():
    """A set of one servo on every class gives that servo's own draw, bit for bit (the sum runs
    joint by joint in both), so a report's idle figures do not move with how the motors are
    grouped."""
    ax = CATALOGUE["AX-18A"]
    names = tuple(f"j{k}" for k in range(18))
    same = MotorSet.per_class({"a": names[:6], "b": names[6:12], "c": names[12:]}, names,
                              {"a": ax, "b": ax, "c": ax})
    assert same.idle_power(18) == ax.idle_power(18) == standby_draw((("AX-18A", 12.0),) * 18)


def test_combined_sums_and_names_everything():
    one = Idle(0.5, 0.2, 0.7, (), ("A",), {"A": "a's page"})
    none = Idle(None, None, None, ("B",), (), {"B": "none"})
    both = combined([one, one])
    assert (both.power, both.low, both.high, both.family) == (1.0, 0.4, 1.4, ("A",))
    assert combined([one, none]) == Idle(None, None, None, ("B",), ("A",),
                                         {"A": "a's page", "B": "none"})
