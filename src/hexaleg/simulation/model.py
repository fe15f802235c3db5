"""The robot in MuJoCo: tree, ground, contacts, springs, servos, sensors, timestep and integrator.

:func:`build_model` writes one MJCF document (:mod:`~hexaleg.simulation.mjcf` for the robot's
tree, :mod:`~hexaleg.simulation.springs` for the springs,
:mod:`~hexaleg.simulation.controllers` for the servos) and compiles it:

* a ground plane (the world's ``ground`` geom) and explicit contact ``<pair>``\\ s only — the foot
  spheres, and every collision geom of the robot that stays clear of the ground over the planned
  motion (:data:`CLEARANCE`; a geom that the plan brings closer, e.g. a shank mesh that contains
  the foot, is left out and noted). No robot–robot contacts: the analysis has none;
* contact parameters from :class:`~hexaleg.simulation.ground.Ground` (physical K, B, μ →
  ``solref``/``solimp``, per pair from its body's ``body_invweight0``), elliptic friction cones
  (the analysis' ``"soc"`` cone), ``impratio`` and the optional no-slip pass;
* sensors: each servo's actuator force and each foot site's position.

**Integrator and timestep.** MuJoCo's semi-implicit (symplectic) Euler, with its implicit joint
damping switched off (``eulerdamp`` disabled) so that the damping force recorded is the one
applied: every force of the model — servo PD, back-EMF damping, springs, the penalty-like
contacts — is then explicit in the state, and the recorded motor torque times the recorded speed is
exactly the power integrated. Symplectic Euler conserves the energy of a conservative system up to
an O(dt) oscillation without drift (Hairer, Lubich & Wanner, *Geometric Numerical Integration*,
2006, §VI.3), which is what a run over many cycles needs; a digital servo holds its command over a
control period anyway. An explicit scheme is stable for ``ẍ = −a ẋ − b x`` while
``b dt² + 2 a dt < 4`` (the Jury criterion of the symplectic-Euler step matrix);
:func:`check_timestep` asks for half of that for every servo (``a = max(kd, D)/I``,
``b = kp/I``, I the effective inertia ``1/(M⁻¹)_jj`` at the start) and every foot contact
(``a = B/m``, ``b = K/m``, m the mass the foot point moves while its friction holds it, at the
start: :func:`~hexaleg.simulation.foot_mass.held_masses`), and a timestep below the gait's sample
spacing. For a contact's damping this is MuJoCo's own rule for soft constraints (documentation,
"Modeling → Solver parameters": ``solref``'s time constant, here ``2m/B``, at least twice the
timestep). The contact's force is the physical ``K δ + B δ̇`` whatever ``solref`` was scaled by
(:mod:`~hexaleg.simulation.ground`), so the mass it moves is the foot point's, not its body's
``body_invweight0``: HyQ's foot at the end of its shank moves 0.83 kg on a 2-kg shank, and sized
at the shank its feet lost the ground in up to 39 % of their stance samples. The default
:data:`TIMESTEP` meets both for the built-in robot; the convergence of the results under dt/2 is
in ``docs/simulate.md``.

**Constraint solver.** MuJoCo's projected Gauss–Seidel (``PGS``) on the dual of the contact
problem instead of its default primal Newton solver: both solve the same strictly convex soft-
constraint program (MuJoCo documentation, Computation → Solver), and on the built-in gait the
energies per cycle agree to 1e-5 J (tested) while a step costs about a fifth less — with six
point contacts the dual is 18 rows against Newton's 24 × 24 Hessian. MuJoCo's constraint-island
discovery (on by default since 3.3) is switched off: every contact of a walking robot couples
through its base, so there is one island and the search only costs time (about 4 % of a step;
the states are bitwise the same, tested).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg.checks import positive
from hexaleg.errors import InvalidParameterError, RobotModelError
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet
from hexaleg.simulation.controllers import Servo, ServoMotor, servo_xml
from hexaleg.simulation.foot_mass import held_masses, point_sliding_masses
from hexaleg.simulation.ground import FOOT_RADIUS, IMPRATIO, Ground
from hexaleg.simulation.mjcf import (
    FOOT_CLASS,
    GEOM_CLASS,
    contact_geoms,
    fmt,
    foot_site,
    tree_xml,
)
from hexaleg.simulation.springs import SpringPlan, plan_springs
from hexaleg.simulation.state import JointMap
from hexaleg.units import G

TIMESTEP = 5e-4
"""s: the default simulation timestep (half the default gait's sample spacing)."""
CLEARANCE = 2e-3
"""m: a robot geom gets a ground contact if it stays this far above the ground over the plan."""
NOSLIP_ITERATIONS = 20
"""MuJoCo ``noslip_iterations`` when :attr:`Ground.noslip` is set."""
STABILITY = 2.0
"""The explicit-stability bound b dt² + 2 a dt must stay below this (half the limit 4)."""
GROUND = "ground"
"""Name of the ground plane geom."""


@dataclass(frozen=True, eq=False)
class SimModel:
    """A compiled MuJoCo model of a robot with its springs and servos.

    Attributes:
        robot: The robot.
        model: The ``mujoco.MjModel``.
        xml: The MJCF it was compiled from (contact ``solref`` set after compiling).
        joints: The Pinocchio ↔ MuJoCo map.
        springs: How the springs are built (:class:`~hexaleg.simulation.springs.SpringPlan`).
        servo: The servo settings.
        ground: The ground.
        kp: Position gains, (nj,), N·m/rad. kd: Velocity gains, (nj,), N·m·s/rad.
        damping: Back-EMF damping D, (nj,), N·m·s/rad. stall: Stall torques, (nj,), N·m.
        foot_geoms: MuJoCo geom id of each leg's foot sphere (a sole's first corner), (n_legs,),
            legs in robot order.
        notes: What was approximated or left out.
        tree: The robot's bodies as MJCF (:func:`~hexaleg.simulation.mjcf.tree_xml`).
        contacts: Its ground contacts as MJCF ``<pair>`` elements.
        foot_contacts: Per leg, the geom ids of its foot's contact spheres: the foot sphere,
            or a sole's four corners (:func:`~hexaleg.simulation.mjcf.contact_geoms`).
    """

    robot: Robot
    model: object
    xml: str
    joints: JointMap
    springs: SpringPlan
    servo: Servo
    ground: Ground
    kp: np.ndarray
    kd: np.ndarray
    damping: np.ndarray
    stall: np.ndarray
    foot_geoms: np.ndarray
    notes: tuple[str, ...]
    tree: str = ""
    contacts: str = ""
    foot_contacts: tuple[tuple[int, ...], ...] = ()

    @property
    def timestep(self) -> float:
        """s."""
        return float(self.model.opt.timestep)  # type: ignore[attr-defined]

    def spring_torque(self, data: object) -> np.ndarray:
        """The springs' torque on every joint at a computed ``mujoco.MjData`` (after
        ``mj_forward``), shape (nj,), N·m: MuJoCo's passive spring force (joint and tendon
        springs), the spring actuators (constant torques, preload steps) and the non-native
        terms."""
        import mujoco

        m, d = self.model, data
        assert isinstance(m, mujoco.MjModel) and isinstance(d, mujoco.MjData)
        tau = np.array(d.qfrc_spring)[self.joints.dof]
        for actuator in self.springs.actuators:
            aid = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, actuator.name)
            tau[self.robot.column(actuator.joint)] += d.actuator_force[aid]
        return tau + self.springs.python_torque(d.qpos[self.joints.qpos],
                                                d.qvel[self.joints.dof])

    def sensor_slices(self) -> tuple[slice, slice]:
        """Where ``sensordata`` holds the servo forces (nj) and the foot positions
        (n_legs × 3)."""
        nj, n_legs = self.robot.nj, len(self.robot.legs)
        return slice(0, nj), slice(nj, nj + 3 * n_legs)


