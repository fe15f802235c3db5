"""Tests of hexaleg.robot.actuator: every kind of actuator the package builds is an Actuator, its
methods agree with the datasheet on known values, a set answers each joint with that joint's own
actuator, and a model that is no Motor goes through the set and the energy metrics."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np
import pytest

from hexaleg.dynamics import energy
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.actuator import EVERY_JOINT, Actuator, joint_models
from hexaleg.robot.brushless import a1_energy_model, mini_cheetah, odri_actuator
from hexaleg.robot.catalogue import CATALOGUE
from hexaleg.robot.identify import identify_actuator
from hexaleg.robot.motor import RPM, as_torque_speed, generic_actuator
from hexaleg.robot.motor_set import MotorSet
from hexaleg.robot.standby import Idle

AX18, MX64 = CATALOGUE["AX-18A"], CATALOGUE["MX-64"]


def _identified():
    t = np.linspace(0.0, 2.0, 200)[:, None]
    tau = 0.4 * np.sin(2 * np.pi * t + np.arange(3))
    qdot = 1.5 * np.cos(2.6 * np.pi * t + np.arange(3))
    return identify_actuator(AX18, tau, qdot, current=1.1 * AX18.current(tau)).motor


def _set() -> MotorSet:
    """AX-18A on joints a0 and a1 (class "a"), MX-64 on b0 (class "b"), in the order a0 b0 a1."""
    return MotorSet.per_class({"a": ("a0", "a1"), "b": ("b0",)}, ("a0", "b0", "a1"),
                              {"a": AX18, "b": MX64})


@pytest.mark.parametrize("kind", [
    "catalogue servo", "brushless", "published energy model", "generic", "identified", "set"])
def test_every_kind_of_actuator_is_an_actuator(kind):
    actuator = {"catalogue servo": lambda: AX18, "brushless": odri_actuator,
                "published energy model": a1_energy_model,
                "generic": lambda: generic_actuator(2.0, 6.0),
                "identified": _identified, "set": _set}[kind]()
    assert isinstance(actuator, Actuator)


@pytest.mark.parametrize("thing", ["AX-18A", None, {"a": AX18}, 1.0])
def test_what_is_no_actuator_is_not(thing):
    assert not isinstance(thing, Actuator)


def test_the_methods_are_the_datasheet_on_known_values():
    """The AX-18A's e-Manual figures (1.8 N·m at 12 V and 2.2 A, 97 rpm): the stall torque
    draws the stall current, and at stall the whole electrical power is V · I_stall = 26.4 W
    (all Joule: c τ_s² = R I_s² with R = V / I_s); η = τ_s ω_0 / (V I_s) splits motoring from
    back-driving."""
    v, i_s, tau_s, omega_0 = 12.0, 2.2, 1.8, 97 * RPM
    c = (v / i_s) / (tau_s / i_s) ** 2
    eta = tau_s * omega_0 / (v * i_s)
    assert AX18.joule_coefficient == pytest.approx(c, rel=1e-14)
    assert AX18.gearbox_efficiency == pytest.approx(eta, rel=1e-14)
    assert (AX18.stall_torque, AX18.voltage) == (tau_s, v)
    assert AX18.no_load_speed == pytest.approx(omega_0, rel=1e-14)
    assert AX18.current(tau_s) == pytest.approx(i_s, rel=1e-14)
    assert AX18.electrical_power(tau_s, 0.0) == pytest.approx(v * i_s, rel=1e-14)
    tau, qdot = np.array([0.5, 0.5, 0.5]), np.array([2.0, -10.0, -10.0])
    got = AX18.electrical_power(tau, qdot, regeneration=True)
    assert got[0] == pytest.approx(1.0 / eta + c * 0.25, rel=1e-14)  # motoring: P / η
    assert got[1] == pytest.approx(-5.0 * eta + c * 0.25, rel=1e-14)  # back-driven: η P
    assert got[1] < 0  # the gearbox returns more than the windings heat
    assert AX18.electrical_power(tau, qdot)[2] == 0.0  # no regeneration: the driver burns it
    assert AX18.joule_power(tau) == pytest.approx(c * tau**2, rel=1e-14)
    assert AX18.idle_power(3).power == pytest.approx(3 * 0.050 * v, rel=1e-14)  # its family's


def test_one_model_drives_every_joint():
    assert dict(AX18.models) == {EVERY_JOINT: AX18}
    assert AX18.joint_labels(3) == (EVERY_JOINT,) * 3
    assert joint_models(AX18, 3) == (AX18, AX18, AX18)


def test_a_set_is_a_mapping_of_its_classes_actuators():
    motors = _set()
    assert list(motors) == ["a", "b"] and len(motors) == 2
    assert motors["a"] is AX18 and motors["b"] is MX64 and motors.get("c") is None
    assert dict(motors.items()) == {"a": AX18, "b": MX64}
    assert motors.models is motors
    assert motors.joint_labels(3) == ("a", "b", "a")
    assert joint_models(motors, 3) == (AX18, MX64, AX18)
    with pytest.raises(KeyError):
        motors["c"]
    with pytest.raises(InvalidParameterError, match="motor joints"):
        motors.joint_labels(4)
    assert hash(motors) == hash(_set()) and motors == _set()  # a frozen value, as before


def test_a_set_answers_each_joint_with_its_own_actuator():
    """Two different motors: each column is its own motor's current, Joule loss and power (the
    AX-18A's on columns 0 and 2, the MX-64's on column 1), and the figures are per joint."""
    motors = _set()
    rng = np.random.default_rng(3)
    tau, qdot = rng.normal(0.0, 0.6, (50, 3)), rng.normal(0.0, 3.0, (50, 3))
    for method, args in (("current", (tau,)), ("joule_power", (tau,)),
                         ("electrical_power", (tau, qdot))):
        got = getattr(motors, method)(*args)
        for col, m in enumerate((AX18, MX64, AX18)):
            own = getattr(m, method)(*(a[:, col] for a in args))
            np.testing.assert_array_equal(got[:, col], own, err_msg=method)
    assert not np.allclose(motors.current(tau)[:, 0], MX64.current(tau[:, 0]))  # not one motor
    np.testing.assert_array_equal(motors.joule_coefficient, [AX18.joule_coefficient,
                                                             MX64.joule_coefficient,
                                                             AX18.joule_coefficient])
    np.testing.assert_array_equal(motors.stall_torque, [1.8, 6.0, 1.8])
    np.testing.assert_array_equal(motors.voltage, [12.0, 12.0, 12.0])


def test_a_set_takes_each_joints_regeneration():
    cheetah = mini_cheetah()
    regen = MotorSet.per_class({"a": ("a0",), "b": ("b0",)}, ("a0", "b0"),
                               {"a": AX18, "b": dataclasses.replace(cheetah, regeneration=True)})
    tau, qdot = np.array([[0.5, 0.5]]), np.array([[-10.0, -10.0]])
    p = regen.electrical_power(tau, qdot)
    assert p[0, 0] == 0.0 and p[0, 1] < 0  # clipped on a, returned on b
    np.testing.assert_array_equal(regen.regeneration, [False, True])


def test_a_set_refuses_what_is_not_one_actuator_model():
    with pytest.raises(InvalidParameterError, match="MotorSet motor of a"):
        MotorSet(("j",), ("a",), (("a", "AX-18A"),))
    with pytest.raises(InvalidParameterError, match="MotorSet motor of a"):
        MotorSet(("j0", "j1"), ("a", "a"), (("a", _set()),))  # a set in a set


@dataclass(frozen=True)
class DirectDrive:
    """A model that is no Motor: a direct-drive motor without gearbox, ``i = τ / k_t``,
    ``P_e = τ q̇ + (R / k_t²) τ²`` (the DC model with G = 1 and η = 1), always regenerating."""

    k_t: float = 0.5
    resistance: float = 0.2
    name: str = "direct"
    source: str = "test"
    notes: str = ""
    stall_torque: float = 3.0
    no_load_speed: float = 40.0
    gearbox_efficiency: float = 1.0
    regeneration: bool = True
    voltage: float = 24.0

    @property
    def joule_coefficient(self) -> float:
        return self.resistance / self.k_t**2

    @property
    def models(self):
        return MappingProxyType({EVERY_JOINT: self})

    def joint_labels(self, n_joints):
        return (EVERY_JOINT,) * n_joints

    def idle_power(self, n_joints):  # its own driver: 0.1 A at 24 V a joint
        return Idle(2.4 * n_joints, 2.4 * n_joints, 2.4 * n_joints, (), (),
                    {self.name: "test: 0.1 A at 24 V"})

    def current(self, tau):
        return np.asarray(tau, dtype=float) / self.k_t

    def joule_power(self, tau):
        return self.joule_coefficient * np.asarray(tau, dtype=float) ** 2

    def electrical_power(self, tau, qdot, regeneration=None):
        t, w = as_torque_speed(tau, qdot)
        p = t * w + self.joule_power(t)
        regen = self.regeneration if regeneration is None else regeneration
        return p if regen else np.maximum(p, 0.0)


def test_a_new_model_goes_through_a_set_and_the_metrics():
    """The interface is what the package asks: a class that is no Motor sits in a set beside a
    catalogue servo and its joint's energies are its own formulas'."""
    direct = DirectDrive()
    assert isinstance(direct, Actuator)
    motors = MotorSet.per_class({"a": ("a0",), "b": ("b0",)}, ("a0", "b0"),
                                {"a": AX18, "b": direct})
    t = np.linspace(0.0, 1.0, 100, endpoint=False)
    tau = np.stack([0.5 * np.sin(2 * math.pi * t), 0.8 * np.cos(2 * math.pi * t)], axis=1)
    qdot = np.stack([np.cos(2 * math.pi * t), np.sin(2 * math.pi * t) + 0.3], axis=1)
    m = energy.metrics(tau, qdot, 0.01, motors)
    assert m["joint"]["joule"][1] == pytest.approx(0.01 * np.sum(0.8 * tau[:, 1] ** 2),
                                                   rel=1e-13)
    assert m["joint"]["electrical"][1] == pytest.approx(
        0.01 * np.sum(tau[:, 1] * qdot[:, 1] + 0.8 * tau[:, 1] ** 2), rel=1e-13)
    assert m["joint"]["electrical"][0] == pytest.approx(
        energy.metrics(tau[:, 0], qdot[:, 0], 0.01, AX18)["total"]["electrical"], rel=1e-13)
    assert motors.name == "AX-18A (a) · direct (b)"
    assert motors.idle_power(2).power == pytest.approx(0.6 + 2.4)  # AX-18A's 50 mA · 12 V


def test_the_metrics_name_what_is_no_actuator():
    with pytest.raises(InvalidParameterError, match=r"metrics\(motor=…\) = 'AX-18A'"):
        energy.metrics(np.zeros((3, 2)), np.zeros((3, 2)), 0.1, "AX-18A")
