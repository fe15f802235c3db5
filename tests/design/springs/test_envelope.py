"""Tests of each spring over its joints' whole envelope (hexaleg.design.springs.envelope).

The default robot's recommendation (one-sided springs on femur and tibia, preloaded by ≈156°)
is rebuilt from its printed law: the femur spring engages 0.2058 rad below the femur's centre of
motion with 0.0626 N·m and rate 0.02295 N·m/rad; at the femur's +150° URDF limit it winds ≈287°
and drops below the design factor 1.2 (issue #30 measured S_y/σ = 0.99 on the 7.5-turn spring);
the sphere pose (femur 75°) holds.
"""

from __future__ import annotations

import math

import pytest

from hexaleg.design.springs import envelope as ev
from hexaleg.design.springs.parts import SpringPart, motion_centres
from hexaleg.design.springs.torsion_spring import (
    TorsionRequirement,
    bending_stress,
    design_torsion_spring,
)
from hexaleg.errors import InvalidParameterError, UnknownNameError

FEMURS = ("LF_femur", "LM_femur", "LH_femur", "RF_femur", "RM_femur", "RH_femur")
RATE, PRELOAD, MAX_TORQUE = 0.02295, 0.06262, 0.07210
ENGAGE = -0.2058  # rad from the centre of motion


def _part(side: str = "above", engage: float | None = ENGAGE, free: float | None = None,
          joints: tuple[str, ...] = FEMURS, preload: float = PRELOAD,
          max_torque: float = MAX_TORQUE) -> SpringPart:
    req = TorsionRequirement(rate=RATE, max_torque=max_torque, preload_torque=preload,
                             max_outer_diameter=0.02)
    s = 1 if side == "above" else -1
    if free is None:
        assert engage is not None
        free = engage - s * preload / RATE
    return SpringPart(group="femur", joints=joints, side=side, role="one-sided", rate=RATE,
                      preload_torque=preload, max_torque=max_torque, engage=engage, free=free,
                      constant_torque=False, max_outer_diameter=0.02,
                      spring=design_torsion_spring(req))


def _gait_part(prepared) -> SpringPart:
    """The femur part with its max torque where the gait's motion reaches (as spring_parts)."""
    centres = motion_centres(prepared, FEMURS)
    reach = max(float(prepared.q[:, prepared.robot.column(j)].max()) - centres[j]
                for j in FEMURS)
    return _part(max_torque=PRELOAD + RATE * (reach - ENGAGE))


def test_the_femur_limit_is_beyond_yield_and_a_stop_is_stated(robot, prepared):
    part = _gait_part(prepared)
    centres = motion_centres(prepared, FEMURS)
    ranges = ev.envelope_ranges(robot, FEMURS, prepared=prepared)
    env = ev.part_envelope(part, centres, ranges)
    assert env is not None and part.spring is not None
    assert env.source == ev.URDF and env.angle == pytest.approx(math.radians(150))
    assert math.degrees(env.max_windup) == pytest.approx(287, abs=1)
    assert env.safety_factor < 1.2 and not env.meets
    assert env.safety_factor == pytest.approx(env.by_source[ev.URDF])
    assert env.by_source["sphere pose"] > 1.2  # 75°: holds
    # over the gait alone the envelope is the spring's own check
    assert env.by_source[ev.GAIT] == pytest.approx(part.spring.safety_factor, rel=1e-9)
    # the stop: σ there is S_y / 1.2, the torque k·w, on the far side of the gait
    stop = env.stop
    assert stop is not None and env.problem == ""
    k, d, D = part.spring.rate, part.spring.wire_diameter, part.spring.mean_diameter
    assert stop.torque == pytest.approx(k * stop.windup, rel=1e-12)
    assert float(bending_stress(stop.torque, d, D)) == pytest.approx(
        part.spring.yield_strength / 1.2, rel=1e-12)
    assert stop.windup == pytest.approx(part.spring.preload_angle + stop.angle_from_centre
                                        - ENGAGE, rel=1e-12)
    assert part.spring.max_deflection < stop.windup < env.max_windup
    for j in FEMURS:
        assert stop.angles[j] == pytest.approx(centres[j] + stop.angle_from_centre)
        assert prepared.q[:, robot.column(j)].max() < stop.angles[j] < math.radians(150)
    table = env.table()
    assert table["hard_stop"]["torque"] == {"value": stop.torque, "unit": "N·m"}
    assert table["worst"]["source"] == ev.URDF and table["meets"] is False