def _lowest(kind: np.ndarray, size: np.ndarray, rz: np.ndarray) -> np.ndarray:
    """Depth of MuJoCo primitives' lowest points below their centres, shape (…, g): geoms of
    types ``kind`` (g,) and sizes ``size`` (g, 3) whose rotations have the third rows ``rz``
    (…, g, 3) — a sphere its radius, a box Σ |R₂ⱼ| hⱼ, a capsule ``h |R₂₂| + r``, a cylinder
    ``h |R₂₂| + r √(1 − R₂₂²)``."""
    import mujoco

    axial = size[:, 1] * np.abs(rz[..., 2])
    cylinder = axial + size[:, 0] * np.sqrt(np.maximum(0.0, 1.0 - rz[..., 2] ** 2))
    return np.select([kind == mujoco.mjtGeom.mjGEOM_SPHERE, kind == mujoco.mjtGeom.mjGEOM_BOX,
                      kind == mujoco.mjtGeom.mjGEOM_CAPSULE],
                     [np.broadcast_to(size[:, 0], axial.shape),
                      np.sum(np.abs(rz) * size[:, :3], axis=-1), axial + size[:, 0]], cylinder)


def _inverse_weight(model: object, geom: int) -> float:
    """MuJoCo's ``body_invweight0`` (translation) of a geom's body, 1/kg: Â of its contacts."""
    m: Any = model
    weights = np.asarray(m.body_invweight0).reshape(m.nbody, 2)
    return float(weights[int(m.geom_bodyid[geom]), 0])


