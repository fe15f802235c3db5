"""Sanity checks of a user's robot, as data: physically impossible inertias, a base below the feet.

Users bring their own URDFs, and a wrong number there silently changes every result downstream
(one public URDF gives a 0.58 m radius of gyration to 6 cm links, which doubles the predicted
energy). :func:`robot_findings` returns one :class:`Finding` per problem — empty when all is
well — and never raises on a bad robot: the caller decides whether to print, warn or stop.

The checks run on the rigid bodies of the Pinocchio model, i.e. one body per moving joint, with
every URDF link welded to it by fixed joints merged in (that is the inertia the dynamics use;
Carpentier et al., "The Pinocchio C++ library", SII 2019). A body is named after the URDF link
its joint moves (plus the number of links fixed to it), so the remedy points at the file.

The checks of a motion are in :mod:`hexaleg.motion.sanity`, those of joint torques in
:mod:`hexaleg.dynamics.sanity`; all return lists of the same :class:`Finding`.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from hexaleg.robot.loaded import Robot

TRIANGLE_TOL = 1e-3
"""Relative tolerance of the triangle inequality of the principal moments: a body is flagged when
``I1 + I2 < (1 − TRIANGLE_TOL) · I3``. Thin rods sit on the equality ``I1 + I2 = I3`` (with
``I1 → 0``) and URDFs print inertias to a few digits, so exact equality must pass; 1e-3 admits
rounding to four significant digits and nothing physically meaningful (the registry robots keep
≥ 1.5 % slack)."""
DEFINITE_TOL = 1e-12
"""A principal moment ``≤ DEFINITE_TOL · I_max`` counts as zero (not positive definite)."""
PLACEHOLDER_RANGE = 3.0 * math.pi
"""A joint range (upper − lower) above this, rad, is a placeholder: a leg joint turns less than
one and a half turns (the ±10 rad, 1000 N·m, 1000 rad/s a URDF exporter writes when no limit was
set, issue #39)."""
PLACEHOLDER_SPEED = 100.0
"""A joint speed limit above this, rad/s (955 rpm at the joint), is a placeholder: legged
robots' joints reach ~10–40 rad/s."""
PLACEHOLDER_TORQUE = 20.0
"""A joint torque limit above this many times the robot's weight at the leg's reach (m g L,
N·m) is a placeholder: it would lift twenty robots at arm's length."""
GYRATION_FACTOR = 2.0
"""A body is flagged when its radius of gyration exceeds ``GYRATION_FACTOR`` times its size.

Mass inside a ball of radius R about the centre of mass gives ``k = sqrt(I_max / m) ≤ R`` exactly
(see :func:`gyration_findings`), so ``k > R`` is impossible if the link's geometry holds all its
mass; the factor 2 (``I_max`` four times the largest possible) leaves room for geometry that
omits parts (motors, cables) and still catches the gross errors: a 0.58 m radius of gyration on a
6 cm link is ≈ 10 times its size. Registry robots: largest ``k / R`` is 1.11 (hexaleg's femur,
the paper's Table 6 "equivalent" inertia), the quadrupeds stay ≤ 0.62."""


@dataclass(frozen=True)
class Finding:
    """One failed sanity check: what, where, the value, what is allowed and how to fix it.

    Attributes:
        check: Short identifier of the check, e.g. ``"inertia_triangle"`` or ``"joint_speed"``.
        where: The link, joint, leg or instant it concerns, e.g. ``"joint LF_femur at t = 0.25 s"``.
        value: The offending value, in ``unit`` (SI).
        unit: Unit of ``value`` (``"kg"``, ``"m"``, ``"rad/s"``, ``"N·m"``, ``""`` for ratios).
        allowed: What would pass, in words with numbers and units.
        remedy: What to change, in the URDF, SRDF or gait.
    """

    check: str
    where: str
    value: float
    unit: str
    allowed: str
    remedy: str

    @property
    def message(self) -> str:
        """One line: ``check: where: value unit (allowed: …); remedy``."""
        # + 0.0 prints −0 as 0
        value = f"{self.value + 0.0:.4g}" + (f" {self.unit}" if self.unit else "")
        return f"{self.check}: {self.where}: {value} (allowed: {self.allowed}); {self.remedy}"


def robot_findings(robot: Robot) -> list[Finding]:
    """Every finding of the robot checks, in model order; empty when all pass.

    Checks :func:`inertia_findings` (masses, positive definite inertias, triangle inequality),
    :func:`gyration_findings` (radius of gyration against the link's size) and
    :func:`stand_findings` (the base above the feet in the stand pose) and
    :func:`stand_limit_findings` (joints outside their limits in the stand pose) and
    :func:`limit_findings` (placeholder joint limits).
    """
    return [*inertia_findings(robot), *gyration_findings(robot), *stand_findings(robot),
            *stand_limit_findings(robot), *limit_findings(robot)]


def body_name(model: pin.Model, joint_id: int) -> str:
    """``"link L (joint J)"``: the URDF link moved by joint ``joint_id`` and the joint, with the
    number of further links fixed to it (merged into the same Pinocchio body) when there are any."""
    joint = model.names[joint_id]
    bodies = [f for f in model.frames if f.type == pin.FrameType.BODY and f.parentJoint == joint_id]
    own = [f.name for f in bodies if model.frames[f.parentFrame].name == joint] or \
        [f.name for f in bodies[:1]]
    if not own:
        return f"joint {joint}"
    fixed = len(bodies) - 1
    extra = f", with {fixed} link{'s' if fixed > 1 else ''} fixed to it" if fixed else ""
    return f"link {own[0]} (joint {joint}{extra})"


def principal_moments(model: pin.Model, joint_id: int) -> np.ndarray:
    """Principal moments of inertia about the centre of mass of body ``joint_id``, ascending,
    shape (3,), kg·m² (eigenvalues of the symmetric rotational inertia)."""
    return np.linalg.eigvalsh(np.asarray(model.inertias[joint_id].inertia))


def inertia_findings(robot: Robot) -> list[Finding]:
    """Masses and rotational inertias that no rigid body can have.

    Per body (one per joint, free-flyer base included): the mass must be > 0; the rotational
    inertia about the centre of mass must be positive definite (principal moments
    ``0 < I1 ≤ I2 ≤ I3``, Featherstone, *Rigid Body Dynamics Algorithms*, Springer 2008, ch. 2:
    a rigid body's inertia is symmetric positive definite) and its principal moments must satisfy
    the triangle inequality ``I1 + I2 ≥ I3`` (with ``I_i = ∫ (r_j² + r_k²) dm``:
    ``I1 + I2 − I3 = 2 ∫ r_3² dm ≥ 0``; Traversaro, Brossette, Escande & Nori, "Identification of
    fully physical consistent inertial parameters using optimization on manifolds", IROS 2016).
    The other two inequalities hold whenever this one does for sorted moments. Tolerance:
    :data:`TRIANGLE_TOL`, :data:`DEFINITE_TOL`. A body that fails one check is not checked further.
    """
    model, found = robot.model, []
    for jid in range(1, model.njoints):
        where, mass = body_name(model, jid), float(model.inertias[jid].mass)
        fix = f"fix the URDF <inertial> of {where.split(' (')[0]}"
        if not mass > 0:
            found.append(Finding("mass", where, mass, "kg", "> 0 kg",
                                 f"{fix}: a zero or negative <mass> (Pinocchio accepts it, the "
                                 "dynamics are then meaningless)"))
            continue
        moments = principal_moments(model, jid)
        text = ", ".join(f"{i:.4g}" for i in moments)
        if not moments[0] > DEFINITE_TOL * max(abs(moments[2]), 1e-300):
            found.append(Finding("inertia_definite", where, float(moments[0]), "kg·m²",
                                 "smallest principal moment > 0 kg·m² (positive definite)",
                                 f"{fix}: principal moments {text} kg·m² about the CoM"))
            continue
        ratio = float((moments[0] + moments[1]) / moments[2])
        if ratio < 1.0 - TRIANGLE_TOL:
            found.append(Finding("inertia_triangle", where, ratio, "",
                                 f"(I1 + I2) / I3 ≥ {1.0 - TRIANGLE_TOL:g} (triangle inequality)",
                                 f"{fix}: principal moments {text} kg·m² about the CoM "
                                 "(no mass distribution has them)"))
    return found


def aabb_corners(obj: pin.GeometryObject) -> np.ndarray:
    """Corners of a geometry's local bounding box in its joint's frame, shape (8, 3), m
    (empty (0, 3) for unbounded or unsupported shapes)."""
    try:
        shape = obj.geometry
        shape.computeLocalAABB()
        lo, hi = np.asarray(shape.aabb_local.min_), np.asarray(shape.aabb_local.max_)
    except (AttributeError, RuntimeError):
        return np.zeros((0, 3))
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
        return np.zeros((0, 3))
    corners = np.array([[(hi if b else lo)[i] for i, b in enumerate(bits)]
                        for bits in itertools.product((0, 1), repeat=3)])
    return corners @ np.asarray(obj.placement.rotation).T + np.asarray(obj.placement.translation)


def body_size(robot: Robot, joint_id: int) -> float:
    """Size of body ``joint_id``: the largest distance from its centre of mass to its shape, m.

    The shape is every visual and collision geometry attached to the body (the 8 corners of each
    one's local axis-aligned bounding box, which contains it — Ericson, *Real-Time Collision
    Detection*, 2005, ch. 4) together with the body's joint origin, its child joints' origins and
    its frames (e.g. the foot): without geometry, the distance to the child joints.
    """
    model = robot.model
    points = [np.zeros((1, 3))]
    for gmodel in (robot.visual_model, robot.collision_model):
        points += [aabb_corners(g) for g in gmodel.geometryObjects if g.parentJoint == joint_id]
    points.append(np.array([model.jointPlacements[c].translation for c in range(1, model.njoints)
                            if model.parents[c] == joint_id]).reshape(-1, 3))
    points.append(np.array([f.placement.translation for f in model.frames
                            if f.parentJoint == joint_id]).reshape(-1, 3))
    com = np.asarray(model.inertias[joint_id].lever)
    return float(np.max(np.linalg.norm(np.vstack(points) - com, axis=1)))


def gyration_findings(robot: Robot) -> list[Finding]:
    """Bodies whose radius of gyration is too large for their size.

    The radius of gyration ``k = sqrt(I_max / m)`` (``I_max`` the largest principal moment about
    the CoM) of a mass inside a ball of radius R about its CoM is at most R: the distance of a
    point to an axis through the CoM is at most its distance to the CoM, so
    ``I = ∫ d⊥² dm ≤ ∫ |r|² dm ≤ m R²`` (the bounding-volume condition of Wensing, Kim & Slotine,
    "Linear matrix inequalities for physically consistent inertial parameter identification",
    IEEE RA-L 2018). R is :func:`body_size`; a body is flagged when ``k > GYRATION_FACTOR · R``
    (:data:`GYRATION_FACTOR`). Bodies without positive mass are left to :func:`inertia_findings`.
    """
    model, found = robot.model, []
    for jid in range(1, model.njoints):
        mass = float(model.inertias[jid].mass)
        moments = principal_moments(model, jid)
        if not (mass > 0 and moments[2] > 0):
            continue
        k, size = math.sqrt(moments[2] / mass), body_size(robot, jid)
        if k > GYRATION_FACTOR * size:
            where = body_name(model, jid)
            found.append(Finding(
                "radius_of_gyration", where, k, "m",
                f"≤ {GYRATION_FACTOR:g} × the link's size {size:.4g} m = "
                f"{GYRATION_FACTOR * size:.4g} m",
                f"fix the URDF <inertia> of {where.split(' (')[0]}: I_max = {moments[2]:.4g} "
                f"kg·m² with mass {mass:.4g} kg is a radius of gyration {k / size:.3g} times the "
                "link's size (inertia in the wrong unit, or about the joint, not the CoM?)"))
    return found


def stand_findings(robot: Robot) -> list[Finding]:
    """The base (root) frame must sit above the feet in the stand pose.

    In the ``stand`` pose (the neutral configuration when the SRDF has none), base at the origin
    with identity orientation: the body height ``h = z_base − mean_i z_foot,i`` must be > 0, and
    when it is, every foot must lie below the base origin (``z_foot,i < z_base``). A root frame
    below the feet makes every gait place the body under the ground (the body height printed
    negative) — usually a URDF whose root link is a foot-level frame, or legs posed upwards.
    """
    has_stand = "stand" in robot.poses
    q = robot.pose("stand") if has_stand else pin.neutral(robot.model)
    q[:7] = pin.neutral(robot.model)[:7]
    pose = "stand pose" if has_stand else "neutral configuration (no stand pose in the SRDF)"
    feet = robot.foot_positions(q)
    height = float(-feet[:, 2].mean())
    root = body_name(robot.model, 1).split(" (")[0]
    remedy = (f"pose the legs below the body in the SRDF's stand group_state, or move the URDF's "
              f"root frame ({root}) into the body above the feet")
    if not height > 0:
        return [Finding("body_height", f"base above the mean foot height in the {pose}", height,
                        "m", "> 0 m (the base origin above the feet)", remedy)]
    return [Finding("foot_above_base", f"foot {leg.foot_frame} of leg {leg.name} in the {pose}",
                    float(z), "m", "< 0 m (below the base origin)", remedy)
            for leg, z in zip(robot.legs, feet[:, 2], strict=True) if not z < 0]


STAND_LIMIT_TOL = 1e-9
"""rad (or m): a stand joint this far beyond its URDF limit is outside it (rounding allowed)."""


def stand_limit_findings(robot: Robot) -> list[Finding]:
    """Joints outside their URDF position limits in the stand pose (the neutral configuration
    when there is none): one finding that counts them and names the first few with their angle
    and range. The gait starts from the stand, so every motion then has the joint outside its
    limits (a knee at 0 whose range is [−2.7, −0.8] rad: a stand given by joint angles that left
    it out, or an SRDF state for another robot)."""
    model = robot.model
    q = robot.pose("stand") if "stand" in robot.poses else pin.neutral(model)
    pose = "stand pose" if "stand" in robot.poses else "neutral configuration (no stand pose)"
    out = []
    for name in robot.joint_names:
        iq = model.joints[model.getJointId(name)].idx_q
        lo, hi, x = model.lowerPositionLimit[iq], model.upperPositionLimit[iq], q[iq]
        beyond = max(lo - x, x - hi)
        if beyond > STAND_LIMIT_TOL:
            out.append((beyond, name, x, lo, hi))
    if not out:
        return []
    worst = max(out)
    named = ", ".join(f"{n} at {x:+.4g} rad (range [{lo:+.4g}, {hi:+.4g}])"
                      for _, n, x, lo, hi in out[:3])
    more = f" and {len(out) - 3} more" if len(out) > 3 else ""
    return [Finding("stand_joint_limits", f"{len(out)} joint(s) outside their URDF limits in "
                    f"the {pose}: {named}{more}", float(worst[0]), "rad",
                    "0 rad beyond (every joint within its <limit>)",
                    "give a stand within the limits: stand = {body_height = …} solves the legs "
                    "within them, or set the joints' angles in [robot] stand or the SRDF state")]


def limit_findings(robot: Robot) -> list[Finding]:
    """Actuated joints whose URDF limits are placeholders, not the robot's: a range over
    :data:`PLACEHOLDER_RANGE`, a speed over :data:`PLACEHOLDER_SPEED`, a torque over
    :data:`PLACEHOLDER_TORQUE` × m g L (L the longest leg's reach from its first joint to its
    foot in the stand pose). Joint limits bound the gait and build the generic actuator (its
    stall torque and no-load speed), so a placeholder silently changes the energy. One finding
    per kind of limit: the joints counted and the first few named, the largest value."""
    model = robot.model
    q = robot.pose("stand") if "stand" in robot.poses else pin.neutral(model)
    data = model.createData()
    pin.forwardKinematics(model, data, q)
    pin.updateFramePlacements(model, data)
    reach = max(float(np.linalg.norm(data.oMf[model.getFrameId(leg.foot_frame)].translation
                                     - data.oMi[model.getJointId(leg.joint_names[0])]
                                     .translation)) for leg in robot.legs)
    torque_cap = PLACEHOLDER_TORQUE * robot.mass * 9.81 * reach
    ids = [model.getJointId(name) for name in robot.joint_names]
    iq = [model.joints[j].idx_q for j in ids]
    iv = [model.joints[j].idx_v for j in ids]
    checks = (
        ("joint_range", model.upperPositionLimit[iq] - model.lowerPositionLimit[iq], "rad",
         PLACEHOLDER_RANGE, f"≤ {PLACEHOLDER_RANGE:.3g} rad (1.5 turns)"),
        ("joint_speed_limit", model.velocityLimit[iv], "rad/s", PLACEHOLDER_SPEED,
         f"≤ {PLACEHOLDER_SPEED:g} rad/s"),
        ("joint_torque_limit", model.effortLimit[iv], "N·m", torque_cap,
         f"≤ {PLACEHOLDER_TORQUE:g} × m g L = {torque_cap:.3g} N·m (L = {reach:.3g} m)"))
    found = []
    for check, values, unit, cap, allowed in checks:
        over = [(name, float(v)) for name, v in zip(robot.joint_names, values, strict=True)
                if v > cap]
        if not over:
            continue
        names = ", ".join(name for name, _ in over[:3])
        more = f" and {len(over) - 3} more" if len(over) > 3 else ""
        where = f"joint {names}" if len(over) == 1 else f"{len(over)} joints ({names}{more})"
        found.append(Finding(check, where, max(v for _, v in over), unit, allowed,
                             "a placeholder, not a limit: set the URDF <limit> of the joints to "
                             "the robot's (its drawing or the servo's datasheet)"))
    return found
