"""Tests of hexaleg.motion.balance and the balanced trot of hexaleg.motion.legged: the periodic LIP
sway solves its equation exactly, the RNEA support-line moment equals the centroidal-dynamics
moment, the swayed trot stands on exactly two feet at rest, needs no moment about the support line
and goes through the force program; the hexapod's tripod is untouched."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import analyze
from hexaleg.errors import InfeasibleForcesError, InvalidParameterError
from hexaleg.motion import balance as balance_module
from hexaleg.motion.balance import (
    BALANCE_TOL,
    Sway,
    crossing,
    leg_plane,
    periodic_lip_sway,
    support_moment,
    sway_direction,
)
from hexaleg.motion.legged import sample_gait, tripod_gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.scaling import robot_gait
from hexaleg.robot.registry import TROT, description
from hexaleg.units import G

SAMPLES = 100
NO_LIMITS = ContactParams(torque_limits=False)


@pytest.fixture(scope="module")
def solo() -> hexaleg.Robot:
    return hexaleg.load("solo12")


def trot_params(**changes) -> GaitParams:
    return dataclasses.replace(robot_gait("solo12"), **{"samples": SAMPLES, **changes})


@pytest.fixture(scope="module", params=[0.5, 0.6, "turn"])
def trot(request, solo) -> tuple[GaitParams, hexaleg.Motion]:
    """β = 0.5 (always two feet), β = 0.6 (four-foot phases) and a turning trot."""
    if request.param == "turn":
        gait = trot_params(duty_factor=0.6, yaw_rate=0.5)
    else:
        gait = trot_params(duty_factor=request.param)
    return gait, tripod_gait(solo, gait)


# --------------------------------------------------------------------------- LIP and sway


def test_periodic_lip_sway_of_one_harmonic_is_the_closed_form():
    """f = A cos(nωt) → d = A cos(nωt) / (g + h (nω)²)."""
    period, h, g, n = 0.5, 0.22, 9.81, 3
    t = np.arange(64) * period / 64
    w = 2 * math.pi / period
    d = periodic_lip_sway(0.7 * np.cos(n * w * t), period, h, g)
    assert np.allclose(d, 0.7 * np.cos(n * w * t) / (g + h * (n * w) ** 2), atol=1e-15)
    # A constant right-hand side is the static pendulum: d = f / g.
    assert np.allclose(periodic_lip_sway(np.full(64, 2.0), period, h, g), 2.0 / g)


def test_sway_solves_the_lip_exactly_at_every_sample_for_a_discontinuous_moment():
    """A square-wave moment (the switch between support lines): g d − h d̈ = f at the samples,
    Nyquist term included; d is periodic, and close to the continuous periodic solution
    d = (F/g) (1 − cosh λ(t − T/4) / cosh(λT/4)), λ = √(g/h), on the first half-period."""
    period, h, g, N, F = 0.6, 0.3, 9.81, 400, 0.5
    t = np.arange(N) * period / N
    f = np.where(t < period / 2, F, -F)
    sway = Sway.from_samples(np.array([0.0, 1.0, 0.0]), period, periodic_lip_sway(f, period, h, g))
    d, _, dd = sway(t)
    assert np.abs(g * d - h * dd - f).max() <= 1e-10 * F  # round-off of 201 harmonics
    assert np.allclose(sway(t + period)[0], d, atol=1e-15)
    assert np.allclose(d[N // 2:], -d[:N // 2], atol=1e-15)  # antisymmetric like f
    # The sampled square wave switches between samples, half a sample before t = 0 and T/2.
    lam, shifted = math.sqrt(g / h), t + period / N / 2
    first = t < period / 2
    exact = F / g * (1 - np.cosh(lam * (shifted[first] - period / 4)) / np.cosh(lam * period / 4))
    assert np.abs(d[first] - exact).max() <= 1e-3 * F / g
    assert sway.amplitude == pytest.approx(np.ptp(d) / 2)


def test_sway_derivatives_equal_central_differences():
    rng = np.random.default_rng(1)
    sway = Sway.from_samples(np.array([0.0, 1.0, 0.0]), 0.5, rng.normal(size=16) * 1e-2)
    t, h = np.linspace(0.0, 0.5, 23), 1e-6
    _, v, a = sway(t)
    assert np.allclose((sway(t + h)[0] - sway(t - h)[0]) / (2 * h), v, rtol=1e-6, atol=1e-7)
    assert np.allclose((sway(t + h)[1] - sway(t - h)[1]) / (2 * h), a, rtol=1e-6, atol=1e-4)


def test_lip_gravity_defaults_to_standard_gravity():
    f = np.cos(2 * math.pi * np.arange(16) / 16)
    assert np.array_equal(periodic_lip_sway(f, 0.5, 0.2), periodic_lip_sway(f, 0.5, 0.2, G))
    assert G == 9.81


def test_lip_rejects_bad_parameters():
    for kwargs in ({"period": 0.0}, {"height": -1.0}, {"gravity": math.nan}):
        args = {"period": 1.0, "height": 0.2, "gravity": 9.81} | kwargs
        with pytest.raises(InvalidParameterError, match=next(iter(kwargs))):
            periodic_lip_sway(np.zeros(8), **args)


def test_sway_direction_crosses_the_support_lines():
    trot = np.array([[0.8, 0.6, 0.0], [0.8, -0.6, 0.0]])
    assert np.array_equal(sway_direction(trot), [0.0, 1.0, 0.0])
    assert np.array_equal(sway_direction(np.array([[1.0, 0.0, 0.0]])), [0.0, 1.0, 0.0])  # pace
    assert np.array_equal(sway_direction(np.array([[0.0, 1.0, 0.0]])), [1.0, 0.0, 0.0])  # bound
    assert np.allclose(np.abs(crossing(trot, np.array([0.0, 1.0, 0.0]))), 0.8)


def test_sway_direction_is_lateral_to_the_heading():
    """Turning the support lines and the heading together turns the sway direction with them."""
    left = np.array([0.0, 1.0, 0.0])
    trot = np.array([[-0.6, 0.8, 0.0], [0.6, 0.8, 0.0]])  # the trot above, heading +y
    assert np.allclose(sway_direction(trot, left), [-1.0, 0.0, 0.0], atol=1e-15)
    assert np.allclose(sway_direction(np.array([[1.0, 0.0, 0.0]]), left), [0.0, 1.0, 0.0],
                       atol=1e-15)  # a bound when walking along +y
    assert np.array_equal(sway_direction(trot, np.array([1.0, 0.0, 0.0])),
                          sway_direction(trot))  # the default heading is x


def test_a_trot_facing_another_way_sways_across_its_heading(solo, rotated):
    """Solo-12 described facing +y trots the same joint motion, its sway turned with it."""
    gait = trot_params(duty_factor=0.6)
    forward = tripod_gait(solo, gait)
    turned = tripod_gait(rotated(solo, math.pi / 2), gait)
    assert np.abs(turned.q[:, 7:] - forward.q[:, 7:]).max() < 1e-8
    assert np.abs(turned.a[:, 6:] - forward.a[:, 6:]).max() < 1e-5 * np.abs(forward.a).max()
    d0, d1 = (np.array(m.info["balance"]["direction"]) for m in (forward, turned))
    assert np.allclose(d0, [0.0, 1.0, 0.0]) and np.allclose(d1, [-1.0, 0.0, 0.0], atol=1e-12)
    rot = pin.rpy.rpyToMatrix(0.0, 0.0, math.pi / 2)
    assert np.allclose(turned.q[:, :3], forward.q[:, :3] @ rot.T, atol=1e-9)
    assert turned.info["balance"]["amplitude"] == pytest.approx(
        forward.info["balance"]["amplitude"], abs=1e-9)


# --------------------------------------------------------------------------- support moment


def test_two_joint_legs_trot_swaying_in_their_planes(solo):
    """Legs of two parallel joints move their feet in vertical planes along the body: the trot
    of the two-joint test quadruped sways along the heading, in those planes (a lateral sway,
    the one three-joint legs take, put every foot 2 cm off its plane and the gait was refused),
    balanced to the tolerance, every foot within 1e-6 m of its plane; three-joint legs have no
    common plane."""
    from pathlib import Path

    from hexaleg.motion.legged import gait

    quad = str(Path(__file__).resolve().parents[1] / "data" / "quad2dof.toml")
    robot = description(quad).load()
    assert leg_plane(robot) == pytest.approx([1.0, 0.0, 0.0], abs=1e-12)
    assert leg_plane(solo) is None and leg_plane(hexaleg.load()) is None
    params = dataclasses.replace(robot_gait(quad), groups=TROT, samples=SAMPLES)
    motion = gait(robot, params)
    info = motion.info["balance"]
    assert info["mode"] == "sway" and info["direction"] == [1.0, 0.0, 0.0]
    assert info["residual"] <= BALANCE_TOL and info["amplitude"] > 1e-3
    moment, mask, _ = support_moment(robot, motion)
    assert np.abs(moment[mask]).max() <= BALANCE_TOL * robot.mass * G * info["height"]


def test_support_moment_is_the_centroidal_moment_about_the_line(solo):
    """RNEA base rows projected on the support line = u · ((c − p) × m (c̈ − g) + L̇_c), the
    whole-body Newton–Euler moment from Pinocchio's centroidal dynamics (an independent path)."""
    motion = tripod_gait(solo, trot_params(duty_factor=0.5, balance="none"))
    moment, mask, _ = support_moment(solo, motion)
    assert mask.all()
    model, data = solo.model, solo.model.createData()
    expected = np.empty(motion.n_samples)
    for k in range(motion.n_samples):
        q, v, a = motion.q[k], motion.v[k], motion.a[k]
        pin.computeCentroidalMomentumTimeVariation(model, data, q, v, a)
        c = data.com[0]
        i, j = np.flatnonzero(motion.stance[k])
        p, u = motion.feet[k, i], motion.feet[k, j] - motion.feet[k, i]
        u /= np.linalg.norm(u)
        force = data.dhg.linear - solo.mass * model.gravity.linear  # m c̈ − m g
        expected[k] = u @ (np.cross(c - p, force) + data.dhg.angular)
    scale = solo.mass * 9.81 * 0.2
    assert np.abs(moment - expected).max() <= 1e-10 * scale
    # The rigid trot needs a moment the two feet cannot give: the reason for the sway.
    assert np.abs(moment).max() > 0.05 * scale


