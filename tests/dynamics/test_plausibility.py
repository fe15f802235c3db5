"""The cost-of-transport plausibility check: the animal line, the band, the flags, and every
registry robot's default gait within the band or flagged."""

from __future__ import annotations

import dataclasses
import math

import pytest

import hexaleg
from hexaleg.dynamics.plausibility import (
    HIGH_FACTOR,
    LOW_FACTOR,
    animal_cost_of_transport,
    check_cost_of_transport,
    plausible_range,
    uses_generic,
)
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.scaling import robot_gait
from hexaleg.robot.catalogue import CATALOGUE
from hexaleg.robot.motor import generic_actuator
from hexaleg.robot.registry import DESCRIPTIONS
from hexaleg.units import G


def test_animal_line_is_taylor_1982() -> None:
    """10.7 M^-0.316 J/(kg m) over g: 1.091 at 1 kg; at 13 kg (the Cornell biped) 0.485, so its
    0.2 (Collins 2005) is 0.41 x the line, inside the band; ASIMO's 3.2 at 52 kg is 10.2 x,
    the high bound (issue #40: 20 x let a generic A1 at 19.8 x through)."""
    assert animal_cost_of_transport(1.0) == pytest.approx(10.7 / G, rel=1e-12)
    assert animal_cost_of_transport(13.0) == pytest.approx(10.7 * 13 ** -0.316 / G)
    assert check_cost_of_transport(0.2, 13.0).plausible
    asimo = check_cost_of_transport(3.2 * (1 - 1e-9), 52.0)
    assert asimo.plausible and HIGH_FACTOR == pytest.approx(3.2 / asimo.reference, rel=1e-12)
    assert not check_cost_of_transport(3.2 * (1 + 1e-9), 52.0).plausible
    assert not check_cost_of_transport(19.8 * animal_cost_of_transport(13.7), 13.7).plausible
    near = [r["robot"] for r in asimo.as_dict()["published"]]
    assert near == ["MIT Cheetah", "ASIMO"]
    low, high = plausible_range(2.0)
    assert (low, high) == (pytest.approx(LOW_FACTOR * animal_cost_of_transport(2.0)),
                           pytest.approx(HIGH_FACTOR * animal_cost_of_transport(2.0)))


def test_flags_and_messages() -> None:
    ref = animal_cost_of_transport(12.0)
    high = check_cost_of_transport(43.0, 12.0, generic=True)  # the A1 figure
    assert high.flag == "high" and not high.plausible
    assert "implausibly high" in high.message and "generic" in high.message
    low = check_cost_of_transport(0.1 * ref, 12.0)
    assert low.flag == "low" and "implausibly low" in low.message and "generic" not in low.message
    edge = check_cost_of_transport(HIGH_FACTOR * ref * (1 - 1e-9), 12.0)
    assert edge.plausible and "plausible" in edge.message
    data = high.as_dict()
    assert data["plausible"] is False and data["flag"] == "high"
    assert data["mass"] == {"value": 12.0, "unit": "kg"} and "Taylor" in data["rule"]
    with pytest.raises(InvalidParameterError, match="cost of transport"):
        check_cost_of_transport(math.nan, 12.0)
    with pytest.raises(InvalidParameterError, match="mass"):
        check_cost_of_transport(1.0, 0.0)


def test_uses_generic() -> None:
    assert uses_generic(generic_actuator(1.0, 5.0))
    assert not uses_generic(CATALOGUE["AX-18A"])


@pytest.mark.parametrize("name", list(DESCRIPTIONS))
def test_every_registry_robot_is_within_the_band_or_flagged(name: str) -> None:
    """Each robot's default gait (100 samples), its own actuators: the electrical cost of
    transport is positive and either inside the band or flagged with a message that says so."""
    desc = DESCRIPTIONS[name]
    robot = desc.load()
    gait = dataclasses.replace(robot_gait(name), samples=100)
    motor = desc.actuator(robot)
    base = hexaleg.prepare(robot, hexaleg.gait(robot, gait), motor=motor).baseline("joule")
    cot = base["cost_of_transport"]["electrical"]
    verdict = check_cost_of_transport(cot, robot.mass, generic=uses_generic(motor))
    assert cot > 0
    assert verdict.plausible == (verdict.low <= cot <= verdict.high)
    assert ("plausible:" in verdict.message) == verdict.plausible
    if uses_generic(motor):
        assert "generic" in verdict.message


