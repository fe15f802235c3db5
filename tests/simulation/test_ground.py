"""The ground is the contact law in physical units: deflection, frequency, friction cone."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.simulation.ground import IMPEDANCE, Ground


def _ball(ground: Ground, mass: float, z0: float) -> tuple[mujoco.MjModel, mujoco.MjData]:
    """A 1 cm ball on slide joints (x, z: it cannot roll) and a plane, paired as a foot is."""
    xml = f"""<mujoco><option timestep="1e-4" cone="elliptic" impratio="1e4"><flag
      eulerdamp="disable"/></option><worldbody><geom name="g" type="plane" size="0 0 1"/>
      <body name="b" pos="0 0 {z0}"><joint name="x" type="slide" axis="1 0 0"/><joint
      name="z" type="slide" axis="0 0 1"/><geom name="s" type="sphere" size="0.01"
      mass="{mass}" contype="0" conaffinity="0"/></body></worldbody></mujoco>"""
    first = mujoco.MjModel.from_xml_string(xml)
    inv = np.asarray(first.body_invweight0).reshape(first.nbody, 2)[1, 0]
    pair = (f'<contact><pair geom1="g" geom2="s" condim="3" friction="{ground.mu} {ground.mu} '
            f'0.005 0.0001 0.0001" solref="{" ".join(map(str, ground.solref(inv)))}" '
            f'solreffriction="{" ".join(map(str, ground.solreffriction()))}" '
            f'solimp="{" ".join(map(str, ground.solimp()))}"/></contact>')
    m = mujoco.MjModel.from_xml_string(xml.replace("</mujoco>", pair + "</mujoco>"))
    m.geom_conaffinity[0] = m.geom_contype[0] = 0
    return m, mujoco.MjData(m)


def test_contact_is_the_physical_spring_damper():
    """Static deflection m g / K (exact for any impedance) and the damped frequency of
    √(K/m − (B/2m)²) within the added-mass factor 1 + d/(1−d) of the mapping (docs/simulate.md:
    3e-5 and 3e-4)."""
    ground = Ground(stiffness=5e3, damping=5.0)
    mass = 0.5
    m, d = _ball(ground, mass, 0.01)
    z = []
    for _ in range(20000):
        mujoco.mj_step(m, d)
        z.append(d.qpos[1])
    z = np.array(z)  # the slide's displacement from contact: penetration is −z
    assert -z[-1] == pytest.approx(mass * 9.81 / ground.stiffness, rel=1e-4)
    crossings = np.flatnonzero(np.diff(np.sign(z[:8000] - z[-1])) > 0)
    period = np.mean(np.diff(crossings)) * m.opt.timestep
    added = 1 + IMPEDANCE / (1 - IMPEDANCE)
    omega = np.sqrt(ground.stiffness / (mass * added) - (ground.damping / (2 * mass * added)) ** 2)
    assert 2 * np.pi / period == pytest.approx(omega, rel=1e-3)


@pytest.mark.parametrize("ratio, slides", [(0.5, False), (1.5, True)])
def test_friction_sticks_inside_the_cone_and_slides_outside(ratio, slides):
    """A horizontal push of ``ratio`` μ m g: below the cone the ball creeps less than 0.05 mm in
    0.5 s (docs/simulate.md: 0.03 mm); above it accelerates at (F − μ m g)/m."""
    ground = Ground(mu=0.6)
    mass = 0.5
    m, d = _ball(ground, mass, 0.01)
    for _ in range(2000):  # settle
        mujoco.mj_step(m, d)
    x0 = d.qpos[0]
    push = ratio * ground.mu * mass * 9.81
    d.qfrc_applied[0] = push
    xs = []
    for _ in range(5000):
        mujoco.mj_step(m, d)
        xs.append(d.qpos[0] - x0)
    if not slides:
        assert abs(xs[-1]) < 5e-5
    else:
        t = np.arange(1, 5001) * m.opt.timestep
        accel = np.polyfit(t[2000:], np.array(xs[2000:]), 2)[0] * 2
        assert accel == pytest.approx((push - ground.mu * mass * 9.81) / mass, rel=1e-6)


@pytest.mark.parametrize("field, value", [("stiffness", 0.0), ("damping", -1.0), ("mu", 0.0),
                                          ("incline", 2.0), ("noslip", 1)])
def test_ground_rejects_bad_values(field, value):
    with pytest.raises(InvalidParameterError, match=field):
        Ground(**{field: value})
