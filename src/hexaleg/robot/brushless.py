"""Brushless quasi-direct-drive actuators in the catalogue's DC model, with every assumption stated.

A field-oriented brushless motor is, in the rotor (dq) frame, the DC model of
:mod:`hexaleg.robot.motor` with ``i`` the q-axis current: the output torque per ampere ``k_t G``
comes from a published torque at a published current, the resistance from the phase resistance
``R_s`` (a star winding loses ``(3/2) R_s i²`` with amplitude-invariant currents, so
``R = 1.5 R_s``), the no-load output speed from the motor's speed constant (rpm/V) times the
supply voltage over the gear ratio, and the transmission efficiency η is assumed. Such an
actuator's "stall torque" is the torque at its current limit (the driver, not the winding's
``V / R``, sets it), so the relations of :func:`~hexaleg.robot.motor.from_datasheet` do not apply.

In the catalogue (:data:`hexaleg.robot.catalogue.CATALOGUE`): the ODRI module of Solo-12
(:func:`odri_actuator`), and the published energy model of the Unitree A1's joints
(:func:`a1_energy_model`: not identified constants, an empirical Joule coefficient).

Not in the catalogue, because no public source found gives a winding (or phase) resistance and a
torque constant for them, and the Joule loss ``c = R / (k_t G)²`` needs both — the registry robots
that keep a generic actuator from their URDF limits (:func:`hexaleg.robot.motor.generic_actuator`):

* Unitree A1 joint motor (``a1``): only the output torque and speed are public (the URDF's limits,
  33.5 N·m and 21 rad/s on every joint). Unitree's actuator SDK (unitreerobotics/
  unitree_actuator_sdk) keeps even the gear ratio inside its compiled library; the
  MIT-Cheetah-style A1 ports copy Mini Cheetah's ``_motorKT = .05`` and ``_motorR = 0.173``,
  marked "not sure" or "not used". What the A1 has instead is the energy model of published
  work on it, in the catalogue as ``A1-Yang2021`` (:func:`a1_energy_model`).
* Unitree GO-M8010-6 (Go1's joint motor, the stand-in third-party Go2 models use; ``go2``, whose
  URDF gives 23.7 N·m and 30.1 rad/s, the knee 45.43 N·m and 15.7 rad/s): its user manual gives a
  30 V maximum and, as quoted by third-party code, 6.33 : 1 and 30 rad/s at 24 V, but no winding
  resistance; a 0.639 N·m/A output torque constant circulates in third-party code without a
  stated origin.
* ANYbotics ANYdrive (``anymal``, ``anymal_c``): Vitruvio (leggedrobotics/vitruvio,
  ``getActuatorProperties.m``) lists 40 N·m, 12 rad/s, 240 W, 50 : 1, 1.09 kg and a motor
  efficiency band of 0.1–0.97, but no torque constant or resistance; no ANYdrive datasheet giving
  them was found.
"""

from __future__ import annotations

from hexaleg.robot.motor import RPM, Motor


def odri_actuator() -> Motor:
    """The Open Dynamic Robot Initiative actuator module v1 of Solo-12 (Grimminger et al.,
    "An Open Torque-Controlled Modular Robot Architecture for Legged Locomotion Research",
    IEEE RA-L 5(2), 2020).

    Figures from the module's documentation (open-dynamic-robot-initiative,
    open_robot_actuator_hardware, "Brushless Actuator Module v1"): gear ratio 9 (3 : 1 × 3 : 1),
    2.5 N·m at the output at 12 A (so ``k_t G = 2.5 / 12`` N·m/A, belt losses included, as for
    the servos' stall figures), phase resistance ``R_s`` = 0.23255 Ω identified with TI
    Motorware, motor 300 rpm/V (T-Motor Antigravity 4004 300 kV). As the module docstring says,
    ``R = 1.5 R_s``. Assumed: the 12 A is the q-axis current amplitude; a 24 V supply, giving the
    no-load output speed 300 · 24 / 9 = 800 rpm; a belt efficiency of 0.9 (two stages); 2.5 N·m,
    the torque at the 12 A current limit, stands for the stall torque.
    """
    return Motor(name="ODRI-4004", gear_ratio=9.0, torque_constant=2.5 / 12.0 / 9.0,
                 resistance=1.5 * 0.23255, gearbox_efficiency=0.9, regeneration=False,
                 stall_torque=2.5, no_load_speed=300.0 * 24.0 / 9.0 * RPM, voltage=24.0,
                 source="ODRI actuator module v1 (Solo-12), open-dynamic-robot-initiative/"
                        "open_robot_actuator_hardware: 9:1, 2.5 N·m at 12 A, R_s 0.23255 Ω; "
                        "R = 1.5 R_s, 24 V and η = 0.9 assumed",
                 notes="Assumed: the 12 A is the q-axis current amplitude, so R = 1.5 R_s = "
                       "0.349 Ω (star winding, amplitude-invariant currents); a 24 V supply, so "
                       "the no-load output speed is 300 rpm/V · 24 V / 9 = 800 rpm; belt "
                       "efficiency η = 0.9 (two stages); 2.5 N·m, the torque at the 12 A current "
                       "limit, stands for the stall torque.")


A1_JOULE = 0.3
"""The Joule coefficient of the A1 energy model, W/(N·m)² (:func:`a1_energy_model`)."""


def a1_energy_model() -> Motor:
    """The energy model of the Unitree A1's joints used in published work on the A1: per joint
    ``P = max(τ q̇ + 0.3 τ², 0)`` (Yang, Zhang, Coumans, Tan & Boots, "Fast and Efficient
    Locomotion via Learned Gait Transitions", CoRL 2021, arXiv:2104.04644; its code,
    yxyang/fast_and_efficient, ``src/intermediate_envs/gait_change_env.py``:
    ``motor_heat = 0.3 * motor_torques**2`` added to the joint-side ``τ q̇``, each motor clipped
    at 0, then summed).

    In the DC model of :mod:`hexaleg.robot.motor` that is a Joule coefficient
    ``c = R / (k_t G)² = 0.3`` W/(N·m)², no gearbox loss (η = 1) and no regeneration; ``k_t G =
    1`` N·m/A and ``R = 0.3`` Ω are chosen to give it (only c enters the powers). The 0.3 is an
    empirical coefficient: the work states no derivation, and no identified winding resistance
    or torque constant of the A1's motor is public. Stall torque and no-load speed are the
    URDF's limits (unitree_ros, a1_description ``const.xacro``: 33.5 N·m, 21 rad/s); the 24 V
    is assumed and enters no power.
    """
    return Motor(name="A1-Yang2021", gear_ratio=1.0, torque_constant=1.0, resistance=A1_JOULE,
                 gearbox_efficiency=1.0, regeneration=False, stall_torque=33.5,
                 no_load_speed=21.0, voltage=24.0,
                 source="Yang et al., 'Fast and Efficient Locomotion via Learned Gait "
                        "Transitions', CoRL 2021 (code yxyang/fast_and_efficient, "
                        "src/intermediate_envs/gait_change_env.py: P = max(τ q̇ + 0.3 τ², 0) "
                        "per motor); limits from unitree_ros a1_description const.xacro",
                 notes="An empirical energy model, not identified motor constants: Joule "
                       "coefficient 0.3 W/(N·m)² (k_t G = 1 N·m/A and R = 0.3 Ω chosen to give "
                       "it), η = 1 (the model has no gearbox loss), no regeneration; stall "
                       "torque 33.5 N·m and no-load speed 21 rad/s are the URDF's limits; 24 V "
                       "assumed (enters no power).")
