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
(:func:`odri_actuator`, its documentation's 2.5 N·m at 12 A, and :func:`odri_actuator_paper`,
the paper's 0.025 N·m/A × 9), the MIT Mini Cheetah's and Cheetah 3's actuators from their
builders' code (:func:`mini_cheetah`, :func:`cheetah3`; the Mini Cheetah in two sources that
disagree on R and k_t, kept as two entries), and the published energy model of the Unitree A1's
joints (:func:`a1_energy_model`: not identified constants, an empirical Joule coefficient).
Where two sources of one actuator disagree, both entries are kept, so a band over them holds
the disagreement (Mini Cheetah c 0.85 vs 1.28 W/(N·m)² at 6 : 1; ODRI 6.9 vs 8.0).

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

import math

from hexaleg.errors import InvalidParameterError
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


def odri_actuator_paper() -> Motor:
    """The ODRI actuator module as its paper states it (Grimminger et al., IEEE RA-L 5(2) 2020,
    arXiv:1910.00093, text as transcribed in NoLoPhe/PMSM_drivers ``102_Solo_8/README.md``):
    "τjoint = ki i N where ki = 0.025 N m/A and the gear reduction N = 9 which leads to τjoint =
    0.225 i. The actuator can output τmax = 2.7 N m joint torque at 12 A." The phase resistance
    and every assumption are :func:`odri_actuator`'s; only ``k_t G`` (0.225 vs the
    documentation's 2.5/12 = 0.208 N·m/A) and the peak torque (2.7 vs 2.5 N·m) differ, so c is
    6.89 here against 8.04 W/(N·m)² there (reference: shared/reference/motor-sources.md,
    item 5)."""
    docs = odri_actuator()
    return Motor(name="ODRI-4004-RAL2020", gear_ratio=9.0, torque_constant=0.025,
                 resistance=docs.resistance, gearbox_efficiency=docs.gearbox_efficiency,
                 regeneration=False, stall_torque=2.7, no_load_speed=docs.no_load_speed,
                 voltage=docs.voltage,
                 source="Grimminger et al., RA-L 2020 (arXiv:1910.00093): 'ki = 0.025 N m/A "
                        "and the gear reduction N = 9', 'τmax = 2.7 N m joint torque at 12 A'; "
                        "R_s 0.23255 Ω from open_robot_actuator_hardware (MotorWare ID)",
                 notes="The paper's k_t and peak torque; R = 1.5 R_s = 0.349 Ω, 24 V, η = 0.9 "
                       "and the q-axis reading of the 12 A assumed as for ODRI-4004. The module's "
                       "documentation says 2.5 N·m at 12 A instead (ODRI-4004).")


SQRT3 = math.sqrt(3.0)


def _mit(name: str, *, kt_code: float, resistance_s: float, gear_ratio: float,
         motor_tau_max: float, battery: float, efficiency: float, source: str,
         notes: str) -> Motor:
    """An MIT actuator from its builders' constants: ``kt_code`` the code's ``_motorKT`` (flux
    linkage × pole pairs, V·s/rad), so ``k_t = 1.5 kt_code`` N·m per q-axis amp (Cheetah-Software
    ``ActuatorModel.h``: "iDes = tauDesMotor / (_kt * 1.5)"); ``R = 1.5 R_s`` as the module
    docstring says; peak output torque ``motor_tau_max · G``; no-load output speed assumed as the
    battery's phase-peak voltage under space-vector modulation over the back-EMF constant,
    ``V / (√3 · kt_code) / G`` (enters no power)."""
    return Motor(name=name, gear_ratio=gear_ratio, torque_constant=1.5 * kt_code,
                 resistance=1.5 * resistance_s, gearbox_efficiency=efficiency,
                 regeneration=False, stall_torque=motor_tau_max * gear_ratio,
                 no_load_speed=battery / (SQRT3 * kt_code) / gear_ratio, voltage=battery,
                 source=source, notes=notes)


_CHEETAH_SOFTWARE = ("mit-biomimetics/Cheetah-Software, common/include/Dynamics/{file} "
                     "(builders' code): {quote}; ActuatorModel.h: 'iDes = tauDesMotor / (_kt * "
                     "1.5)'")
_KATZ_EFFICIENCY = ("η = 0.9: Katz, Di Carlo & Kim, ICRA 2019, the planetary gearbox's "
                    "'efficiency of greater than 90% at torques above 1.5 N m' (the lower "
                    "figure)")


