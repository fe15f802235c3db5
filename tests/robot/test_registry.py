"""Tests of hexaleg.robot.registry: the registry loads Solo-12, ANYmal and Go2 from
example-robot-data and runs them through the same gait → dynamics → forces → energy pipeline as the
hexapod."""

from __future__ import annotations

import dataclasses
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.design.rules import centred_springs, k_M
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import analyze, prepare
from hexaleg.errors import UnknownNameError
from hexaleg.motion.legged import tripod_gait
from hexaleg.motion.scaling import robot_gait
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.description import RobotDescription
from hexaleg.robot.registry import DESCRIPTIONS, TROT, description, load

QUADRUPEDS = ("solo12", "anymal", "go2", "a1")
SAMPLES = 200
# The catalogue's actuators are hexaleg-sized servos and Solo-12's module (2.5 N·m at 12 A); the
# quadrupeds' torques are the physics under test, not an actuator's limit.
NO_LIMITS = ContactParams(torque_limits=False)

_cache: dict[str, hexaleg.Robot] = {}


def robot_of(name: str) -> hexaleg.Robot:
    """Load each robot once per test session (ANYmal's visual meshes take seconds)."""
    if name not in _cache:
        _cache[name] = load(name)
    return _cache[name]


@pytest.fixture(scope="module", params=QUADRUPEDS)
def quad(request) -> tuple[RobotDescription, hexaleg.Robot]:
    return description(request.param), robot_of(request.param)


def srdf_pose(path, name: str) -> dict[str, float]:
    root = ET.parse(path).getroot()
    state = next(s for s in root.iter("group_state") if s.get("name") == name)
    return {j.get("name"): float(j.get("value")) for j in state
            if j.get("name") != "root_joint"}


def test_registry_names_and_unknown_name_lists_them():
    assert set(QUADRUPEDS) <= set(DESCRIPTIONS) and "hexaleg" in DESCRIPTIONS
    with pytest.raises(UnknownNameError) as err:
        load("spot")
    for name in DESCRIPTIONS:
        assert name in str(err.value)
    assert "'spot'" in str(err.value)


def test_hexaleg_entry_is_the_built_in_robot():
    robot, ref = load("hexaleg"), hexaleg.load()
    assert robot.joint_names == ref.joint_names and robot.leg_names == ref.leg_names
    assert robot.model.nq == 25 and robot.joint_kinds == ("coxa", "femur", "tibia")
    assert set(robot.poses) == set(ref.poses)
    for name, q in ref.poses.items():
        assert np.array_equal(robot.poses[name], q)
    assert description().name == "hexaleg" and description().spring_class == "femur"


def test_loads_with_legs_feet_and_joint_classes(quad):
    desc, robot = quad
    assert (robot.model.nq, robot.model.nv, robot.nj) == (19, 18, 12)
    assert robot.leg_names == ("LF", "RF", "LH", "RH")
    for leg, spec in zip(robot.legs, desc.legs, strict=True):
        assert leg.foot_frame == spec.foot and robot.model.existFrame(spec.foot)
        assert leg.joint_names == spec.joints
    classes = robot.joint_classes
    assert tuple(classes) == desc.joint_kinds
    assert all(len(joints) == 4 for joints in classes.values())
    assert sorted(j for joints in classes.values() for j in joints) == sorted(robot.joint_names)
    # The spring class is the knee: the last joint of every leg.
    assert robot.joints(desc.spring_class) == tuple(leg.joint_names[-1] for leg in robot.legs)
    assert robot.mass > 1.0


def test_stand_is_the_srdf_standing_pose_with_the_base_at_the_origin(quad):
    desc, robot = quad
    q = robot.pose("stand")
    assert np.array_equal(q, robot.pose("standing"))
    assert np.array_equal(q[:7], pin.neutral(robot.model)[:7])
    for joint, value in srdf_pose(desc.srdf_path, "standing").items():
        assert q[robot.model.joints[robot.model.getJointId(joint)].idx_q] == value
    # Standing on flat ground: all four feet at one depth, left and right mirror images.
    feet = robot.foot_positions(q)
    assert np.ptp(feet[:, 2]) <= 1e-9 and feet[0, 2] < -0.1
    left, right = feet[[0, 2]], feet[[1, 3]]
    assert np.allclose(left * [1, -1, 1], right, atol=1e-9)