def test_parts_envelope_is_the_one_call(robot, prepared):
    part = _gait_part(prepared)
    turn = ("turning", {j: (0.0, 0.5) for j in FEMURS})
    (one,) = ev.parts_envelope([part], prepared, extra=[turn])
    by_hand = ev.part_envelope(part, motion_centres(prepared, FEMURS), ev.envelope_ranges(
        robot, FEMURS, prepared=prepared, extra=[turn]))
    assert one == by_hand and "turning" in one.by_source


def test_a_spring_inside_its_gait_meets_the_factor_without_a_stop(robot, prepared):
    part = _gait_part(prepared)
    centres = motion_centres(prepared, FEMURS)
    gait_only = ev.envelope_ranges(robot, FEMURS, prepared=prepared, poses=())
    gait_only = {j: tuple(r for r in rs if r.source == ev.GAIT) for j, rs in gait_only.items()}
    env = ev.part_envelope(part, centres, gait_only)
    assert env is not None and env.meets and env.stop is None
    assert env.max_windup == pytest.approx(part.spring.max_deflection, rel=1e-9)


def test_below_side_mirrors_above():
    up = _part("above", engage=0.1)
    down = _part("below", engage=-0.1)
    centres = {j: 0.3 for j in FEMURS}
    ranges = {j: (ev.AngleRange(0.3 - 2.0, 0.3 + 2.0, "range"),) for j in FEMURS}
    a = ev.part_envelope(up, centres, ranges)
    b = ev.part_envelope(down, centres, ranges)
    assert a is not None and b is not None
    assert a.max_windup == pytest.approx(b.max_windup)
    assert a.angle_from_centre == pytest.approx(2.0)
    assert b.angle_from_centre == pytest.approx(-2.0)
    assert a.stop is not None and b.stop is not None
    assert a.stop.angle_from_centre == pytest.approx(-b.stop.angle_from_centre)


def test_a_stopped_spring_stays_preloaded_and_an_engaged_one_goes_slack():
    centres = {j: 0.0 for j in FEMURS}
    short = {j: (ev.AngleRange(-3.0, -1.0, "far below"),) for j in FEMURS}
    env = ev.part_envelope(_part(), centres, short)  # never reaches contact: rests on its stop
    assert env is not None
    assert env.max_windup == pytest.approx(_part().spring.preload_angle)  # type: ignore[union-attr]
    # engaged throughout (no contact angle), free at −2.9 rad: slack below it
    slack = _part(engage=None, free=-2.9, preload=RATE * 2.0, max_torque=RATE * 3.0)
    env = ev.part_envelope(slack, centres, {j: (ev.AngleRange(-3.5, -3.0, "x"),)
                                            for j in FEMURS})
    assert env is not None and env.max_windup == 0.0


def test_envelope_ranges_of_the_default_robot(robot, prepared):
    ranges = ev.envelope_ranges(robot, ["LF_femur", "LF_tibia"], prepared=prepared,
                                extra=[("turning", {"LF_femur": (0.1, 0.9)})])
    femur = {r.source: r for r in ranges["LF_femur"]}
    assert femur[ev.URDF].low == pytest.approx(-math.radians(150))
    assert femur["sphere pose"].low == femur["sphere pose"].high == pytest.approx(
        math.radians(75))
    assert femur["stand pose"].low == pytest.approx(math.radians(20))
    assert (femur["turning"].low, femur["turning"].high) == (0.1, 0.9)
    assert "turning" not in {r.source for r in ranges["LF_tibia"]}
    assert ev.GAIT in femur


