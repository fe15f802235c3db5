"""Tests of hexaleg.robot.brushless: the ODRI module of Solo-12 from its documented figures, and
the reasons the registry's other brushless actuators are not in the catalogue."""

from __future__ import annotations

import math

import pytest

from hexaleg.robot.catalogue import CATALOGUE, motor


def test_brushless_module_holds_odri_and_names_the_unsourced_registry_actuators() -> None:
    """odri_actuator lives in hexaleg.robot.brushless and is re-exported by the catalogue; that
    module says, for every registry robot left with a generic actuator, why its real one is not
    in the catalogue."""
    from hexaleg.robot import brushless, catalogue
    from hexaleg.robot.registry import DESCRIPTIONS

    assert catalogue.odri_actuator is brushless.odri_actuator
    assert CATALOGUE["ODRI-4004"] == brushless.odri_actuator()
    doc = brushless.__doc__ or ""
    generic = [name for name, d in DESCRIPTIONS.items() if d.motor is None]
    assert sorted(generic) == ["anymal", "anymal_c", "go2"]
    for name in (*generic, "a1"):  # a1: its model is in the catalogue, its motor still not
        assert f"``{name}``" in doc, name
    for actuator in ("A1 joint motor", "GO-M8010-6", "ANYdrive"):
        assert actuator in doc, actuator


def test_odri_actuator_hand_values() -> None:
    """Solo-12's module: 2.5 N·m at 12 A through 9 : 1; copper loss (3/2) R_s i² with
    R_s = 0.23255 Ω; 300 rpm/V at 24 V through 9 : 1."""
    m = motor("odri-4004")
    assert m.current(2.5) == pytest.approx(12.0)
    assert m.joule_power(2.5) == pytest.approx(1.5 * 0.23255 * 12.0**2)
    assert m.joule_coefficient == pytest.approx(1.5 * 0.23255 / (2.5 / 12) ** 2)
    assert m.no_load_speed == pytest.approx(800 * 2 * math.pi / 60)
    assert "open_robot_actuator_hardware" in m.source and "assumed" in m.source
    assert "Assumed" in m.notes and "24 V" in m.notes and "0.9" in m.notes


def test_the_a1_energy_model_is_yang_2021_and_its_trot_draws_what_the_docs_say() -> None:
    """A1-Yang2021 is ``max(τ q̇ + 0.3 τ², 0)`` per joint (Yang et al., CoRL 2021), the A1's
    registry actuator; its trot at 0.5 m/s (0.4 s, 0.20 m, β 0.6, μ 1, 200 samples) draws the
    113 W docs/energy.md quotes (issue #40: ≤ 150 W; the generic actuator gave 314 W)."""
    from pathlib import Path

    import numpy as np

    from hexaleg.robot.registry import description
    from hexaleg.scenario.scenario import Scenario

    a1 = CATALOGUE["A1-Yang2021"]
    tau, qd = np.array([-20.0, 5.0, 10.0]), np.array([3.0, -2.0, -4.0])
    expected = np.maximum(tau * qd + 0.3 * tau**2, 0.0)
    assert np.allclose(a1.electrical_power(tau, qd), expected, rtol=1e-14, atol=1e-12)
    assert description("a1").motor == "A1-Yang2021"
    run = Scenario.from_tables("a1", {
        "gait": {"period": 0.4, "stride_length": 0.2, "duty_factor": 0.6, "samples": 200},
        "contact": {"mu": 1.0}})
    analysis = run.prepare().evaluate(None, "joule")
    watts = analysis.metrics["total"]["electrical"] / 0.4
    assert watts <= 150.0
    docs = (Path(__file__).resolve().parents[2] / "docs" / "energy.md").read_text()
    assert f"the motors draw {watts:.0f} W" in docs
    # #59: the scaling law's actuator of each joint's effort on the same torques and speeds,
    # and the costs of transport docs/energy.md gives (P / (m g v), v = 0.5 m/s)
    from hexaleg.dynamics import energy
    from hexaleg.robot.scaling_law import ENDS, catalogue_law
    from hexaleg.units import G

    model, dt = run.model.model, 0.4 / 200
    law = {end: sum(energy.metrics(analysis.tau_motor[:, [i]], analysis.qdot[:, [i]], dt,
                                   catalogue_law().motor(model.effortLimit[6 + i],
                                                         model.velocityLimit[6 + i], end))[
        "total"]["electrical"] for i in range(run.model.nj)) / 0.4 for end in ENDS}
    assert (f"| {law['low']:.4g}–{law['high']:.4g} W ({law['central']:.4g} W at the law) |"
            in docs)
    per = 1.0 / (run.model.mass * G * 0.5)
    assert (f"| A1, 0.5 m/s, {run.model.mass:.4g} kg | {watts * per:.3g} (A1-Yang2021) | – | "
            f"{law['low'] * per:.3g}–{law['high'] * per:.3g} ({law['central'] * per:.3g} at the "
            "law) |") in docs