def mini_cheetah(joint: str = "hip", constants: str = "cheetah-software") -> Motor:
    """The MIT Mini Cheetah's actuator (iFlight EX-8, 21 pole pairs, 6 : 1 planetary; the knee
    a further 1.55 : 1 belt, 9.33 : 1 in all), in one of two sources that disagree:

    * ``"cheetah-software"``: Cheetah-Software ``MiniCheetah.h``: "_abadGearRatio = 6;
      _hipGearRatio = 6; _kneeGearRatio = 9.33;", "_motorTauMax = 3.f;", "_batteryV = 24;",
      "_motorKT = .05;  // this is flux linkage * pole pairs", "_motorR = 0.173;": k_t =
      0.075 N·m/A, R_s 0.173 Ω, c = 1.28 W/(N·m)² at 6 : 1, 0.53 at 9.33 : 1;
    * ``"katz"`` (hip only): Ben Katz's motor-controller firmware (mbed Hobbyking_Cheetah
      ``Config/motor_config.h``, rev 53, 2019-08-08): "R_PHASE 0.13f //Ohms", "KT .08f //N-m
      per peak phase amp, = WB*NPP*3/2", "GR 6.0f": k_t 0.08, R_s 0.13 Ω, c = 0.85.

    The peak output torque is ``_motorTauMax · G`` (18 N·m at the hip, 28 N·m at the knee);
    η 0.9 from the ICRA 2019 paper; 24 V battery (``_batteryV``); no regeneration (hexaleg's
    conservative default). Reference: shared/reference/motor-sources.md, item 4.

    Raises:
        InvalidParameterError: ``joint`` not "hip" or "knee", ``constants`` not one of the two,
            or the Katz constants asked for the knee (the firmware gives the 6 : 1 module).
    """
    if joint not in ("hip", "knee"):
        raise InvalidParameterError("joint", joint, '"hip" (also the ab/ad) or "knee"')
    if constants not in ("cheetah-software", "katz"):
        raise InvalidParameterError("constants", constants, '"cheetah-software" or "katz"')
    gear = 6.0 if joint == "hip" else 9.33
    if constants == "katz":
        if joint != "hip":
            raise InvalidParameterError("joint", joint,
                                        '"hip": the Katz firmware gives the 6 : 1 module only')
        return _mit("MiniCheetah-hip-Katz", kt_code=0.08 / 1.5, resistance_s=0.13,
                    gear_ratio=gear, motor_tau_max=3.0, battery=24.0, efficiency=0.9,
                    source="Ben Katz, motor-controller firmware (mbed Hobbyking_Cheetah, "
                           "Config/motor_config.h rev 53): 'R_PHASE 0.13f //Ohms', 'KT .08f "
                           "//N-m per peak phase amp', 'GR 6.0f'; peak torque and battery from "
                           "Cheetah-Software MiniCheetah.h ('_motorTauMax = 3.f', '_batteryV = "
                           "24')",
                    notes=f"R = 1.5 R_s = 0.195 Ω, k_t 0.08 N·m/A; {_KATZ_EFFICIENCY}; no-load "
                          "speed V/(√3 k_e)/G assumed (enters no power). Disagrees with "
                          "Cheetah-Software (R_s 0.173 Ω, k_t 0.075): c 0.85 here vs 1.28.")
    return _mit(f"MiniCheetah-{joint}", kt_code=0.05, resistance_s=0.173, gear_ratio=gear,
                motor_tau_max=3.0, battery=24.0, efficiency=0.9,
                source=_CHEETAH_SOFTWARE.format(
                    file="MiniCheetah.h",
                    quote=f"'_{joint}GearRatio = {gear:g}', '_motorTauMax = 3.f', '_batteryV "
                          "= 24', '_motorKT = .05;  // this is flux linkage * pole pairs', "
                          "'_motorR = 0.173'"),
                notes=f"k_t = 1.5 × 0.05 = 0.075 N·m/A, R = 1.5 R_s = 0.2595 Ω; "
                      f"{_KATZ_EFFICIENCY}; no-load speed V/(√3 k_e)/G assumed (enters no "
                      "power). Ben Katz's firmware says R_s 0.13 Ω and k_t 0.08 "
                      "(MiniCheetah-hip-Katz): c differs by 50 %.")


def cheetah3(joint: str = "hip") -> Motor:
    """The MIT Cheetah 3's actuator from Cheetah-Software ``Cheetah3.h``: "_abadGearRatio =
    7.66666666667; _hipGearRatio = 7.66666666667; _kneeGearRatio = 8.846;", "_batteryV = 65;",
    "_motorKT = 0.266;", "_motorR = 0.45;", "_motorTauMax = 27.2;": k_t = 0.399 N·m/A, R =
    1.5 × 0.45 Ω, c = 0.072 W/(N·m)² (hip), 0.054 (knee), peak 208.5 / 240.6 N·m. η = 0.9 is
    assumed (no source gives Cheetah 3's; the Mini Cheetah's planetary figure); no
    regeneration. Reference: shared/reference/motor-sources.md, item 4.

    Raises:
        InvalidParameterError: ``joint`` not "hip" (also the ab/ad) or "knee".
    """
    if joint not in ("hip", "knee"):
        raise InvalidParameterError("joint", joint, '"hip" (also the ab/ad) or "knee"')
    gear = 7.66666666667 if joint == "hip" else 8.846
    return _mit(f"Cheetah3-{joint}", kt_code=0.266, resistance_s=0.45, gear_ratio=gear,
                motor_tau_max=27.2, battery=65.0, efficiency=0.9,
                source=_CHEETAH_SOFTWARE.format(
                    file="Cheetah3.h",
                    quote=f"'_{joint}GearRatio = {gear:g}', '_batteryV = 65', '_motorKT = "
                          "0.266', '_motorR = 0.45', '_motorTauMax = 27.2'"),
                notes="k_t = 1.5 × 0.266 = 0.399 N·m/A, R = 1.5 R_s = 0.675 Ω; η = 0.9 "
                      "assumed (no published Cheetah 3 gearbox efficiency); no-load speed "
                      "V/(√3 k_e)/G assumed (enters no power).")


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