# --------------------------------------------------------------------------- balanced trot


def test_balanced_trot_needs_no_support_line_moment(solo, trot):
    _, motion = trot
    moment, mask, _ = support_moment(solo, motion)
    com_height = motion.info["balance"]["height"]
    assert np.abs(moment[mask]).max() <= 1e-9 * solo.mass * 9.81 * com_height
    info = motion.info["balance"]
    assert info["mode"] == "sway" and info["direction"] == [0.0, 1.0, 0.0]
    assert info["residual"] <= BALANCE_TOL and info["iterations"] <= 10
    assert info["residuals"][0] > 1e-2  # the unswayed trot was far from balanced
    # A few millimetres of lateral sway for a 2.5 kg robot with feet 0.3 m apart.
    assert 1e-3 < info["amplitude"] < 2e-2


def test_switching_instants_of_the_half_duty_trot(solo, trot):
    """β = 0.5: exactly two feet at every sample; {LF, RH} on [0, T/2), {RF, LH} on [T/2, T) —
    the group touching down owns the switching instant."""
    gait, motion = trot
    counts = motion.stance.sum(axis=1)
    legs = solo.leg_names
    first = motion.stance[:, [legs.index("LF"), legs.index("RH")]].all(axis=1)
    second = motion.stance[:, [legs.index("RF"), legs.index("LH")]].all(axis=1)
    if gait.duty_factor == 0.5:
        assert np.all(counts == 2)
        assert np.array_equal(first, motion.t < gait.period / 2)
        assert np.array_equal(second, motion.t >= gait.period / 2)
        assert second[SAMPLES // 2] and not first[SAMPLES // 2]
    else:  # four feet for (β − ½) T after each switch
        four = counts == 4
        assert np.array_equal(four, (motion.t % (gait.period / 2)) < 0.1 * gait.period - 1e-12)
        assert np.all(counts[~four] == 2)


def test_balanced_trot_is_kinematically_consistent(solo, trot):
    """Pinocchio FK of q, v, a: feet on their targets, stance feet at rest (velocity and
    acceleration), and the base velocity/acceleration are the sway's exact derivatives."""
    gait, motion = trot
    model, data = solo.model, solo.model.createData()
    for k in range(motion.n_samples):
        pin.forwardKinematics(model, data, motion.q[k], motion.v[k], motion.a[k])
        pin.updateFramePlacements(model, data)
        for i, leg in enumerate(solo.legs):
            fid = leg.foot_frame_id
            assert np.allclose(data.oMf[fid].translation, motion.feet[k, i], atol=1e-9)
            if motion.stance[k, i]:
                frame = pin.LOCAL_WORLD_ALIGNED
                assert np.abs(pin.getFrameVelocity(model, data, fid, frame).linear).max() <= 1e-9
                assert np.abs(pin.getFrameClassicalAcceleration(model, data, fid, frame)
                              .linear).max() <= 1e-9
    rigid = tripod_gait(solo, dataclasses.replace(gait, balance="none"))
    sway = motion.q[:, :3] - rigid.q[:, :3]
    yaw = 2 * np.arctan2(motion.q[:, 5], motion.q[:, 6])
    lateral = np.stack([-np.sin(yaw), np.cos(yaw), np.zeros_like(yaw)], axis=1)
    d = np.einsum("ti,ti->t", sway, lateral)
    assert np.allclose(sway, d[:, None] * lateral, atol=1e-15)  # horizontal, across the body
    assert np.array_equal(motion.q[:, 3:7], rigid.q[:, 3:7])
    assert np.array_equal(motion.feet, rigid.feet)  # same footholds and swing curves
    # Base velocity = rigid twist + sway derivatives (sway(t) of the sample times).
    t = np.arange(SAMPLES) * gait.period / SAMPLES
    sway_fn = Sway.from_samples(np.array([0.0, 1.0, 0.0]), gait.period, d)
    d_, dd, ddd = sway_fn(t)
    w = gait.yaw_rate
    assert np.allclose(motion.v[:, :3] - rigid.v[:, :3],
                       np.stack([-w * d_, dd, 0 * d_], axis=1), atol=1e-12)
    assert np.allclose(motion.a[:, :3], np.stack([-w * dd, ddd, 0 * d_], axis=1), atol=1e-9)


def test_balanced_trot_goes_through_the_force_program(solo, trot):
    """The rigid trot has no contact forces; the swayed one does, with Newton–Euler exact."""
    gait, motion = trot
    with pytest.raises(InfeasibleForcesError, match="body sway"):
        analyze(solo, tripod_gait(solo, dataclasses.replace(gait, balance="none")),
                        contact=NO_LIMITS)
    result = analyze(solo, motion, contact=NO_LIMITS)
    model, data = solo.model, solo.model.createData()
    for k in range(0, motion.n_samples, 3):
        pin.centerOfMass(model, data, motion.q[k], motion.v[k], motion.a[k])
        rhs = solo.mass * (data.acom[0] - model.gravity.linear)
        assert np.allclose(result.forces[k].sum(axis=0), rhs, rtol=0, atol=1e-8 * np.abs(rhs).max())
    swing = ~motion.stance
    assert not result.forces[swing].any()
    assert np.all(result.forces[..., 2][motion.stance] > 0)  # the feet push, never pull


def test_sampling_off_the_grid_uses_the_same_sway(solo, trot):
    """Explicit times (the grid and one period later) give the cycle-grid motion and its
    periodic continuation: the sway is periodic."""
    gait, motion = trot
    again = sample_gait(solo, gait, np.append(motion.t, gait.period))
    assert not again.periodic and again.info["balance"]["mode"] == "sway"
    for name in ("q", "v", "a"):
        assert np.allclose(getattr(again, name)[:-1], getattr(motion, name), atol=1e-10)
    if gait.yaw_rate == 0:  # one cycle later: the same pose one stride ahead
        assert np.allclose(again.q[-1, 1:], motion.q[0, 1:], atol=1e-10)
        assert again.q[-1, 0] == pytest.approx(motion.q[0, 0] + gait.stride, abs=1e-10)
        assert np.allclose(again.v[-1], motion.v[0], atol=1e-9)


def test_tripod_is_not_swayed():
    robot = hexaleg.load()
    motion = tripod_gait(robot, GaitParams(samples=60))
    assert motion.info["balance"] == {"mode": "none"}
    assert np.array_equal(motion.q[:, 1], np.zeros(60))
    assert np.array_equal(motion.a[:, :6], np.zeros((60, 6)))


def test_balance_parameter_and_failures(solo, monkeypatch):
    with pytest.raises(InvalidParameterError, match="auto or none"):
        GaitParams(balance="sway please")
    assert GaitParams.from_toml({"balance": "none"}).balance == "none"
    go2 = robot_gait(description("go2"))
    assert go2.groups == TROT and go2.balance == "auto"
    gait = trot_params(duty_factor=0.5, samples=40)
    monkeypatch.setattr(balance_module, "BALANCE_MAX_ITER", 1)
    with pytest.raises(InfeasibleForcesError, match="did not converge in 1 iterations"):
        tripod_gait(solo, gait)
    monkeypatch.setattr(balance_module, "BALANCE_MAX_ITER", 60)
    monkeypatch.setattr(balance_module, "MIN_CROSSING", 0.99)
    with pytest.raises(InvalidParameterError, match="sway can cross"):
        tripod_gait(solo, gait)


def test_gait_command_summarises_the_sway(capsys, tmp_path):
    """'hexaleg gait --robot solo12': the robot's trot, the file's [gait] keys on top."""
    from hexaleg.cli import main

    (tmp_path / "gait.toml").write_text(f"[gait]\nsamples = {SAMPLES}\n")
    assert main(["gait", "--robot", "solo12", "--config", str(tmp_path / "gait.toml")]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[1] == "groups: LF RH | RF LH" and f"{SAMPLES} samples" in lines[0]
    assert "duty factor 0.6" in lines[0]
    assert lines[3].startswith("balance: body sway ±4.2") and "[0.0, 1.0, 0.0]" in lines[3]
    assert main(["gait", "--robot", "spot"]) == 2
