"""The MuJoCo model is the analysed robot: inverse dynamics and the mass matrix agree with
Pinocchio, every clear geom touches the ground, the timestep is checked."""

from __future__ import annotations

import copy
import dataclasses

import mujoco
import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError
from hexaleg.simulation import stepping
from hexaleg.simulation.foot_mass import held_masses
from hexaleg.simulation.ground import Ground
from hexaleg.simulation.model import TIMESTEP, build_model, timestep_limit
from hexaleg.simulation.state import JointMap


@pytest.fixture(scope="module")
def sim(prepared):
    return build_model(prepared.robot, prepared.motion, prepared.motor)


def _random_states(robot: hexaleg.Robot, n: int, seed: int = 0):
    rng = np.random.default_rng(seed)
    m = robot.model
    for _ in range(n):
        q = pin.randomConfiguration(m, -np.ones(m.nq), np.ones(m.nq))
        yield q, rng.normal(size=m.nv), rng.normal(size=m.nv)


def _inverse(model, joints: JointMap, q, v, a) -> np.ndarray:
    """MuJoCo's inverse dynamics (no constraints, no passive forces) of Pinocchio ``q, v, a``."""
    m = model
    data = mujoco.MjData(m)
    data.qpos[:], data.qvel[:] = joints.to_mujoco(q, v)
    data.qacc[:] = joints.acceleration_to_mujoco(q, v, a)
    mujoco.mj_inverse(m, data)
    return data.qfrc_inverse.copy()


def _bare(sim) -> mujoco.MjModel:
    """A copy of the model without contacts, constraints, springs, damping and actuation."""
    m = copy.copy(sim.model)
    for flag in ("CONSTRAINT", "SPRING", "DAMPER", "PASSIVE", "ACTUATION"):
        m.opt.disableflags |= int(getattr(mujoco.mjtDisableBit, f"mjDSBL_{flag}", 0))
    m.dof_damping[:] = 0.0
    return m


@pytest.mark.parametrize("which", ["robot", "spider"])
def test_mujoco_inverse_dynamics_is_pinocchio_rnea(which, request):
    """mj_inverse at random states = RNEA (free flyer mapped), to 1e-12 N·m (docs/simulate.md:
    1.2e-14 of 17 N·m at 50 states): the joint order, the
    axes, the inertias and the free flyer's velocity and force conventions all agree. The spider
    (a test hexapod facing +y, joints found from its URDF) checks another tree."""
    robot = request.getfixturevalue(which)
    motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=100))
    sim = build_model(robot, motion, hexaleg.robot.catalogue.motor("AX-18A"), timestep=2.5e-4)
    m = _bare(sim)
    for q, v, a in _random_states(robot, 4):
        tau = pin.rnea(robot.model, robot.model.createData(), q, v, a)
        assert np.allclose(_inverse(m, sim.joints, q, v, a), sim.joints.force_to_mujoco(q, tau),
                           rtol=0, atol=1e-12)


def test_mass_matrices_agree(sim, robot):
    """Columns of MuJoCo's mass matrix (inverse dynamics of unit accelerations, no velocity, no
    gravity) are Pinocchio's CRBA mapped by the free flyer's velocity map T: M_mj = Tᵀ M T."""
    m = _bare(sim)
    m.opt.gravity[:] = 0.0
    q = next(_random_states(robot, 1, seed=3))[0]
    M = pin.crba(robot.model, robot.model.createData(), q)
    M = np.triu(M) + np.triu(M, 1).T
    rot = pin.Quaternion(q[3:7]).toRotationMatrix()
    T = np.eye(robot.model.nv)
    T[:3, :3] = rot.T  # v_pin = T v_mj
    data = mujoco.MjData(m)
    qpos, _ = sim.joints.to_mujoco(q, np.zeros(robot.model.nv))
    cols = []
    for i in range(m.nv):
        data.qpos[:], data.qvel[:] = qpos, 0.0
        data.qacc[:] = np.eye(m.nv)[i]
        mujoco.mj_inverse(m, data)
        cols.append(data.qfrc_inverse.copy())
    assert np.allclose(np.array(cols).T, T.T @ M @ T, rtol=0, atol=1e-10)


def test_every_geom_clear_of_the_plan_touches_the_ground(sim, robot):
    """Body collision: the torso, coxa, femur and tibia geoms each have a ground pair, plus one
    per foot."""
    assert sim.model.npair == len(robot.legs) + robot.collision_model.ngeoms - len(robot.legs)
    assert not sim.notes