def test_bad_input_is_a_named_error(robot):
    with pytest.raises(UnknownNameError):
        ev.envelope_ranges(robot, ["LF_knee"])
    with pytest.raises(InvalidParameterError):
        ev.envelope_ranges(robot, ["LF_femur"], extra=[("x", {"LF_femur": (1.0, 0.0)})])
    with pytest.raises(InvalidParameterError):
        ev.AngleRange(math.nan, 0.0, "x")
    with pytest.raises(InvalidParameterError):
        ev.part_envelope(_part(), {}, {})  # no centre for the joints
    with pytest.raises(InvalidParameterError):
        ev.part_envelope(_part(), {j: 0.0 for j in FEMURS},
                         {j: (ev.AngleRange(0, 1, "x"),) for j in FEMURS}, design_factor=0.5)
    no_spring = SpringPart(group="g", joints=FEMURS, side="above", role="constant torque",
                           rate=0.0, preload_torque=0.1, max_torque=0.1, engage=None,
                           free=None, constant_torque=True, max_outer_diameter=0.02)
    assert ev.part_envelope(no_spring, {}, {}) is None
    assert ev.envelope([no_spring], {}, {}) == ()


def _arbor_part(arbor: float) -> SpringPart:
    """The femur part of this module's law with its spring designed to clear an ``arbor``-m
    arbor over the gait (by the design's margin), engaged throughout the range ±2.5 rad."""
    req = TorsionRequirement(rate=RATE, max_torque=MAX_TORQUE, preload_torque=PRELOAD,
                             max_outer_diameter=0.02, arbor_diameter=arbor)
    return SpringPart(group="femur", joints=FEMURS, side="above", role="one-sided", rate=RATE,
                      preload_torque=PRELOAD, max_torque=MAX_TORQUE, engage=ENGAGE,
                      free=ENGAGE - PRELOAD / RATE, constant_torque=False,
                      max_outer_diameter=0.02, spring=design_torsion_spring(req))


def test_a_coil_winding_past_its_arbors_clearance_gets_a_stop_there():
    """A coil that the envelope winds down past the clearance the design demands over its
    arbor is stopped where its inside diameter reaches that clearance (the wind-up found by
    inverting §10-12, checked here forward), beyond the gait's wind-up; the design factor
    holds there. Fails on an envelope that only stops for stress (no stop: the coil closes to
    8.64 mm over an 8.2-mm arbor whose clearance is 9.02 mm) and on a wrong inversion."""

    part = _arbor_part(0.0082)
    spring = part.spring
    assert spring is not None
    centres = {j: 0.0 for j in FEMURS}
    env = ev.part_envelope(part, centres, {j: (ev.AngleRange(-2.5, 2.5, "range"),)
                                           for j in FEMURS})
    assert env is not None and env.stop is not None and env.stop.limit == ev.ARBOR
    clear = 0.0082 * (1 + spring.requirement.arbor_margin)
    assert env.wound_inner_diameter < clear  # unstopped, the coil would close past it
    d, D, nb, k = spring.wire_diameter, spring.mean_diameter, spring.body_turns, spring.rate
    from hexaleg.design.springs.materials import material as wire
    from hexaleg.design.springs.torsion_spring import deflection_turns, wound_diameter

    E = wire(spring.material).young_modulus(d)
    at_stop = float(wound_diameter(D, nb, deflection_turns(k * env.stop.windup, d, D, nb, E))) - d
    assert at_stop == pytest.approx(clear, rel=1e-12)
    assert env.held_inner_diameter == pytest.approx(clear, rel=1e-12) and env.clears_arbor
    assert spring.max_deflection < env.stop.windup < env.max_windup  # the gait is untouched
    assert float(bending_stress(env.stop.torque, d, D)) < spring.yield_strength / 1.2
    assert env.table()["hard_stop"]["limit"] == ev.ARBOR


def test_the_stop_is_the_nearer_of_stress_and_arbor():
    """With a smaller arbor the design factor binds first: the stop is the stress stop, and
    at it the coil still clears its arbor."""
    part = _arbor_part(0.0075)
    env = ev.part_envelope(part, {j: 0.0 for j in FEMURS},
                           {j: (ev.AngleRange(-2.5, 2.5, "range"),) for j in FEMURS})
    assert env is not None and env.stop is not None and env.stop.limit == ev.STRESS
    assert env.clears_arbor and env.held_inner_diameter > 0.0075 * 1.1