@pytest.fixture(scope="module")
def trot(quad) -> Motion:
    """The robot's default trot, balanced by the body sway (``GaitParams.balance = "auto"``)."""
    desc, robot = quad
    return tripod_gait(robot, dataclasses.replace(robot_gait(desc), samples=SAMPLES))


def _stance_feet_at_rest(robot: hexaleg.Robot, motion: Motion) -> None:
    model, data = robot.model, robot.model.createData()
    frame = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    for k in range(0, motion.n_samples, 7):
        pin.forwardKinematics(model, data, motion.q[k], motion.v[k], motion.a[k])
        pin.updateFramePlacements(model, data)
        for i, leg in enumerate(robot.legs):
            pos = data.oMf[leg.foot_frame_id].translation
            assert np.allclose(pos, motion.feet[k, i], atol=1e-9)
            if motion.stance[k, i]:
                fid = leg.foot_frame_id
                assert np.allclose(pin.getFrameVelocity(model, data, fid, frame).linear, 0.0,
                                   atol=1e-9)
                assert np.allclose(pin.getFrameClassicalAcceleration(model, data, fid, frame)
                                   .linear, 0.0, atol=1e-9)


def test_trot_moves_diagonal_pairs_with_stance_feet_at_rest(quad, trot):
    desc, robot = quad
    assert robot_gait(desc).groups == TROT
    assert set(trot.info["ik"].values()) == {"newton"}
    legs = robot.leg_names
    stance = trot.stance
    assert np.array_equal(stance[:, legs.index("LF")], stance[:, legs.index("RH")])
    assert np.array_equal(stance[:, legs.index("RF")], stance[:, legs.index("LH")])
    assert trot.info["min_stance_feet"] == 2
    _stance_feet_at_rest(robot, trot)


def _support_line_moment(robot: hexaleg.Robot, motion: Motion, system) -> float:
    """The largest moment about the two stance feet's line that the base rows need, relative
    to m g |r| (r: the first foot from the base), after checking that the two feet's forces
    have none."""
    worst = 0.0
    for k in np.flatnonzero(motion.stance.sum(axis=1) == 2):
        i, j = np.flatnonzero(motion.stance[k])
        p_i, p_j = motion.feet[k, i], motion.feet[k, j]
        axis = (p_j - p_i) / np.linalg.norm(p_j - p_i)
        # Base rows: force (3) then moment about the base origin (3), in the local base frame;
        # the moment about the support line is the one along ``axis`` at a point on it.
        rot = pin.Quaternion(motion.q[k, 3:7]).toRotationMatrix()
        r_i = rot.T @ (p_i - motion.q[k, :3])
        ax = rot.T @ axis
        row = np.concatenate([np.cross(r_i, ax), ax])  # uᵀ (f, m) = axis · (m − r_i × f)
        assert np.abs(row @ system.A[k]).max() <= 1e-9 * np.abs(system.A[k]).max()
        worst = max(worst, abs(row @ system.b_base[k]) / (robot.mass * 9.81 * np.linalg.norm(
            r_i[:2])))
    return worst


def test_rigid_trot_on_two_point_feet_has_no_contact_forces(quad):
    """Forces at two points have no moment about the line through them; the constant-velocity
    body of the kinematic trot (``balance="none"``) needs one (gravity and the swing legs), so
    no contact forces exist in its two-foot phases."""
    desc, robot = quad
    rigid = tripod_gait(robot, dataclasses.replace(robot_gait(desc), samples=SAMPLES,
                                                   balance="none"))
    assert rigid.info["balance"] == {"mode": "none"}
    assert _support_line_moment(robot, rigid, prepare(robot, rigid, contact=NO_LIMITS).system) \
        > 1e-3  # the moment the two feet cannot give, relative to m g |r|
    with pytest.raises(hexaleg.errors.InfeasibleForcesError, match="body sway"):
        analyze(robot, rigid, contact=NO_LIMITS)