def test_the_mit_actuators_joule_coefficients_by_hand():
    """c = 1.5 R_s / (1.5 λp G)² from the builders' quoted constants (#59): Cheetah-Software
    Mini Cheetah 1.5·0.173/(0.075·6)² = 1.28 (knee 9.33: 0.53), Katz's firmware
    1.5·0.13/(0.08·6)² = 0.85, Cheetah 3 1.5·0.45/(0.399·7.667)² = 0.072 (knee 8.846: 0.054);
    peak torque = _motorTauMax · G."""
    from hexaleg.robot.brushless import cheetah3, mini_cheetah

    cases = [(mini_cheetah("hip"), 0.173, 0.075, 6.0, 3.0),
             (mini_cheetah("knee"), 0.173, 0.075, 9.33, 3.0),
             (mini_cheetah("hip", "katz"), 0.13, 0.08, 6.0, 3.0),
             (cheetah3("hip"), 0.45, 0.399, 7.66666666667, 27.2),
             (cheetah3("knee"), 0.45, 0.399, 8.846, 27.2)]
    for m, r_s, k_t, gear, tau_max in cases:
        assert m.joule_coefficient == pytest.approx(1.5 * r_s / (k_t * gear) ** 2, rel=1e-12)
        assert m.stall_torque == pytest.approx(tau_max * gear, rel=1e-12)
        assert not m.regeneration and m.source
    assert mini_cheetah("hip").joule_coefficient == pytest.approx(1.28, abs=0.005)
    assert mini_cheetah("hip", "katz").joule_coefficient == pytest.approx(0.846, abs=0.005)
    assert cheetah3("hip").joule_coefficient == pytest.approx(0.072, abs=0.0005)


def test_the_odri_paper_and_documentation_disagree_as_a_range():
    """c = 1.5·0.23255/(k_t G)²: the paper's 0.225 N·m/A gives 6.89, the docs' 2.5/12 8.04."""
    from hexaleg.robot.brushless import odri_actuator, odri_actuator_paper

    assert odri_actuator_paper().joule_coefficient == pytest.approx(
        1.5 * 0.23255 / 0.225 ** 2, rel=1e-12)
    assert odri_actuator_paper().joule_coefficient == pytest.approx(6.89, abs=0.01)
    assert odri_actuator().joule_coefficient == pytest.approx(8.04, abs=0.01)


@pytest.mark.parametrize(("joint", "constants"), [("elbow", "cheetah-software"),
                                                  ("hip", "mit"), ("knee", "katz")])
def test_a_wrong_mit_actuator_is_refused_by_name(joint, constants):
    from hexaleg.errors import InvalidParameterError
    from hexaleg.robot.brushless import mini_cheetah

    with pytest.raises(InvalidParameterError, match=r"joint|constants"):
        mini_cheetah(joint, constants)
