"""Property-based tests (Hypothesis) of the springs, the gait parameters and the force program:
random valid inputs keep the invariants, random invalid ones get named errors.

* Springs: every family's torque is −dU/dq (the work of the torque along a path equals the drop
  of the stored energy) and a closed cycle does zero net work.
* Gait parameters: valid values are kept in canonical types with the documented derived
  quantities and survive a TOML round trip; a wrong type, NaN/inf or an out-of-range value of any
  field is an ``InvalidParameterError`` naming that field and value.
* Force program: whatever the gait and the springs, the forces and torques satisfy the robot's
  equations of motion ``M a + h = Σ J_footᵀ f + [0; τ_motor + τ_spring]`` (Newton–Euler of the
  base in the first six rows) and the friction cone.

The example budget is fixed (``settings(max_examples=…, deadline=None)``) so CI time is bounded.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pinocchio as pin
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import hexaleg
from hexaleg.config import from_mapping
from hexaleg.errors import InvalidParameterError

FAST = settings(max_examples=40, deadline=None)
SLOW = settings(max_examples=10, deadline=None,
                suppress_health_check=[HealthCheck.function_scoped_fixture])

finite = st.floats(min_value=-3.0, max_value=3.0, allow_nan=False)
stiff = st.floats(min_value=0.0, max_value=5.0, allow_nan=False)
angle = st.floats(min_value=0.01, max_value=1.0, allow_nan=False)


@st.composite
def springs(draw):
    """A spring of a random family with random valid parameters."""
    kind = draw(st.sampled_from(["dead_zone", "linear", "preloaded", "one_sided",
                                 "stiffening"]))
    neutral = draw(finite)
    if kind == "dead_zone":
        lo, hi = sorted(draw(st.lists(angle, min_size=2, max_size=2, unique=True)))
        return hexaleg.DeadZoneSpring(stiffness=draw(stiff), theta_minus=-lo, theta_plus=hi,
                                      stiffness_minus=draw(stiff), k2=draw(stiff),
                                      alpha=draw(st.floats(0.5, 2.0)), neutral=neutral,
                                      convention=draw(st.sampled_from(["eq7", "eq14"])))
    if kind == "linear":
        return hexaleg.LinearSpring(draw(stiff), neutral, draw(finite))
    if kind == "preloaded":
        return hexaleg.PreloadedSpring(draw(stiff), draw(stiff), theta_k=draw(angle),
                                       neutral=neutral)
    if kind == "one_sided":
        return hexaleg.OneSidedSpring(draw(stiff), neutral,
                                      draw(st.sampled_from(["above", "below"])), draw(stiff))
    up = sorted(draw(st.lists(angle, min_size=1, max_size=3, unique=True)))
    return hexaleg.StiffeningSpring(above=tuple((neutral + a, draw(stiff)) for a in up))


@FAST
@given(springs(), finite, finite)
def test_spring_torque_is_minus_the_energy_gradient(spring, a, b):
    """∫ τ dq from a to b = U(a) − U(b) (torque = −dU/dq, kinks and preload jumps included)."""
    q = np.linspace(a, b, 20001)
    tau = spring.torque(q)
    work = float(np.sum(0.5 * (tau[1:] + tau[:-1]) * np.diff(q)))
    drop = float(spring.energy(np.array(a)) - spring.energy(np.array(b)))
    scale = 1.0 + float(np.max(np.abs(tau))) * abs(b - a)
    assert work == pytest.approx(drop, abs=1e-3 * scale)


@FAST
@given(stiff, angle, angle, st.floats(0.01, 2.0), st.floats(0.05, 2.0))
def test_a_damped_spring_only_dissipates_over_a_cycle(k, lo, hi, c, amplitude):
    """Over a closed cycle the conservative part of a spring does no net work, so what is left
    is the damper's: never positive (passivity), and negative once the motion engages the
    spring (eq. 8 with viscous damping while engaged; ∫ τ q̇ dt = −c ∫_engaged q̇² dt)."""
    spring = hexaleg.DeadZoneSpring(stiffness=k, theta_minus=-lo, theta_plus=hi, damping=c)
    t = np.linspace(0.0, 1.0, 40001)
    q = amplitude * np.sin(2 * np.pi * t)
    qdot = 2 * np.pi * amplitude * np.cos(2 * np.pi * t)
    power = spring.torque(q, qdot) * qdot
    work = float(np.sum(0.5 * (power[1:] + power[:-1]) * np.diff(t)))
    without = spring.torque(q) * qdot  # the same spring, no velocity: no damping
    conservative = float(np.sum(0.5 * (without[1:] + without[:-1]) * np.diff(t)))
    scale = 1.0 + float(np.max(np.abs(power)))
    assert abs(conservative) <= 1e-3 * scale
    assert work <= 1e-3 * scale
    if amplitude > 1.5 * max(lo, hi):  # engaged on both sides for a finite time
        assert work < -1e-6
bad_numbers = st.one_of(st.just(math.nan), st.just(math.inf), st.just(-math.inf),
                        st.booleans(), st.text(max_size=3), st.none())


@FAST
@given(st.sampled_from(["stiffness", "theta_k", "stiffness_minus", "k2", "alpha", "damping",
                        "neutral"]), bad_numbers)
def test_a_spring_parameter_that_is_not_a_number_is_named(field, value):
    if value is None and field in ("theta_k", "stiffness_minus"):
        return  # None is allowed there (θ_k through θ±, k⁻ = k)
    kwargs = {"stiffness": 1.0, "theta_k": 0.1, field: value}
    with pytest.raises(InvalidParameterError) as e:
        hexaleg.DeadZoneSpring(**kwargs)
    assert e.value.name == field
    assert e.value.value is value or e.value.value == value or (
        isinstance(value, float) and math.isnan(value))


# --------------------------------------------------------------------------- gait parameters

gait_values = {
    "period": st.floats(0.2, 5.0), "duty_factor": st.floats(0.5, 0.95),
    "stride_length": st.floats(0.0, 0.2), "speed": st.none() | st.floats(0.0, 0.5),
    "step_height": st.floats(0.005, 0.1), "body_height": st.none() | st.floats(0.02, 0.2),
    "foot_radius": st.none() | st.floats(0.05, 0.3), "yaw_rate": st.floats(-1.0, 1.0),
    "samples": st.integers(20, 5000),
}


@FAST
@given(st.fixed_dictionaries({}, optional=gait_values))
def test_valid_gait_parameters_are_kept_and_round_trip(values):
    gait = hexaleg.GaitParams(**values)
    for name, value in values.items():
        assert getattr(gait, name) == value
    assert type(gait.samples) is int and isinstance(gait.groups[0], tuple)
    expected = values.get("speed")
    stride = gait.stride_length if expected is None else expected * gait.period
    assert gait.stride == pytest.approx(stride) and gait.velocity == pytest.approx(
        stride / gait.period)
    table = {k: (list(map(list, v)) if k == "groups" else v)
             for k, v in dataclasses.asdict(gait).items() if v is not None}
    assert from_mapping(hexaleg.GaitParams, table) == gait


bad_gait = {
    "period": st.one_of(bad_numbers, st.floats(max_value=0.0)),
    "duty_factor": st.one_of(bad_numbers.filter(lambda v: v is not None),  # None: the default
                             st.floats(min_value=1.0), st.floats(max_value=0.0)),
    "stride_length": st.one_of(bad_numbers, st.floats(max_value=-1e-9)),
    "step_height": st.one_of(bad_numbers, st.floats(max_value=0.0)),
    "yaw_rate": bad_numbers.filter(lambda v: v is not None),
    "samples": st.one_of(st.booleans(), st.floats(allow_nan=True), st.integers(max_value=19),
                         st.integers(min_value=70000), st.text(max_size=2)),
    "groups": st.one_of(st.text(min_size=1, max_size=3), st.just(()), st.just((("LF", "LF"),))),
}


@FAST
@given(st.sampled_from(sorted(bad_gait)).flatmap(
    lambda name: st.tuples(st.just(name), bad_gait[name])))
def test_invalid_gait_parameters_are_named(bad):
    name, value = bad
    with pytest.raises(InvalidParameterError) as e:
        hexaleg.GaitParams(**{name: value})
    assert e.value.name == name
    shown = str(e.value)
    assert f"{name} = " in shown and (repr(value) in shown or str(value) in shown)


# --------------------------------------------------------------------------- the force program


@pytest.fixture(scope="module")
def hexapod():
    return hexaleg.load()


@SLOW
@given(period=st.floats(0.6, 2.0), stride=st.floats(0.0, 0.06),
       step_height=st.floats(0.015, 0.04), k=st.floats(0.0, 1.0), theta=st.floats(0.02, 0.3),
       joint=st.sampled_from(["femur", "tibia"]))
def test_forces_satisfy_newton_euler_for_any_gait_and_springs(hexapod, period, stride,
                                                              step_height, k, theta, joint):
    from hexaleg.design.rules import centred_springs

    robot = hexapod
    gait = hexaleg.GaitParams(period=period, stride_length=stride, step_height=step_height,
                              samples=40)
    motion = hexaleg.gait(robot, gait)
    springs = centred_springs(robot, motion, joint, k, dead_zone=min(theta / 0.3, 0.9))
    analysis = hexaleg.prepare(robot, motion, contact=hexaleg.ContactParams(
        torque_limits=False)).evaluate(springs)
    model, data = robot.model, robot.model.createData()
    mu = analysis.contact.mu
    for i in range(motion.n_samples):
        q, v, a = motion.q[i], motion.v[i], motion.a[i]
        b = pin.rnea(model, data, q, v, a)
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacements(model, data)
        contact = np.zeros(model.nv)
        for j, leg in enumerate(robot.legs):
            J = pin.getFrameJacobian(model, data, leg.foot_frame_id,
                                     pin.LOCAL_WORLD_ALIGNED)[:3]
            contact += J.T @ analysis.forces[i, j]
        actuated = np.concatenate([np.zeros(6), analysis.tau_motor[i] + analysis.tau_spring[i]])
        scale = 1.0 + float(np.max(np.abs(b)))
        np.testing.assert_allclose(contact + actuated, b, atol=1e-6 * scale)
        f = analysis.forces[i]
        stance = motion.stance[i]
        assert np.all(f[~stance] == 0.0)
        assert np.all(np.hypot(f[stance, 0], f[stance, 1]) <= mu * f[stance, 2] + 1e-7 * scale)


@FAST
@given(st.sampled_from(["mu", "min_normal_force", "regularization", "cone", "torque_limits"])
       .flatmap(lambda n: st.tuples(st.just(n), bad_numbers if n != "cone"
                                    else st.text(max_size=4).filter(lambda s: s not in
                                                                    ("soc", "pyramid")))))
def test_invalid_contact_settings_are_named(bad):
    name, value = bad
    if name == "torque_limits" and isinstance(value, bool):
        return  # a bool is what torque_limits is
    with pytest.raises(InvalidParameterError) as e:
        hexaleg.ContactParams(**{name: value})
    assert e.value.name == f"ContactParams.{name}"


# --- Every reader of a file hexaleg takes, fed hostile files (#28) ------------------------------
# Each reader gets its file truncated, empty, oversized (a sparse file past its bound), as a named
# pipe with no writer, /dev/zero, a directory, a link to a pipe or garbage bytes: it returns (a
# truncated TOML may still be TOML) or raises a named HexalegError — never another exception,
# never a hang (an alarm ends the example), and nothing outside the output directory changes.

def _seeds(robot: hexaleg.Robot) -> dict[str, bytes]:
    """A valid file for each reader."""
    import io
    import json

    from hexaleg.simulation.motion_file import FORMAT

    design = {"robot": {"name": robot.name}, "springs": [
        {"family": "linear", "joint": "LF_femur", "parameters": {
            "stiffness": {"value": 0.5, "unit": "N·m/rad"},
            "reference": {"value": 0.3, "unit": "rad"}}}]}
    k = 3
    motion = io.BytesIO()
    np.savez_compressed(motion, format=FORMAT, robot=robot.name, run="springs", verdict="ran",
                        message="", joint_names=np.array(robot.joint_names), legs=np.array(
                            robot.leg_names), timestep=5e-4, stride=20, t=np.arange(k) * 0.01,
                        q=np.zeros((k, robot.model.nq)), v=np.zeros((k, robot.model.nv)),
                        **{n: np.zeros((k, robot.nj)) for n in ("tau_motor", "power",
                                                                 "tau_spring")},
                        feet=np.zeros((k, 6, 3)), forces=np.zeros((k, 6, 3)))
    return {"toml": b"[gait]\nperiod = 1.5\nsamples = 100\n",
            "design": json.dumps(design).encode(),
            "manifest": json.dumps({"spec": {"gait": {"samples": 50}}}).encode(),
            "motion": motion.getvalue()}


def _readers(robot: hexaleg.Robot) -> dict[str, tuple[str, object]]:
    """Reader name → (its seed, a call on a path; the manifest's in an output directory)."""
    from hexaleg.config import load_toml
    from hexaleg.design.chain.design_file import read_design
    from hexaleg.report.design_section import design_section
    from hexaleg.simulation.motion_file import read_motion
    from hexaleg.sweep.store import MANIFEST, ResultStore

    def store(path):
        out = path.parent / "sweep"
        out.mkdir(exist_ok=True)
        (out / MANIFEST).unlink(missing_ok=True)
        path.rename(out / MANIFEST) if not path.is_symlink() else (out / MANIFEST).symlink_to(
            path.readlink())
        ResultStore(out, {"gait": {"samples": 50}}).close()

    return {"config": ("toml", load_toml), "design file": ("design", lambda p: read_design(
                p, robot)),
            "report --design": ("design", lambda p: design_section(p, robot)),
            "motion file": ("motion", read_motion), "sweep manifest": ("manifest", store)}


KINDS = ("truncated", "empty", "oversized", "fifo", "dev-zero", "directory", "link-to-fifo",
         "garbage")


@pytest.mark.parametrize("reader", ["config", "design file", "report --design", "motion file",
                                    "sweep manifest"])
@settings(max_examples=25, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(kind=st.sampled_from(KINDS), cut=st.floats(0.0, 1.0), junk=st.binary(max_size=64))
def test_every_reader_names_a_hostile_file(robot, tmp_path_factory, reader, kind, cut, junk):
    import os
    import signal
    from pathlib import Path

    from hexaleg import config
    from hexaleg.simulation import motion_file

    seed_name, read = _readers(robot)[reader]
    seed = _seeds(robot)[seed_name]
    base = tmp_path_factory.mktemp("hostile")
    outside = base / "outside"
    outside.mkdir()
    (outside / "precious.txt").write_text("keep me")
    work = base / "work"
    work.mkdir()
    path = work / "input"
    if kind == "truncated":
        path.write_bytes(seed[:int(cut * len(seed))])
    elif kind == "empty":
        path.write_bytes(b"")
    elif kind == "oversized":
        with open(path, "wb") as f:  # sparse: no disk used
            limit = motion_file.MAX_MOTION_BYTES if reader == "motion file" else \
                config.MAX_TEXT_BYTES
            f.truncate(limit + 1)
    elif kind == "fifo":
        os.mkfifo(path)
    elif kind == "dev-zero":
        path.symlink_to("/dev/zero")
    elif kind == "directory":
        path.mkdir()
    elif kind == "link-to-fifo":
        os.mkfifo(outside / "pipe")
        path.symlink_to(outside / "pipe")
    else:
        path.write_bytes(junk + seed[int(cut * len(seed)):])
    before = {p.name: (p.stat().st_mtime_ns, p.read_bytes() if p.is_file() else b"")
              for p in outside.iterdir()}

    def hang(*_args):
        raise TimeoutError(f"{reader} hung on a {kind} file")

    old = signal.signal(signal.SIGALRM, hang)
    signal.alarm(20)
    try:
        read(path)
    except hexaleg.HexalegError:
        pass
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    after = {p.name: (p.stat().st_mtime_ns, p.read_bytes() if p.is_file() else b"")
             for p in outside.iterdir()}
    assert after == before and Path(outside / "precious.txt").read_text() == "keep me"