def _clear_geoms(model: object, joints: JointMap, motion: Motion, names: tuple[str, ...]
                 ) -> tuple[list[str], list[str]]:
    """The geoms that stay :data:`CLEARANCE` above the ground over ``motion`` (about 40 samples),
    and the others."""
    import mujoco

    assert isinstance(model, mujoco.MjModel)
    data = mujoco.MjData(model)
    ids = np.array([mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, n) for n in names],
                   dtype=int)
    samples = np.linspace(0, motion.n_samples - 1, min(40, motion.n_samples)).astype(int)
    qpos, _ = joints.to_mujoco(motion.q[samples], motion.v[samples])
    centre, rz = np.empty((len(samples), len(ids))), np.empty((len(samples), len(ids), 3))
    for i, q in enumerate(qpos):
        data.qpos[:] = q
        mujoco.mj_kinematics(model, data)
        centre[i], rz[i] = data.geom_xpos[ids, 2], data.geom_xmat[ids, 6:9]
    low = np.min(centre - _lowest(model.geom_type[ids], model.geom_size[ids], rz), axis=0,
                 initial=np.inf)
    clear = [n for n, z in zip(names, low, strict=True) if z > CLEARANCE]
    return clear, [n for n in names if n not in clear]


def _document(robot: Robot, tree: str, plan: SpringPlan, servos: str, pairs: str,
              sensors: str, timestep: float, ground: Ground) -> str:
    """The MJCF document."""
    gravity = ground.gravity(robot.heading, G)
    noslip = NOSLIP_ITERATIONS if ground.noslip else 0
    return "\n".join([
        f'<mujoco model="{robot.name}">',
        '<compiler angle="radian" autolimits="true"/>',
        f'<option timestep="{fmt(timestep)}" integrator="Euler" solver="PGS" cone="elliptic" '
        f'impratio="{fmt(IMPRATIO)}" noslip_iterations="{noslip}" gravity="{fmt(gravity)}">',
        '<flag eulerdamp="disable"/></option>',
        f'<default><default class="{GEOM_CLASS}"><geom contype="0" conaffinity="0" group="1"/>'
        f'</default><default class="{FOOT_CLASS}"><geom contype="0" conaffinity="0" group="2"/>'
        "</default></default>",
        f'<worldbody><geom name="{GROUND}" type="plane" size="0 0 1" contype="0" '
        'conaffinity="0"/>', tree, "</worldbody>",
        plan.tendon_xml(),
        f"<actuator>{servos}\n{plan.actuator_xml()}</actuator>",
        f"<contact>{pairs}</contact>", f"<sensor>{sensors}</sensor>", "</mujoco>"])