def test_every_robot_geom_on_the_floor_touches_it(sim, prepared):
    """Each link's ground pair makes a contact where the link reaches the ground: the robot in
    its stand, lowered until the link is 1 mm into the floor, touches it with that link (a
    contact filter or exclusion that dropped a body, coxa, femur or tibia contact fails here)."""
    m = sim.model
    data = mujoco.MjData(m)
    qpos, _ = sim.joints.to_mujoco(prepared.motion.q[0], prepared.motion.v[0])
    ground = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "ground")
    links = [int(g) for g in m.pair_geom2 if g not in np.ravel(sim.foot_contacts)]
    assert links
    for g in links:
        data.qpos[:] = qpos
        mujoco.mj_kinematics(m, data)
        gap = mujoco.mj_geomDistance(m, data, ground, g, 1.0, None)
        data.qpos[2] -= gap + 1e-3
        mujoco.mj_forward(m, data)
        touching = {int(c.geom2) for c in data.contact[:data.ncon]}
        assert g in touching, mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_GEOM, g)


def test_a_limp_robot_lands_on_its_body_and_is_seen_fallen(sim, prepared):
    """The robot dropped from its stand with its servos off: the run is judged fallen (the base
    below half its planned height), and stepped on, the body comes to rest on the floor — its
    ground contact holds the base at about its half-height (25 mm) instead of letting it
    through."""
    limp = copy.copy(sim.model)
    limp.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_ACTUATION)
    motion = prepared.motion
    qpos0, qvel0 = sim.joints.to_mujoco(motion.q[0], motion.v[0])
    n = 4000
    run = stepping.run(dataclasses.replace(sim, model=limp), np.zeros((n, prepared.robot.nj)),
                       qpos0, qvel0, float(np.mean(motion.q[:, 2])))
    assert run.verdict == "fell" and "base height" in run.message
    data = mujoco.MjData(limp)
    data.qpos[:], data.qvel[:] = qpos0, qvel0
    body = mujoco.mj_name2id(limp, mujoco.mjtObj.mjOBJ_GEOM, "body_0")
    for _ in range(n):
        mujoco.mj_step(limp, data)
    assert body in {int(c.geom2) for c in data.contact[:data.ncon]}
    assert 0.015 < data.qpos[2] < 0.035


def test_the_built_in_robots_limit_is_its_hind_feet_contact(sim, prepared):
    """docs/simulate.md: explicit stability allows 0.68 ms on the built-in robot, set by a hind
    foot's contact at the 0.0726 kg its foot point moves (held by its friction,
    :mod:`hexaleg.simulation.foot_mass`): ``K dt² + 2 B dt ≤ 2 m``, MuJoCo's time constant
    ``2 m / B`` at least twice the step. Sized at MuJoCo's ``body_invweight0`` of the tibia
    (0.085 kg) the contact allowed 0.79 ms and a tibia servo's 0.73 ms set the limit."""
    robot = prepared.robot
    limit, what = timestep_limit(sim, prepared.motion)
    assert limit == pytest.approx(6.80e-4, rel=1e-3)
    assert what.startswith("the ground contact of") and "foot point's mass 0.0726 kg" in what
    k, b = sim.ground.stiffness, sim.ground.damping
    mass = float(held_masses(robot, prepared.motion.q[0]).min())
    assert k * limit**2 + 2 * b * limit == pytest.approx(2 * mass, rel=1e-9)


def test_timestep_must_undercut_the_gait_and_stay_stable(prepared):
    robot, motion, motor = prepared.robot, prepared.motion, prepared.motor
    with pytest.raises(InvalidParameterError, match="sample spacing"):
        build_model(robot, motion, motor, timestep=motion.dt)
    coarse = hexaleg.gait(robot, dataclasses.replace(hexaleg.GaitParams(), samples=200))
    with pytest.raises(InvalidParameterError, match="explicit stability of the servo"):
        build_model(robot, coarse, motor, timestep=2e-3, ground=Ground(2e3, 10.0))
    with pytest.raises(InvalidParameterError, match="ground contact"):
        build_model(robot, motion, motor, timestep=TIMESTEP,
                    ground=Ground(stiffness=1e7, damping=3e3))
    with pytest.raises(InvalidParameterError, match="timestep"):
        build_model(robot, motion, motor, timestep=-1.0)