def test_measured_robots_beside_a_prediction():
    """#59: ANYmal B's 'less than 280 W' matches the registry's 'anymal' by name; Arm et al.'s
    15.65-kg quadruped (23.4 W at 0.4 m/s) any robot of 7.8-31.3 kg by mass; the band's low end
    decides whether an upper limit is met."""
    from hexaleg.dynamics.plausibility import measured_beside

    rows = measured_beside("anymal", 30.0, 383.0, (88.5, 651.8))
    assert rows[0]["matches"] == "the same robot" and len(rows) == 3
    anymal = rows[0]
    assert anymal["power"] == {"value": 280.0, "unit": "W"} and anymal["upper_limit"]
    assert anymal["consistent"] is True and "less than 280 W" in anymal["source"]
    assert measured_beside("anymal", 30.0, 383.0)[0]["consistent"] is False
    go2 = measured_beside("go2", 16.1, 326.0, (92.1, 134.7))
    assert len(go2) == 1 and go2[0]["power"]["value"] == 23.4
    assert go2[0]["speed"] == {"value": 0.4, "unit": "m/s"} and go2[0]["consistent"] is None
    assert "mass class" in go2[0]["matches"]
    assert measured_beside(None, 2.0, 5.0) == []
    assert measured_beside(None, 31.3, 5.0)[0]["robot"].startswith("a 15.65-kg")
    with pytest.raises(InvalidParameterError, match="mass"):
        measured_beside("a1", 0.0, 5.0)


def test_costs_of_transport_beside_the_measured_robots():
    """#59: Bjelonic et al.'s ANYmal CoT 1.27 (as its abstract gives it) beside ANYmal B and C
    runs, matched by family; Arm et al.'s 23.4 W on 15.65 kg at 0.4 m/s as a cost of transport
    computed from those three figures, 23.4 / (15.65 g 0.4) = 0.381, said so; ANYmal B's
    '< 280 W' has no speed, so no cost of transport; the run's own (predicted and band) is
    P / (m g v) at its speed, and none for a motion in place."""
    from hexaleg.dynamics.plausibility import measured_beside
    from hexaleg.units import G

    rows = {r["robot"]: r for r in measured_beside("anymal_c", 30.0, 383.0, (88.5, 651.8),
                                                   speed=0.5)}
    anymal = rows["ANYmal (which one is not named in the abstract)"]
    assert anymal["cost_of_transport"] == {"value": 1.27, "unit": "1"}
    assert anymal["cost_of_transport_is"] == "published" and anymal["power"] is None
    assert "its family" in anymal["matches"] and "(1.27)" in anymal["source"]
    assert anymal["predicted_cost_of_transport"]["value"] == pytest.approx(383.0 / (30 * G * 0.5))
    assert anymal["band_cost_of_transport"]["low"]["value"] == pytest.approx(
        88.5 / (30 * G * 0.5))
    assert anymal["consistent"] is None and "cost of transport 1.27 (published)" in anymal["line"]
    arm = rows["a 15.65-kg quadruped (platform not named in the abstract)"]
    assert arm["cost_of_transport"]["value"] == pytest.approx(23.4 / (15.65 * G * 0.4))
    assert f"{arm['cost_of_transport']['value']:.3g}" == "0.381"
    assert arm["cost_of_transport_is"].startswith("computed here from the quoted power")
    b = measured_beside("anymal", 30.0, 383.0, speed=0.5)[0]
    assert b["robot"] == "ANYmal (B)" and b["cost_of_transport"] is None
    assert measured_beside("anymal", 30.0, 383.0)[0]["predicted_cost_of_transport"] is None
    with pytest.raises(InvalidParameterError, match="speed"):
        measured_beside("anymal", 30.0, 383.0, speed=0.0)