def test_balanced_trot_needs_no_moment_about_the_support_line(quad, trot):
    """The default trot sways laterally by a few millimetres (Solo) to centimetres (ANYmal) so
    that its two-foot phases need no support-line moment (≤ 1e-9 m g h by construction)."""
    _, robot = quad
    info = trot.info["balance"]
    assert info["mode"] == "sway" and info["direction"] == [0.0, 1.0, 0.0]
    assert info["residual"] <= 1e-9 and info["iterations"] <= 10
    assert 1e-3 < info["amplitude"] < 0.05
    assert _support_line_moment(robot, trot, prepare(robot, trot, contact=NO_LIMITS).system) \
        <= 1e-9


@pytest.fixture(scope="module")
def trotting(quad, trot):
    desc, robot = quad
    knee = robot.joints(desc.spring_class)
    springs = centred_springs(robot, trot, desc.spring_class, 4 * k_M(robot, trot, knee[0]))
    prepared = prepare(robot, trot, contact=NO_LIMITS)
    return prepared, prepared.evaluate(springs)


def test_knee_springs_through_the_pipeline_keep_the_invariants(quad, trot, trotting):
    """The real trot with knee springs: Newton–Euler of the whole robot, exact base rows, zero
    cyclic joint work, springs engaged only on the knees, the stance feet push."""
    desc, robot = quad
    prepared, result = trotting
    model, data = robot.model, robot.model.createData()
    rhs = np.empty((SAMPLES, 3))
    for k in range(SAMPLES):
        pin.centerOfMass(model, data, trot.q[k], trot.v[k], trot.a[k])
        rhs[k] = robot.mass * (data.acom[0] - model.gravity.linear)
    total = result.forces.sum(axis=1)
    assert np.max(np.abs(total - rhs)) <= 1e-8 * np.max(np.abs(rhs))
    f = result.forces.reshape(SAMPLES, -1)
    residual = np.einsum("tik,tk->ti", prepared.system.A, f) - prepared.system.b_base
    # Relative to the base wrench (ANYmal's is ~300 N): the sway leaves ≤ 1e-10 m g h.
    assert np.max(np.abs(residual)) <= 1e-9 * np.abs(prepared.system.b_base).max()
    p = result.tau_total * result.qdot
    assert abs(p.sum() * trot.dt) <= 1e-6 * np.abs(p).sum() * trot.dt
    knees = [robot.column(j) for j in robot.joints(desc.spring_class)]
    others = [c for c in range(robot.nj) if c not in knees]
    assert np.all(np.abs(result.tau_spring[:, knees]).max(axis=0) > 0)
    assert not result.tau_spring[:, others].any()
    assert not result.forces[~trot.stance].any()
    assert np.all(result.forces[..., 2][trot.stance] > 0)
    for key, value in result.savings["total"].items():
        assert np.isfinite(value), key
    assert result.metrics["total"]["absolute_work"] > 0


def test_stiff_knees_bind_friction_on_two_feet_and_stay_exact(quad, trot, trotting):
    """Stiff knee springs push the Joule-optimal forces out of the friction cone, so two-foot
    samples go to the conic solver (which must cope with the rank-5 base rows); the forces
    still meet the base rows and the cone."""
    desc, robot = quad
    prepared, _ = trotting
    stiff = centred_springs(robot, trot, desc.spring_class,
                            2000 * k_M(robot, trot, robot.joints(desc.spring_class)[0]))
    result = prepared.evaluate(stiff)
    assert result.resolved.any()
    f = result.forces.reshape(SAMPLES, -1)
    residual = np.einsum("tik,tk->ti", prepared.system.A, f) - prepared.system.b_base
    assert np.max(np.abs(residual)) <= 1e-6 * np.abs(prepared.system.b_base).max()
    fz = result.forces[..., 2]
    ft = np.hypot(result.forces[..., 0], result.forces[..., 1])
    assert np.all(ft[trot.stance] <= NO_LIMITS.mu * fz[trot.stance] + 1e-6)