def build_model(robot: Robot, motion: Motion, motor: ServoMotor, *,
                springs: SpringSet | None = None, servo: Servo | None = None,
                ground: Ground | None = None, timestep: float = TIMESTEP, check: bool = True,
                like: SimModel | None = None) -> SimModel:
    """The MuJoCo model of ``robot`` for simulating ``motion`` (module docstring).

    Args:
        robot: The robot.
        motion: The planned motion (a gait): which geoms may touch the ground, the sample
            spacing the timestep must undercut, the inertias of the stability check.
        motor: The servo model (stall torque and no-load speed, one or per joint).
        springs: The springs, or None.
        servo: Controller and gains (default :class:`Servo`).
        ground: The ground (default :class:`Ground`).
        timestep: Simulation timestep, s, > 0.
        check: Check the timestep (:func:`check_timestep`); off only to find a timestep
            (:func:`timestep_limit`).
        like: A model already built of the same robot, motion, motor, servo and ground (any
            springs and timestep): its bodies, joint map and ground contacts are taken as they
            are — the same MJCF, so the same model — instead of being worked out again (which
            geoms stay clear of the ground over the plan, each contact's inverse weight): two
            thirds of the cost of building a model (``docs/simulate.md``, "Speed").

    Returns:
        The compiled model.

    Raises:
        InvalidParameterError: a timestep that is not below the gait's sample spacing or too
            large for explicit stability (names the limit and the joint or foot that sets it).
        UnknownNameError: a sprung joint the robot does not have.
        RobotModelError: a joint the simulation cannot build, an inertia MuJoCo refuses, or the
            base below the feet (:func:`check_stand`).
        InvalidParameterError: ``like`` a model of another robot, servo, motor or ground.
    """
    import mujoco

    servo, ground = servo or Servo(), ground or Ground()
    positive("timestep (s)", timestep)
    plan = plan_springs(robot, springs)
    kp, kd, damping, stall = servo.gains(motor, robot.nj)
    servos = servo_xml(robot.joint_names, kp, kd, damping, stall)
    sensors = "\n".join([*(f'<actuatorfrc actuator="{j}_servo"/>' for j in robot.joint_names),
                         *(f'<framepos objtype="site" objname="{foot_site(leg.name)}"/>'
                           for leg in robot.legs)])
    feet = contact_geoms(robot)
    if like is not None:
        if like.robot is not robot or like.servo != servo or like.ground != ground or not all(
                np.array_equal(a, b) for a, b in ((like.kp, kp), (like.kd, kd),
                                                  (like.damping, damping), (like.stall, stall))):
            raise InvalidParameterError("like", "a model of another robot, servo, motor or "
                                        "ground", "a model of this robot with this servo, motor "
                                        "and ground")
        return _compiled(robot, motion, _document(robot, like.tree, plan, servos, like.contacts,
                                                  sensors, timestep, ground),
                         plan, servo, ground, (kp, kd, damping, stall), like.joints, feet,
                         like.notes, like.tree, like.contacts, check)
    check_stand(robot, motion)
    tree = tree_xml(robot, FOOT_RADIUS)
    first = mujoco.MjModel.from_xml_string(
        _document(robot, tree.xml, plan, servos, "", sensors, timestep, ground))
    joints = JointMap.build(robot, first)
    clear, touching = _clear_geoms(first, joints, motion, tree.geoms)

    def pair(geom: str) -> str:
        inverse_weight = _inverse_weight(first, mujoco.mj_name2id(first, mujoco.mjtObj.mjOBJ_GEOM,
                                                                  geom))
        foot = geom.endswith("_foot_contact")
        margin = f' margin="{fmt(-FOOT_RADIUS)}" gap="{fmt(FOOT_RADIUS)}"' if foot else ""
        return (f'<pair geom1="{GROUND}" geom2="{geom}" condim="3" friction="'
                f'{fmt([ground.mu, ground.mu, 0.005, 1e-4, 1e-4])}" '
                f'solref="{fmt(ground.solref(inverse_weight))}" '
                f'solreffriction="{fmt(ground.solreffriction())}" '
                f'solimp="{fmt(ground.solimp())}"{margin}/>')

    contacts = "\n".join(pair(g) for g in [*(g for leg in feet for g in leg), *clear])
    notes = (*tree.notes, *(f"{g}: no ground contact (within {CLEARANCE * 1e3:g} mm of the "
                            "ground in the plan)" for g in touching))
    return _compiled(robot, motion, _document(robot, tree.xml, plan, servos, contacts, sensors,
                                              timestep, ground),
                     plan, servo, ground, (kp, kd, damping, stall), joints, feet, notes,
                     tree.xml, contacts, check)