def test_a_model_built_like_another_is_the_same_model(sim, prepared, optimal):
    """``build_model(..., like=)`` takes another model's bodies and ground contacts instead of
    working them out again: the document it compiles is the one built from scratch, character
    for character (so the model is the same), for other springs and another timestep; a model of
    another servo or ground is refused, never silently reused."""
    from hexaleg.simulation.controllers import Servo

    p = prepared
    kwargs = {"springs": optimal.springs, "timestep": TIMESTEP / 2}
    scratch = build_model(p.robot, p.motion, p.motor, **kwargs)
    like = build_model(p.robot, p.motion, p.motor, like=sim, **kwargs)
    assert like.xml == scratch.xml and like.notes == scratch.notes
    assert like.contacts == sim.contacts and like.contacts.count("<pair") >= len(p.robot.legs)
    assert like.springs.native and like.timestep == TIMESTEP / 2
    for other in ({"servo": Servo("position")}, {"ground": Ground(mu=0.3)}):
        with pytest.raises(InvalidParameterError, match="like"):
            build_model(p.robot, p.motion, p.motor, like=sim, **other)


def test_a_geoms_lowest_point_is_its_lowest_surface_point():
    """The clearance check's depth of a primitive's lowest point below its centre, for each kind
    at tilted poses, against MuJoCo's own surface: a point of a sphere, box, capsule and cylinder
    dropped onto a ground plane at that depth touches it (mj_geomDistance ≈ 0)."""
    from hexaleg.simulation.model import _lowest

    rng = np.random.default_rng(3)
    kinds = {"sphere": (0.03, 0, 0), "box": (0.02, 0.05, 0.01), "capsule": (0.015, 0.04, 0),
             "cylinder": (0.02, 0.03, 0)}
    for kind, size in kinds.items():
        xml = (f'<mujoco><worldbody><geom name="ground" type="plane" size="1 1 1"/><body>'
               f'<freejoint/><geom name="g" type="{kind}" size="{" ".join(map(str, size))}"/>'
               "</body></worldbody></mujoco>")
        m = mujoco.MjModel.from_xml_string(xml)
        d = mujoco.MjData(m)
        for _ in range(5):
            quat = rng.normal(size=4)
            d.qpos[:] = [0, 0, 1.0, *(quat / np.linalg.norm(quat))]
            mujoco.mj_kinematics(m, d)
            depth = _lowest(m.geom_type[1:], m.geom_size[1:], d.geom_xmat[None, 1:, 6:9])[0, 0]
            d.qpos[2] = depth  # the centre at the depth: the lowest point on the plane
            mujoco.mj_kinematics(m, d)
            gap = mujoco.mj_geomDistance(m, d, 0, 1, 1.0, None)
            assert abs(gap) < 1e-9, (kind, gap)


def test_a_contact_points_own_mass_is_mujocos_and_sets_its_limit():
    """``contact_point_limit`` on the biped on soles: each sole corner's effective mass along the
    normal (Pinocchio's ``M⁻¹`` and frame Jacobians) is MuJoCo's ``1/(J M⁻¹ Jᵀ)`` at the corner's
    site (``mj_jacSite``, ``mj_solveM``) to 1e-9, the lightest sets the limit, and at it the
    explicit step sits on its bound ``b dt² + 2 a dt = 4``. The corner moves with 0.137 kg where
    its body's ``body_invweight0`` says 1.04 kg (the foot turning about its ankle)."""
    from pathlib import Path

    from hexaleg.scenario.scenario import Scenario
    from hexaleg.simulation.mjcf import contact_sites
    from hexaleg.simulation.model import contact_point_limit

    p = Scenario.from_tables(str(Path(__file__).parents[1] / "data" / "biped6.toml"),
                             {"gait": {"samples": 100}}).prepare()
    robot, motion = p.robot, p.motion
    ground = Ground(stiffness=2.4e5, damping=1.2e3)
    sim = build_model(robot, motion, p.motor, ground=ground, check=False)
    limit, point, mass = contact_point_limit(sim, motion)
    m, data = sim.model, mujoco.MjData(sim.model)
    data.qpos[:], data.qvel[:] = sim.joints.to_mujoco(motion.q[0], motion.v[0])
    mujoco.mj_forward(m, data)
    masses = []
    for site in contact_sites(robot):
        jac = np.zeros((3, m.nv))
        mujoco.mj_jacSite(m, data, jac, None, mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE, site))
        x = np.zeros((1, m.nv))
        mujoco.mj_solveM(m, data, x, jac[2:3].copy())
        masses.append(1.0 / float(jac[2] @ x[0]))
    assert mass == pytest.approx(min(masses), rel=1e-9) and mass == pytest.approx(0.137, abs=1e-3)
    assert point == "R1's sole corner 0"
    a, b = ground.damping / mass, ground.stiffness / mass
    assert b * limit**2 + 2 * a * limit == pytest.approx(4.0, rel=1e-12)