def test_cli_robot_option(capsys):
    from hexaleg.cli import main

    assert main(["robot", "--robot", "go2"]) == 0
    out = capsys.readouterr().out
    assert "nq = 19" in out and "LH: RL_hip_joint, RL_thigh_joint, RL_calf_joint → RL_foot" in out
    assert "stand" in out.splitlines()[-1]
    assert main(["robot", "--robot", "spot"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("hexaleg robot: error: unknown robot 'spot'") and "solo12" in err
    assert main(["robot", "--robot", "go2", "--urdf", "x.urdf"]) == 2
    assert "either --robot or --urdf" in capsys.readouterr().err


@pytest.mark.parametrize("name", QUADRUPEDS)
def test_report_for_a_registry_robot(name, tmp_path, capsys, upstream_placeholders):
    """'hexaleg report --robot NAME': the trot from the description (the file's [gait] keys
    on top), knee springs and stiffness curve, all files; Solo-12 with its own actuator (ODRI
    module), A1 with its published energy model, the others with a generic actuator from their
    URDF limits and a note giving its assumptions; torque limits on for all (the actuator's
    stall torque)."""
    import json

    from hexaleg.cli import main

    config = tmp_path / "report.toml"
    config.write_text("[gait]\nsamples = 40\n[report]\nstiffness_points = 3\npaper_samples = 8\n")
    assert main(["report", "--robot", name, "--config", str(config),
                 "--out", str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    own = description(name).motor is not None
    assert own == (name in ("solo12", "a1"))
    assert (f"note: {description(name).title}" in out) != own
    assert ("names no catalogue motor" in out and "a generic actuator from its URDF limits"
            in out) != own
    assert max(len(line) for line in out.splitlines()) < 600  # one 3000-character note was
    data = json.loads((tmp_path / "out" / "report.json").read_text())
    desc, robot = description(name), robot_of(name)
    if own:
        assert data["motor"]["name"] == {"solo12": "ODRI-4004", "a1": "A1-Yang2021"}[name]
    else:  # one generic actuator per joint class, from that class's URDF limits
        effort = {k: robot.model.effortLimit[[6 + robot.column(j) for j in joints]].max()
                  for k, joints in robot.joint_classes.items()}
        stall = {c["joint_class"]: c["stall_torque"]["value"]
                 for c in data["motor"].get("classes", [])} or dict.fromkeys(
                     effort, data["motor"]["stall_torque"]["value"])
        assert stall == effort
        assert f"generic ({name} URDF limits)" in data["motor"]["name"]
    knees = list(robot.joints(desc.spring_class))
    assert data["gait"]["groups"] == [list(g) for g in TROT] and data["gait"]["samples"] == 40
    assert data["gait"]["period"]["value"] == robot_gait(desc).period
    assert data["gait"]["min_stance_feet"] == 2
    assert data["contact"]["torque_limits"] is True
    assert sorted(data["reference"]["joints"]) == sorted(knees)  # the paper's design, on knees
    assert data["stiffness_curve"]["joints"] == knees and not data["stiffness_curve"]["infeasible"]
    assert data["title"].startswith(desc.title)
    # The stance feet carry the weight on average over the cycle.
    weight = data["forces"]["weight"]["value"]
    assert data["forces"]["peak_total_normal_force"]["value"] > weight
    assert {"report.html", "report.json", "stiffness_curve.png"} <= set(data["files"])
    html = (tmp_path / "out" / "report.html").read_text()
    assert len(html) > 10_000
    # The caveats are on the page, not only in the terminal: motor figures and the sway.
    assert any("names no catalogue motor" in n for n in data["notes"]) != own
    assert any(n.startswith("two-foot gait: the body sways") for n in data["notes"])
    placeholders = len(upstream_placeholders.get(name, ()))  # the URDF's limits, flagged
    assert html.count("<b>Note:</b>") == len(data["notes"]) == (1 if own else 2) + placeholders
    assert data["transform"] is None and 'id="transform"' not in html  # no sphere pose