def _compiled(robot: Robot, motion: Motion, xml: str, plan: SpringPlan, servo: Servo,
              ground: Ground, gains: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
              joints: JointMap, feet: list[list[str]], notes: tuple[str, ...], tree: str,
              contacts: str, check: bool) -> SimModel:
    """The model of a finished document (:func:`build_model`): compiled, the springs and the
    back-EMF damping applied, the flags set, the timestep checked."""
    import mujoco

    kp, kd, damping, stall = gains
    model = mujoco.MjModel.from_xml_string(xml)
    plan.apply(model)
    model.dof_damping[joints.dof] = damping
    if hasattr(mujoco.mjtDisableBit, "mjDSBL_AUTORESET"):  # keep a diverged state (a verdict)
        model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_AUTORESET)
    if hasattr(mujoco.mjtDisableBit, "mjDSBL_ISLAND"):  # one island: the search is pure cost
        model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_ISLAND)
    ids = tuple(tuple(mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, g) for g in leg)
                for leg in feet)
    sim = SimModel(robot=robot, model=model, xml=xml, joints=joints, springs=plan, servo=servo,
                   ground=ground, kp=kp, kd=kd, damping=damping, stall=stall,
                   foot_geoms=np.array([leg[0] for leg in ids]), notes=notes, tree=tree,
                   contacts=contacts, foot_contacts=ids)
    if check:
        check_timestep(sim, motion)
    return sim


def check_stand(robot: Robot, motion: Motion) -> None:
    """The base above the feet at the motion's start, checked before anything is built.

    A root frame below the feet (a URDF whose root link is a foot-level frame) places the body
    origin under the ground at every sample: the gait is then no stand at all, and MuJoCo's
    contacts and the measures come out empty. Requires ``z_base − mean_i z_foot,i > 0`` at
    ``motion.q[0]`` (as :func:`hexaleg.robot.sanity.stand_findings` in the stand pose).

    Raises:
        RobotModelError: names the body height found, what is allowed and the fix.
    """
    q = motion.q[0]
    height = float(q[2] - robot.foot_positions(q)[:, 2].mean())
    if not height > 0:
        from hexaleg.robot.sanity import body_name

        root = body_name(robot.model, 1).split(" (")[0]
        raise RobotModelError(
            f"{robot.name}: the base origin is {height:+.4g} m above the mean foot at the "
            "motion's start (allowed: > 0 m, the base above the feet); the simulation cannot "
            f"stand it: move the URDF's root frame ({root}) into the body above the feet, or "
            "pose the legs below the body in the stand pose")


def _dt_limit(a: float, b: float) -> float:
    """Largest dt with ``b dt² + 2 a dt ≤ STABILITY``."""
    if b <= 0:
        return STABILITY / (2 * a) if a > 0 else np.inf
    return float((-2 * a + np.sqrt(4 * a * a + 4 * b * STABILITY)) / (2 * b))


def timestep_limit(sim: SimModel, motion: Motion) -> tuple[float, str]:
    """The largest timestep explicit integration allows (module docstring), s, and what sets it
    (a servo or a foot contact, with its numbers)."""
    robot = sim.robot
    minv = pin.computeMinverse(robot.model, robot.model.createData(), motion.q[0])
    inertia = 1.0 / np.diag(minv)[sim.joints.pin_v]  # the diagonal: the upper triangle holds it
    limits = [(_dt_limit(max(sim.kd[i], sim.damping[i]) / inertia[i], sim.kp[i] / inertia[i]),
               f"the servo of {j} (kp {sim.kp[i]:.3g} N·m/rad, kd {sim.kd[i]:.3g} N·m·s/rad, "
               f"effective inertia {inertia[i]:.3g} kg·m²)")
              for i, j in enumerate(robot.joint_names)]
    for leg, mass in zip(robot.legs, held_masses(robot, motion.q[0]), strict=True):
        b, a = sim.ground.explicit_rate(mass)
        limits.append((_dt_limit(a, b), f"the ground contact of {leg.name} (K "
                       f"{sim.ground.stiffness:.3g} N/m, B {sim.ground.damping:.3g} N·s/m, "
                       f"foot point's mass {mass:.3g} kg)"))
    return min(limits)


CONTACT_BOUND = 4.0
"""The explicit step's own stability bound ``b dt² + 2 a dt < 4`` (module docstring), which
:func:`contact_point_limit` holds a timestep to (not :data:`STABILITY`'s half of it)."""


def contact_point_limit(sim: SimModel, motion: Motion, bound: float = CONTACT_BOUND
                        ) -> tuple[float, str, float]:
    """The explicit-stability limit of the ground contacts at each contact point's own
    effective mass free to slide, s, the point and that mass (kg): ``m = 1/(J M⁻¹ Jᵀ)_zz`` at
    the motion's start (:func:`~hexaleg.simulation.foot_mass.point_sliding_masses`: a point
    foot's foot point, a sole's every corner), ``a = B/m``, ``b = K/m``, the largest dt with
    ``b dt² + 2 a dt ≤ bound``.

    :func:`timestep_limit` sizes a contact by the mass its foot point moves held by its friction
    (:func:`~hexaleg.simulation.foot_mass.held_masses`), not a sole's corners free to slide: a
    sole's toe corner on Unitree G1's 0.61-kg foot moves with 0.124 kg (``body_invweight0``
    1.31 kg), and at the automatic 0.2 ms the contact is past this bound (7.9 against 4): its
    forces jump 0 ↔ 4 kN between samples and the robot falls. Point feet on shanks move with a
    fifth of their body's mass too (``analysis/bench_logs/newcomers_simulate.log``) and walk at
    the automatic timestep, so this limit names a cause after a fall
    (:func:`hexaleg.simulation.falls.fall_cause`) and does not set the timestep."""
    worst = (np.inf, "", 0.0)
    for what, mass in zip(*point_sliding_masses(sim.robot, motion.q[0]), strict=True):
        b, a = sim.ground.explicit_rate(float(mass))
        limit = (float((-2 * a + np.sqrt(4 * a * a + 4 * b * bound)) / (2 * b)) if b > 0
                 else bound / (2 * a) if a > 0 else np.inf)
        worst = min(worst, (limit, what, float(mass)))
    return worst


def check_timestep(sim: SimModel, motion: Motion) -> None:
    """Check the timestep against the gait's sample spacing and explicit stability (module
    docstring).

    Raises:
        InvalidParameterError: names the timestep, the limit and what sets it.
    """
    dt = sim.timestep
    if dt >= motion.dt:
        raise InvalidParameterError("timestep (s)", dt, f"< the gait's sample spacing "
                                    f"{motion.dt:.4g} s (raise the gait's samples or lower dt)")
    limit, what = timestep_limit(sim, motion)
    if dt > limit:
        raise InvalidParameterError("timestep (s)", dt, f"≤ {limit:.3g} s for explicit "
                                    f"stability of {what}; lower dt or the gains/stiffness")
